#include "common/csv.hpp"

#include "common/error.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <fstream>
#include <set>

namespace sartor {

namespace {

std::string trim(const std::string& text) {
  const auto first = text.find_first_not_of(" \t\r");
  if (first == std::string::npos) return "";
  const auto last = text.find_last_not_of(" \t\r");
  return text.substr(first, last - first + 1);
}

std::vector<std::string> split_fields(const std::string& line) {
  std::vector<std::string> fields;
  std::size_t start = 0;
  while (true) {
    const auto comma = line.find(',', start);
    fields.push_back(trim(line.substr(start, comma - start)));
    if (comma == std::string::npos) return fields;
    start = comma + 1;
  }
}

bool parse_number(const std::string& text, double& value) {
  const char* begin = text.data();
  const char* end = begin + text.size();
  if (end - begin > 1 && *begin == '+' && begin[1] != '-') ++begin;
  const auto result = std::from_chars(begin, end, value);
  return result.ec == std::errc() && result.ptr == end && std::isfinite(value);
}

} // namespace

std::optional<std::size_t> CsvTable::find(const std::vector<std::string>& accepted) const {
  for (const auto& name : accepted) {
    const auto it = std::find(names.begin(), names.end(), name);
    if (it != names.end()) return static_cast<std::size_t>(it - names.begin());
  }
  return std::nullopt;
}

std::size_t CsvTable::require(const std::vector<std::string>& accepted,
                              const std::string& meaning) const {
  if (const auto column = find(accepted)) return *column;
  std::string expected;
  for (const auto& name : accepted)
    expected += (expected.empty() ? "'" : " or '") + name + "'";
  std::string present;
  for (const auto& name : names)
    present += (present.empty() ? "" : ", ") + name;
  throw InputError(path, header_line,
                   "missing column " + expected + " (" + meaning + "); the header has: " + present);
}

CsvTable read_csv(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot open file");
  CsvTable table;
  table.path = path;
  std::string line;
  long number = 0;
  bool have_header = false;
  while (std::getline(in, line)) {
    ++number;
    const std::string content = trim(line);
    if (content.empty() || content[0] == '#') continue;
    std::vector<std::string> fields = split_fields(content);
    if (!have_header) {
      if (fields.size() == 1 && content.find_first_of(";\t") != std::string::npos) {
        throw InputError(path, number,
                         "columns must be separated by commas, got '" + content + "'");
      }
      std::set<std::string> seen;
      for (auto& name : fields) {
        // Instrument exports quote their headers: "Time (s)".
        if (name.size() >= 2 && name.front() == '"' && name.back() == '"') {
          name = trim(name.substr(1, name.size() - 2));
        }
        std::transform(name.begin(), name.end(), name.begin(),
                       [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
        if (name.empty()) throw InputError(path, number, "empty column name in the header");
        double ignored = 0.0;
        if (parse_number(name, ignored)) {
          throw InputError(path, number,
                           "the first line must name the columns (e.g. time_s,strain), got '" +
                               content + "'");
        }
        if (!seen.insert(name).second) {
          throw InputError(path, number, "column '" + name + "' appears twice in the header");
        }
      }
      table.names = fields;
      table.header_line = number;
      table.columns.assign(fields.size(), {});
      have_header = true;
      continue;
    }
    if (fields.size() != table.names.size()) {
      throw InputError(path, number,
                       "expected " + std::to_string(table.names.size()) + " values, found " +
                           std::to_string(fields.size()));
    }
    for (std::size_t c = 0; c < fields.size(); ++c) {
      double value = 0.0;
      if (!parse_number(fields[c], value)) {
        throw InputError(path, number,
                         "column '" + table.names[c] + "': '" + fields[c] +
                             "' is not a finite number within double range");
      }
      table.columns[c].push_back(value);
    }
    table.lines.push_back(number);
  }
  if (!have_header) throw InputError(path + ": the file is empty (expected a header line)");
  if (table.rows() == 0) throw InputError(path + ": the file has a header but no data rows");
  return table;
}

void require_nondecreasing(const CsvTable& table, std::size_t column) {
  const auto& values = table.columns[column];
  for (std::size_t row = 1; row < values.size(); ++row) {
    if (values[row] < values[row - 1]) {
      throw InputError(table.path, table.lines[row],
                       "'" + table.names[column] + "' decreases (" + format_number(values[row]) +
                           " after " + format_number(values[row - 1]) +
                           "); rows must be in time order");
    }
  }
}

std::string format_number(double value) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, result.ptr);
}

} // namespace sartor
