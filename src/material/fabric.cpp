#include "material/fabric.hpp"

#include "common/error.hpp"
#include "common/yaml_input.hpp"

#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <set>

namespace sartor {

const char* name_of(Direction direction) {
  return direction == Direction::warp ? "warp" : "weft";
}

Direction parse_direction(const std::string& text, const std::string& context) {
  if (text == "warp") return Direction::warp;
  if (text == "weft") return Direction::weft;
  throw InputError(context + ": unknown direction '" + text + "' (expected warp or weft)");
}

const DirectionalMaterial& Fabric::in(Direction direction) const {
  const auto& material = direction == Direction::warp ? warp : weft;
  if (!material) {
    throw InputError("fabric '" + name + "' (" + source + ") has no " + name_of(direction) +
                     " parameters");
  }
  return *material;
}

const std::vector<FabricPreset>& fabric_presets() {
  // {E (N/m), alpha, lambda_load (1/s), lambda_unload (1/s)}, thesis Table 5.1.
  static const std::vector<FabricPreset> presets = {
      {"cotton_twill", {32600, 0.897, 0.0886, 0.00200}, {14100, 0.873, 0.0275, 0.00243}},
      {"silk", {54000, 0.742, 0.0572, 0.00157}, {21600, 0.794, 0.311, 0.00190}},
      {"denim", {25600, 0.667, 0.0331, 0.0147}, {42700, 0.728, 0.0540, 0.00310}},
      {"nylon", {49600, 0.729, 0.0594, 0.00534}, {30800, 0.705, 0.0376, 0.0598}},
      {"polyester", {80400, 0.674, 0.00508, 0.00197}, {10700, 0.645, 0.0227, 0.00870}},
  };
  return presets;
}

namespace {

DirectionalMaterial preset_direction(const CreepParameters& creep, const std::string& context) {
  validate(creep, context);
  return {creep,
          TensionCurve::linear(preset_elastic_to_creep_modulus * creep.creep_modulus, context)};
}

std::string preset_names() {
  std::string names;
  for (const auto& preset : fabric_presets()) {
    names += names.empty() ? "" : ", ";
    names += preset.name;
  }
  return names;
}

// --- YAML fabric files -------------------------------------------------------

class FabricFileReader {
public:
  explicit FabricFileReader(std::string path) : path_(std::move(path)) {}

  Fabric read() {
    const YAML::Node root = load_yaml_input(path_, "fabric file");
    if (!root.IsMap()) fail(root, "a fabric file is a mapping with keys name, warp, weft");
    check_keys(root, {"name", "source", "warp", "weft"});
    Fabric fabric;
    fabric.name =
        root["name"] ? scalar(root["name"], "name") : std::filesystem::path(path_).stem().string();
    fabric.source = root["source"] ? scalar(root["source"], "source") : path_;
    if (root["warp"]) fabric.warp = direction(root["warp"], fabric.name + ":warp");
    if (root["weft"]) fabric.weft = direction(root["weft"], fabric.name + ":weft");
    if (!fabric.warp && !fabric.weft) fail(root, "needs a 'warp' or a 'weft' section");
    return fabric;
  }

private:
  [[noreturn]] void fail(const YAML::Node& node, const std::string& what) const {
    throw InputError(path_, node.Mark().line + 1, what);
  }

  void check_keys(const YAML::Node& map, const std::set<std::string>& allowed) const {
    for (const auto& entry : map) {
      const std::string key = entry.first.as<std::string>();
      if (allowed.count(key) == 0) {
        std::string list;
        for (const auto& k : allowed)
          list += (list.empty() ? "" : ", ") + k;
        fail(entry.first, "unknown key '" + key + "' (expected one of: " + list + ")");
      }
    }
  }

  std::string scalar(const YAML::Node& node, const std::string& key) const {
    if (!node.IsScalar()) fail(node, "'" + key + "' must be a single value");
    return node.as<std::string>();
  }

  double number(const YAML::Node& node, const std::string& key) const {
    const std::string text = scalar(node, key);
    try {
      std::size_t used = 0;
      const double value = std::stod(text, &used);
      if (used == text.size()) return value;
    } catch (const std::exception&) {
    }
    fail(node, "'" + key + "' must be a number, got '" + text + "'");
  }

  DirectionalMaterial direction(const YAML::Node& node, const std::string& context) const {
    if (!node.IsMap()) fail(node, context + " must be a mapping of parameters");
    check_keys(node,
               {"E", "alpha", "lambda_load", "lambda_unload", "elastic_modulus", "elastic_curve"});
    for (const char* key : {"E", "alpha", "lambda_load", "lambda_unload"}) {
      if (!node[key]) fail(node, context + ": missing '" + key + "'");
    }
    CreepParameters creep;
    creep.creep_modulus = number(node["E"], "E");
    creep.alpha = number(node["alpha"], "alpha");
    creep.lambda_load = number(node["lambda_load"], "lambda_load");
    creep.lambda_unload = number(node["lambda_unload"], "lambda_unload");
    const std::string where = path_ + ":" + std::to_string(node.Mark().line + 1) + ": " + context;
    validate(creep, where);
    if (node["elastic_modulus"] && node["elastic_curve"]) {
      fail(node, context + ": give elastic_modulus or elastic_curve, not both");
    }
    if (node["elastic_curve"]) return {creep, curve(node["elastic_curve"], where)};
    const double modulus = node["elastic_modulus"]
                               ? number(node["elastic_modulus"], "elastic_modulus")
                               : preset_elastic_to_creep_modulus * creep.creep_modulus;
    return {creep, TensionCurve::linear(modulus, where)};
  }

  TensionCurve curve(const YAML::Node& node, const std::string& where) const {
    if (!node.IsSequence()) fail(node, "elastic_curve must be a list of [strain, tension] pairs");
    std::vector<CurvePoint> points;
    for (const auto& pair : node) {
      if (!pair.IsSequence() || pair.size() != 2) {
        fail(pair, "elastic_curve entries must be [strain, tension (N/m)] pairs");
      }
      points.push_back({number(pair[0], "strain"), number(pair[1], "tension")});
    }
    return TensionCurve::piecewise(points, where);
  }

  std::string path_;
};

} // namespace

Fabric preset_fabric(const std::string& name) {
  for (const auto& preset : fabric_presets()) {
    if (name == preset.name) {
      Fabric fabric;
      fabric.name = preset.name;
      fabric.source = "thesis Table 5.1 (creep); elastic modulus assumed " +
                      std::to_string(static_cast<int>(preset_elastic_to_creep_modulus)) + "E";
      fabric.warp = preset_direction(preset.warp, fabric.name + ":warp");
      fabric.weft = preset_direction(preset.weft, fabric.name + ":weft");
      return fabric;
    }
  }
  throw InputError("unknown fabric '" + name + "' (presets: " + preset_names() +
                   "; or give a fabric file ending in .yaml)");
}

Fabric load_fabric_file(const std::string& path) {
  return FabricFileReader(path).read();
}

std::vector<MaterialChoice> resolve_fabrics(const std::string& spec) {
  std::vector<MaterialChoice> choices;
  const auto add_both = [&choices](const Fabric& fabric) {
    for (Direction d : {Direction::warp, Direction::weft}) {
      if (fabric.has(d)) choices.push_back({fabric, d});
    }
  };
  if (spec == "all") {
    for (const auto& preset : fabric_presets())
      add_both(preset_fabric(preset.name));
    return choices;
  }
  std::string name = spec;
  std::string direction;
  const auto colon = spec.rfind(':');
  if (colon != std::string::npos) {
    name = spec.substr(0, colon);
    direction = spec.substr(colon + 1);
  }
  const auto ends_with = [&name](const std::string& suffix) {
    return name.size() > suffix.size() &&
           name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0;
  };
  const bool is_file = ends_with(".yaml") || ends_with(".yml");
  const Fabric fabric = is_file ? load_fabric_file(name) : preset_fabric(name);
  if (direction.empty()) {
    add_both(fabric);
  } else {
    const Direction d = parse_direction(direction, "fabric '" + spec + "'");
    fabric.in(d);
    choices.push_back({fabric, d});
  }
  return choices;
}

} // namespace sartor
