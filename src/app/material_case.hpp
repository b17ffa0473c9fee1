#pragma once
// The material of a cloth case (docs/fabrics.md): the options that choose a
// fabric and override what it holds (moduli, Poisson coupling, membrane and
// bending models, rigidities, density, Hessian projections), read once into
// a typed MaterialCase, and the ClothMaterial each fabric of the cloth
// becomes.

#include "app/cli.hpp"
#include "element/bending.hpp"
#include "element/membrane.hpp"
#include "fem/cloth_model.hpp"

#include <string>
#include <vector>

namespace sartor {

// The material options, declared by this module.
const std::vector<OptionSpec>& material_option_specs();

// An option's value (its default when not given) and whether it was given:
// what a fabric holds yields only to a value given explicitly.
template <class T>
struct GivenOr {
  T value{};
  bool given = false;
};

struct MaterialCase {
  std::string fabric;                       // --fabric: preset, FILE.yaml or measured FILE.json
  GivenOr<double> warp_modulus;             // --warp-modulus, N/m: a linear curve
  GivenOr<double> weft_modulus;             // --weft-modulus, N/m
  GivenOr<double> poisson;                  // --poisson; else a measured table's own
  GivenOr<double> shear_modulus;            // --shear-modulus, N/m; else the fabric's
  GivenOr<element::MembraneModel> membrane; // --membrane-model; else measured for a table
  GivenOr<element::BendingModel> bending;   // --bending-model; else discrete_shell on creases
  GivenOr<double> bending_stiffness;        // --bending-stiffness, N m; else the fabric's curves
  GivenOr<double> bending_weft;             // --bending-weft, N m (patch model)
  GivenOr<double> bending_twist;            // --bending-twist, N m (patch model)
  GivenOr<double> density;                  // --density, kg/m^2; else the fabric's
  bool project_membrane = false;            // --membrane-psd
  bool project_bending = false;             // --bending-psd
  bool patch_gauss_newton = false;          // --bending-psd-method gauss-newton
};

// Throws InputError naming the option for a malformed value.
MaterialCase read_material_case(const Options& options);

// The material of `fabric_spec` (a preset, FILE.yaml or a measured
// FILE.json) with the case's overrides. A mesh with creases takes the
// discrete shell unless a bending model is given. Throws InputError for a
// fabric that cannot be read or a rigidity the bending model lacks.
ClothMaterial build_material(const MaterialCase& material, const std::string& fabric_spec,
                             bool mesh_has_creases);

// The materials of a cloth, one per fabric of `fabrics` (in the order of the
// mesh's material ids), warning once when creases choose the bending model.
std::vector<ClothMaterial> case_materials(const MaterialCase& material,
                                          const std::vector<std::string>& fabrics,
                                          std::size_t crease_edges);

// The fabric whose larger initial modulus is the largest (seams take their
// automatic stiffness from it).
const ClothMaterial& stiffest_material(const std::vector<ClothMaterial>& materials);

} // namespace sartor
