#pragma once
// Strict reader for numeric CSV tables: one header line of column names, then
// rows of numbers separated by commas. Blank lines and lines starting with '#'
// are ignored. Errors say FILE:LINE and what is wrong.

#include <optional>
#include <string>
#include <vector>

namespace sartor {

struct CsvTable {
  std::string path;
  std::vector<std::string> names;           // lower-case, trimmed, outer quotes removed
  std::vector<std::vector<double>> columns; // columns[c][row]
  std::vector<long> lines;                  // file line of each row (1-based)
  long header_line = 0;                     // file line of the header (1-based)

  std::size_t rows() const { return lines.size(); }
  std::optional<std::size_t> find(const std::vector<std::string>& accepted) const;
  // Like find(), but throws InputError listing the accepted names.
  std::size_t require(const std::vector<std::string>& accepted, const std::string& meaning) const;
};

CsvTable read_csv(const std::string& path);

// Throws InputError at the first row whose value in `column` is smaller than
// the one before it.
void require_nondecreasing(const CsvTable& table, std::size_t column);

// Shortest text that reads back as the same double.
std::string format_number(double value);

} // namespace sartor
