#include "common/yaml_input.hpp"

#include "common/error.hpp"

#include <map>

namespace sartor {

namespace {

// Every mapping in `node`, nested ones included, has each key once.
void reject_duplicate_keys(const YAML::Node& node, const std::string& path) {
  if (node.IsSequence()) {
    for (const auto& item : node)
      reject_duplicate_keys(item, path);
  }
  if (!node.IsMap()) return;
  std::map<std::string, int> first_line;
  for (const auto& entry : node) {
    const std::string key = entry.first.Scalar();
    const int line = entry.first.Mark().line + 1;
    const auto [where, fresh] = first_line.emplace(key, line);
    if (!fresh) {
      throw InputError(path, line,
                       "key '" + key + "' is given twice (first on line " +
                           std::to_string(where->second) + ")");
    }
    reject_duplicate_keys(entry.second, path);
  }
}

} // namespace

YAML::Node load_yaml_input(const std::string& path, const std::string& what) {
  YAML::Node root;
  try {
    root = YAML::LoadFile(path);
  } catch (const YAML::BadFile&) {
    throw InputError(path + ": cannot open " + what);
  } catch (const YAML::ParserException& e) {
    throw InputError(path, e.mark.line + 1, "YAML syntax error: " + e.msg);
  }
  reject_duplicate_keys(root, path);
  return root;
}

} // namespace sartor
