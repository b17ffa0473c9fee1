#pragma once
// Errors a user can act on. Every message says where (file:line when there is
// one) and what is wrong; drivers print it and exit non-zero.

#include <stdexcept>
#include <string>

namespace sartor {

class InputError : public std::runtime_error {
public:
  explicit InputError(const std::string& message) : std::runtime_error(message) {}
  // "FILE:LINE: message", the form compilers use so editors can jump to it.
  InputError(const std::string& file, long line, const std::string& message)
      : std::runtime_error(file + ":" + std::to_string(line) + ": " + message) {}
};

} // namespace sartor
