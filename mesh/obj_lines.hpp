#pragma once
// The statement level of Wavefront OBJ files, shared by the cloth reader
// (mesh/obj.cpp) and the body reader (src/contact/body_obj.cpp).

#include <fstream>
#include <string>
#include <vector>

namespace sartor {

// The whitespace-separated words of a line.
std::vector<std::string> split_words(const std::string& line);

// Reads a file's logical lines: comments cut, trailing whitespace dropped,
// backslash continuations joined, each with the number of the physical line
// it starts on.
class ObjLineReader {
public:
  // Throws InputError when the file cannot be opened.
  explicit ObjLineReader(const std::string& path);
  // False at the end of the file.
  bool next(std::string& line, long& number);

private:
  std::ifstream in_;
  long physical_ = 0;
};

} // namespace sartor
