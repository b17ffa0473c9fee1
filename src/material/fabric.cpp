#include "material/fabric.hpp"

#include "common/error.hpp"
#include "common/yaml_input.hpp"

#include <nlohmann/json.hpp>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

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

void Fabric::check_creep() const {
  for (Direction d : {Direction::warp, Direction::weft}) {
    if (has(d) && !in(d).has_creep) {
      throw InputError("fabric '" + name + "' (" + source + ") has no creep parameters for " +
                       name_of(d) +
                       " (give E, alpha, lambda_load, lambda_unload in a fabric file)");
    }
  }
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

// --- Measured materials in ARCSim's JSON layout ------------------------------

class MeasuredFileReader {
public:
  explicit MeasuredFileReader(std::string path) : path_(std::move(path)) {}

  // The file's density and tables; `fabric` gets them and the curves
  // converted from them (docs/fabrics.md).
  void read_into(Fabric& fabric) const {
    const nlohmann::json root = parse();
    if (!root.is_object())
      fail("a measured material is a JSON object with density, stretching, bending");
    for (const auto& entry : root.items()) {
      if (entry.key() != "density" && entry.key() != "stretching" && entry.key() != "bending")
        fail("unknown key '" + entry.key() + "' (expected density, stretching, bending)");
    }
    if (!root.contains("density")) fail("missing 'density' (kg/m^2)");
    const double density = number(root.at("density"), "density");
    if (!(density > 0.0)) fail("'density' must be > 0 (kg/m^2)");
    const auto stretching = matrix<6, 4>(root, "stretching");
    const auto bending = matrix<3, 5>(root, "bending");
    StretchingTable stretch;
    stretch.rows = stretching;
    BendingTable bend;
    bend.rows = bending;
    fabric.areal_density = density;
    fabric.stretching = std::make_shared<const MeasuredStretching>(stretch);
    for (Direction d : {Direction::warp, Direction::weft}) {
      auto& direction = d == Direction::warp ? fabric.warp : fabric.weft;
      const std::string context = path_ + ": " + fabric.name + ":" + name_of(d);
      DirectionalMaterial converted{
          {}, table_tension_curve(stretch, d == Direction::weft, false, context), false, false};
      if (!direction) {
        direction = converted;
      } else if (!direction->elastic_given) {
        direction->elastic = converted.elastic;
      }
    }
    // Shear: W = k3 G01^2 / 2 at zero strain is G g^2 / 2 with g = 2 G01.
    fabric.shear_modulus = table_stiffness(stretch, 0.0, 0.0, 0.0)[3] / 4.0;
    fabric.bending = table_bending_curves(bend, fabric.warnings);
  }

private:
  [[noreturn]] void fail(const std::string& what) const {
    throw InputError(path_ + ": measured material: " + what);
  }

  nlohmann::json parse() const {
    std::ifstream in(path_);
    if (!in) throw InputError(path_ + ": cannot open the measured material file");
    try {
      return nlohmann::json::parse(in);
    } catch (const nlohmann::json::parse_error& e) {
      fail(std::string("not valid JSON: ") + e.what());
    }
  }

  double number(const nlohmann::json& value, const std::string& what) const {
    if (!value.is_number() || !std::isfinite(value.get<double>()))
      fail("'" + what + "' must be a finite number");
    return value.get<double>();
  }

  template <std::size_t Rows, std::size_t Columns>
  std::array<std::array<double, Columns>, Rows> matrix(const nlohmann::json& root,
                                                       const std::string& key) const {
    const auto shape = std::to_string(Rows) + " rows of " + std::to_string(Columns) + " numbers";
    if (!root.contains(key) || !root.at(key).is_array() || root.at(key).size() != Rows)
      fail("'" + key + "' must be " + shape);
    std::array<std::array<double, Columns>, Rows> values{};
    for (std::size_t r = 0; r < Rows; ++r) {
      const nlohmann::json& row = root.at(key)[r];
      if (!row.is_array() || row.size() != Columns) fail("'" + key + "' must be " + shape);
      for (std::size_t c = 0; c < Columns; ++c)
        values[r][c] =
            number(row[c], key + "[" + std::to_string(r) + "][" + std::to_string(c) + "]");
    }
    return values;
  }

  // Warp curvature bends along the warp: fold lines across it (90 degrees);
  // weft curvature: fold lines along the warp (0). Twist from the bias row by
  // cylindrical bending at 45 degrees, D_45 = (D_warp + D_weft)/4 + D_twist.
  // Where the bias row is below a quarter of the sum (the plate would need a
  // negative coupling, which one constant cannot follow along the curves),
  // the twist rigidity is held at 0 and `warnings` says where and by how much.
  FabricBending table_bending_curves(const BendingTable& table,
                                     std::vector<std::string>& warnings) const {
    constexpr double quarter = 0.78539816339744831;
    const std::string where = path_ + ": bending";
    FabricBending curves{table_moment_curve(table, 2.0 * quarter, where + " (warp, 90 degree row)"),
                         table_moment_curve(table, 0.0, where + " (weft, 0 degree row)"),
                         MomentCurve::linear(1.0, where)};
    std::vector<CurvePoint> twist;
    std::vector<double> held; // curvatures where the twist rigidity is held at 0
    double stiffer = 0.0;     // the largest relative excess of the bias rigidity
    for (const CurvePoint& p : curves.warp.points()) {
      if (p.strain == 0.0) continue;
      const double kappa = p.strain;
      const double bias = table_bending_rigidity(table, kappa, quarter);
      const double rigidity =
          bias - 0.25 * (curves.warp.moment(kappa) + curves.weft.moment(kappa)) / kappa;
      if (rigidity < 0.0) {
        held.push_back(kappa);
        stiffer = std::max(stiffer, -rigidity / bias);
      }
      twist.push_back({kappa, std::max(rigidity, 0.0) * kappa});
    }
    if (!held.empty()) {
      std::ostringstream text;
      text.precision(3);
      text << where << ": the 45 degree row is below a quarter of the warp's and weft's sum at "
           << held.size() << " of " << twist.size() << " curvatures (" << held.front() << " to "
           << held.back() << " 1/m): the twist rigidity is held at 0 there, so bias folds bend"
           << " up to " << 100.0 * stiffer << " % stiffer than the table";
      warnings.push_back(text.str());
    }
    curves.twist = MomentCurve::measured(twist, where + " (twist)");
    return curves;
  }

  std::string path_;
};

std::filesystem::path beside(const std::string& file, const std::string& relative) {
  const std::filesystem::path p(relative);
  return p.is_absolute() ? p : std::filesystem::path(file).parent_path() / p;
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
    check_keys(root, {"name", "source", "warp", "weft", "density", "shear_modulus", "bending",
                      "measured"});
    Fabric fabric;
    fabric.name =
        root["name"] ? scalar(root["name"], "name") : std::filesystem::path(path_).stem().string();
    fabric.source = root["source"] ? scalar(root["source"], "source") : path_;
    if (root["warp"]) fabric.warp = direction(root["warp"], fabric.name + ":warp");
    if (root["weft"]) fabric.weft = direction(root["weft"], fabric.name + ":weft");
    if (root["measured"]) {
      const std::string measured = beside(path_, scalar(root["measured"], "measured")).string();
      MeasuredFileReader(measured).read_into(fabric);
    }
    if (!fabric.warp && !fabric.weft) fail(root, "needs a 'warp', a 'weft' or a 'measured' entry");
    for (auto* d : {&fabric.warp, &fabric.weft}) {
      if (!*d || (*d)->elastic_given || fabric.stretching) continue;
      if (!(*d)->has_creep)
        fail(root, "a direction without creep parameters needs elastic_modulus, elastic_curve or "
                   "a 'measured' table");
      (*d)->elastic_given = true; // the presets' rule, elastic modulus 2E
    }
    if (root["density"]) {
      fabric.areal_density = positive(root["density"], "density (kg/m^2)");
      plausible(root["density"], "density", *fabric.areal_density, 0.005, 5.0, "kg/m^2",
                "fabrics weigh 0.02 to 1 kg/m^2: given in g/m^2?");
    }
    if (root["shear_modulus"]) {
      fabric.shear_modulus = positive(root["shear_modulus"], "shear_modulus (N/m)");
      plausible(root["shear_modulus"], "shear_modulus", *fabric.shear_modulus, 1.0, 1e7, "N/m",
                "given in kN/m or N/mm?");
    }
    if (root["bending"]) fabric.bending = bending(root["bending"], fabric);
    fabric.warnings = std::move(warnings_);
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

  // A warning (not an error) when `value` lies outside [low, high]: the
  // range spans what woven fabrics measure with two orders of margin.
  void plausible(const YAML::Node& node, const std::string& key, double value, double low,
                 double high, const char* unit, const char* hint) {
    if (value >= low && value <= high) return;
    std::ostringstream text;
    text << path_ << ":" << node.Mark().line + 1 << ": '" << key << "' = " << value << " " << unit
         << " is outside the plausible " << low << " to " << high << " " << unit << " (" << hint
         << ")";
    warnings_.push_back(text.str());
  }

  double positive(const YAML::Node& node, const std::string& key) const {
    const double value = number(node, key);
    if (!(value > 0.0) || !std::isfinite(value)) fail(node, "'" + key + "' must be > 0");
    return value;
  }

  // Creep parameters: all four or none (a fabric that does not creep).
  DirectionalMaterial direction(const YAML::Node& node, const std::string& context) {
    if (!node.IsMap()) fail(node, context + " must be a mapping of parameters");
    check_keys(node,
               {"E", "alpha", "lambda_load", "lambda_unload", "elastic_modulus", "elastic_curve"});
    bool any_creep = false;
    for (const char* key : {"E", "alpha", "lambda_load", "lambda_unload"})
      any_creep = any_creep || node[key];
    CreepParameters creep;
    const std::string where = path_ + ":" + std::to_string(node.Mark().line + 1) + ": " + context;
    if (any_creep) {
      for (const char* key : {"E", "alpha", "lambda_load", "lambda_unload"}) {
        if (!node[key]) fail(node, context + ": missing '" + key + "'");
      }
      creep.creep_modulus = number(node["E"], "E");
      creep.alpha = number(node["alpha"], "alpha");
      creep.lambda_load = number(node["lambda_load"], "lambda_load");
      creep.lambda_unload = number(node["lambda_unload"], "lambda_unload");
      validate(creep, where);
      // Table 5.1: E 1e4 to 1e5 N/m, rates 0.0016 to 0.31 1/s.
      plausible(node["E"], context + ": E", creep.creep_modulus, 100.0, 1e7, "N/m",
                "given in kN/m?");
      for (const char* key : {"lambda_load", "lambda_unload"}) {
        plausible(node[key], context + ": " + key, number(node[key], key), 1e-7, 10.0, "1/s",
                  "a time constant under 0.1 s: times in ms?");
      }
    }
    if (node["elastic_modulus"] && node["elastic_curve"]) {
      fail(node, context + ": give elastic_modulus or elastic_curve, not both");
    }
    if (node["elastic_curve"]) return {creep, curve(node["elastic_curve"], where), true, any_creep};
    if (node["elastic_modulus"]) {
      plausible(node["elastic_modulus"], context + ": elastic_modulus",
                number(node["elastic_modulus"], "elastic_modulus"), 100.0, 1e7, "N/m",
                "given in kN/m?");
      return {creep,
              TensionCurve::linear(number(node["elastic_modulus"], "elastic_modulus"), where), true,
              any_creep};
    }
    // Not given: the measured table's curve if the file has one (read after
    // the directions), else the presets' rule from E (placeholder without E).
    const double modulus = any_creep ? preset_elastic_to_creep_modulus * creep.creep_modulus : 1.0;
    return {creep, TensionCurve::linear(modulus, where), false, any_creep};
  }

  // bending: {warp: CURVE, weft: CURVE, twist: CURVE}, each a rigidity (N m)
  // or a list of [curvature (1/m), moment (N)] pairs; twist defaults to half
  // the mean of warp and weft's initial rigidities. Replaces the measured one.
  FabricBending bending(const YAML::Node& node, const Fabric& fabric) const {
    if (!node.IsMap()) fail(node, "'bending' must be a mapping with warp, weft, twist");
    check_keys(node, {"warp", "weft", "twist"});
    for (const char* key : {"warp", "weft"})
      if (!node[key]) fail(node, fabric.name + ": bending: missing '" + key + "'");
    const auto one = [&](const YAML::Node& entry, const std::string& key) {
      const std::string where = path_ + ":" + std::to_string(entry.Mark().line + 1) + ": " +
                                fabric.name + ": bending " + key;
      if (entry.IsScalar()) return MomentCurve::linear(number(entry, key), where);
      if (!entry.IsSequence())
        fail(entry, "bending " + key + ": a rigidity (N m) or [curvature, moment] pairs");
      std::vector<CurvePoint> points;
      for (const auto& pair : entry) {
        if (!pair.IsSequence() || pair.size() != 2)
          fail(pair, "bending " + key + " entries must be [curvature (1/m), moment (N)] pairs");
        points.push_back({number(pair[0], "curvature"), number(pair[1], "moment")});
      }
      return MomentCurve::piecewise(points, where);
    };
    FabricBending curves{one(node["warp"], "warp"), one(node["weft"], "weft"),
                         MomentCurve::linear(1.0, path_)};
    curves.twist = node["twist"] ? one(node["twist"], "twist")
                                 : MomentCurve::linear(0.25 * (curves.warp.initial_rigidity() +
                                                               curves.weft.initial_rigidity()),
                                                       path_ + ": bending twist");
    return curves;
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
  std::vector<std::string> warnings_;
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

Fabric load_measured_fabric(const std::string& path) {
  Fabric fabric;
  fabric.name = std::filesystem::path(path).stem().string();
  fabric.source = path + " (measured, Wang et al. 2011 layout)";
  MeasuredFileReader(path).read_into(fabric);
  return fabric;
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
  const Fabric fabric = ends_with(".json") ? load_measured_fabric(name)
                        : is_file          ? load_fabric_file(name)
                                           : preset_fabric(name);
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
