#pragma once
// Reading YAML inputs (fabric files, case files) with one set of rules: a
// syntax error and a key given twice in one mapping are errors naming the
// file and line.

#include <yaml-cpp/yaml.h>

#include <string>

namespace sartor {

// The document in `path`; throws InputError ("FILE:LINE: ...") when it cannot
// be opened (`what` names the kind of file), is not YAML, or repeats a key.
YAML::Node load_yaml_input(const std::string& path, const std::string& what);

} // namespace sartor
