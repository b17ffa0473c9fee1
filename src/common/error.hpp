#pragma once
// Errors a user can act on. Every message says where (file:line when there is
// one) and what is wrong; drivers print it and exit with a status that tells
// the two kinds apart (docs/cli.md):
//   2  InputError: the input (a file, an option, the command line) is wrong;
//      nothing was computed from it.
//   1  SolveFailure: the input was accepted but the computation did not reach
//      what it was asked for (no equilibrium, no certified optimum); what was
//      computed is written and the message says where.

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

class SolveFailure : public std::runtime_error {
public:
  explicit SolveFailure(const std::string& message) : std::runtime_error(message) {}
};

} // namespace sartor
