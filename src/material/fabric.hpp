#pragma once
// A fabric: creep law and immediate-elastic curve per direction (warp along
// the grain line, weft across it), from the Table 5.1 presets or a YAML file.

#include "material/creep_law.hpp"
#include "material/tension_curve.hpp"

#include <optional>
#include <string>
#include <vector>

namespace sartor {

enum class Direction { warp, weft };
const char* name_of(Direction direction);
Direction parse_direction(const std::string& text, const std::string& context);

struct DirectionalMaterial {
  CreepParameters creep;
  TensionCurve elastic;
};

struct Fabric {
  std::string name;
  std::string source; // where the numbers come from, for output metadata
  std::optional<DirectionalMaterial> warp;
  std::optional<DirectionalMaterial> weft; // a file may describe one direction only
  bool has(Direction direction) const {
    return direction == Direction::warp ? warp.has_value() : weft.has_value();
  }
  // Throws InputError when the fabric does not describe `direction`.
  const DirectionalMaterial& in(Direction direction) const;
};

// Table 5.1 of the thesis: fitted creep parameters of five fabrics.
struct FabricPreset {
  const char* name;
  CreepParameters warp;
  CreepParameters weft;
};
const std::vector<FabricPreset>& fabric_presets();

// Table 5.1 reports no immediate-elastic stiffness; presets assume a linear
// elastic modulus of this multiple of the creep modulus E (documented in
// docs/user-guide.md, overridable).
constexpr double preset_elastic_to_creep_modulus = 2.0;

Fabric preset_fabric(const std::string& name);
Fabric load_fabric_file(const std::string& path);

// One fabric direction picked by the user.
struct MaterialChoice {
  Fabric fabric;
  Direction direction;
  std::string label() const { return fabric.name + ":" + name_of(direction); }
  const DirectionalMaterial& material() const { return fabric.in(direction); }
};

// "cotton_twill:warp", "cotton_twill" (both directions), "all" (every preset,
// both directions), or a fabric file "my.yaml" / "my.yaml:weft".
std::vector<MaterialChoice> resolve_fabrics(const std::string& spec);

} // namespace sartor
