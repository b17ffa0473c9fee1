#include "common/checksum.hpp"

#include "common/error.hpp"

#include <cstdio>
#include <fstream>
#include <iterator>

namespace sartor {

std::string file_checksum(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) throw InputError(path + ": cannot open file");
  const std::string bytes((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
  if (file.bad()) throw InputError(path + ": cannot read file");
  Checksum sum;
  sum.add(bytes.data(), bytes.size());
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(sum.value()));
  return text;
}

} // namespace sartor
