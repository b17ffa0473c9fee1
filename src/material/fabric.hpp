#pragma once
// A fabric: creep law and immediate-elastic curve per direction (warp along
// the grain line, weft across it), areal density, bending curves and a
// measured stretching table, from the Table 5.1 presets, a YAML fabric file
// or a measured material in ARCSim's JSON layout (docs/fabrics.md).

#include "material/creep_law.hpp"
#include "material/measured_cloth.hpp"
#include "material/tension_curve.hpp"

#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace sartor {

enum class Direction { warp, weft };
const char* name_of(Direction direction);
Direction parse_direction(const std::string& text, const std::string& context);

struct DirectionalMaterial {
  CreepParameters creep; // meaningless unless has_creep
  TensionCurve elastic;
  // false: `elastic` was converted from the fabric's stretching table (as a
  // function of the Baraff-Witkin strain), not given.
  bool elastic_given = true;
  // false: a measured material without creep parameters; what creeps calls
  // Fabric::check_creep first.
  bool has_creep = true;
};

// Moment-curvature curves of the patch bending model: curvature of the warp
// (kappa_uu), of the weft (kappa_vv) and twist (2 kappa_uv).
struct FabricBending {
  MomentCurve warp;
  MomentCurve weft;
  MomentCurve twist;
};

struct Fabric {
  std::string name;
  std::string source; // where the numbers come from, for output metadata
  std::optional<DirectionalMaterial> warp;
  std::optional<DirectionalMaterial> weft; // a file may describe one direction only
  std::optional<double> areal_density;     // kg/m^2
  std::optional<double> shear_modulus;     // N/m
  std::optional<FabricBending> bending;
  std::shared_ptr<const MeasuredStretching> stretching; // measured table, or none
  // Values that read as a unit mistake ("FILE:LINE: ..."): a creep modulus
  // of 32.6 N/m (kN/m?), rates of 1000/s (times in ms?), 200 kg/m^2 (g/m^2?).
  // They are kept, not refused: the caller prints them (docs/fabrics.md).
  std::vector<std::string> warnings;
  bool has(Direction direction) const {
    return direction == Direction::warp ? warp.has_value() : weft.has_value();
  }
  // Throws InputError when the fabric does not describe `direction`.
  const DirectionalMaterial& in(Direction direction) const;
  // Throws InputError unless both directions carry creep parameters.
  void check_creep() const;
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
// A measured material in ARCSim's JSON layout: {"density": kg/m^2,
// "stretching": 6 rows of 4 (N/m), "bending": 3 rows of 5 (N m)}.
Fabric load_measured_fabric(const std::string& path);

// One fabric direction picked by the user.
struct MaterialChoice {
  Fabric fabric;
  Direction direction;
  std::string label() const { return fabric.name + ":" + name_of(direction); }
  const DirectionalMaterial& material() const { return fabric.in(direction); }
};

// "cotton_twill:warp", "cotton_twill" (both directions), "all" (every preset,
// both directions), a fabric file "my.yaml" / "my.yaml:weft", or a measured
// material "my.json".
std::vector<MaterialChoice> resolve_fabrics(const std::string& spec);

} // namespace sartor
