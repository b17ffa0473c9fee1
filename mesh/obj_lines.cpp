#include "mesh/obj_lines.hpp"

#include "common/error.hpp"

#include <cctype>

namespace sartor {

std::vector<std::string> split_words(const std::string& line) {
  std::vector<std::string> words;
  std::size_t start = 0;
  while ((start = line.find_first_not_of(" \t\r\f\v", start)) != std::string::npos) {
    const std::size_t end = line.find_first_of(" \t\r\f\v", start);
    words.push_back(line.substr(start, end == std::string::npos ? end : end - start));
    start = end;
  }
  return words;
}

ObjLineReader::ObjLineReader(const std::string& path) : in_(path) {
  if (!in_) throw InputError(path + ": cannot open file");
}

bool ObjLineReader::next(std::string& line, long& number) {
  line.clear();
  std::string physical;
  bool started = false;
  while (std::getline(in_, physical)) {
    ++physical_;
    if (!started) number = physical_;
    started = true;
    if (const auto comment = physical.find('#'); comment != std::string::npos)
      physical.erase(comment);
    while (!physical.empty() && std::isspace(static_cast<unsigned char>(physical.back())))
      physical.pop_back();
    if (!physical.empty() && physical.back() == '\\') {
      physical.back() = ' ';
      line += physical;
      continue;
    }
    line += physical;
    return true;
  }
  return started;
}

} // namespace sartor
