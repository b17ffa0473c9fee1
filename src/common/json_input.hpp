#pragma once
// Reading JSON inputs (patterns, seams) with one set of rules: a syntax error,
// a number that overflows a double and a key given twice in one object are
// errors naming the file (and the line where the parser knows it).

#include <nlohmann/json.hpp>

#include <string>

namespace sartor {

// Parses `text` read from `source`; throws InputError.
nlohmann::json parse_json_input(const std::string& text, const std::string& source);

} // namespace sartor
