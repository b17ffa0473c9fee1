#include "app/material_case.hpp"

#include "app/commands.hpp"
#include "common/error.hpp"
#include "fem/bending_models.hpp"
#include "material/fabric.hpp"
#include "material/measured_cloth.hpp"

#include <algorithm>
#include <cmath>
#include <memory>

namespace sartor {

namespace {

std::string alternatives(const std::vector<std::string>& names) {
  std::string text;
  for (std::size_t i = 0; i < names.size(); ++i)
    text += (i == 0 ? "" : i + 1 == names.size() ? " or " : ", ") + names[i];
  return text;
}

// The registered bending models (fem/bending_models.hpp), each with its summary.
std::string bending_model_help() {
  std::vector<std::string> described;
  const std::size_t models = fem::bending_model_names().size();
  for (std::size_t i = 0; i < models; ++i) {
    const auto& entry = fem::bending_model_entry(element::BendingModel(int(i)));
    described.push_back(entry.name + " (" + entry.summary + ")");
  }
  return alternatives(described);
}

// An option without a default is read only when given.
template <class Read>
auto given_or(const Options& options, const std::string& name, Read read) {
  using Value = decltype(read(name));
  const bool given = options.is_set(name);
  if (!given && options.text(name).empty()) return GivenOr<Value>{};
  return GivenOr<Value>{read(name), given};
}

// Bending from the case, or the fabric's curves when it has them and no
// rigidity is given (the hinge models take their initial rigidity).
void set_bending(const MaterialCase& given, const Fabric& fabric, ClothMaterial& material) {
  const bool rigidity_given =
      given.bending_stiffness.given || given.bending_weft.given || given.bending_twist.given;
  if (fabric.bending && !rigidity_given) {
    material.bending_curves = std::make_shared<const FabricBending>(*fabric.bending);
    material.bending_stiffness =
        0.5 * (fabric.bending->warp.initial_rigidity() + fabric.bending->weft.initial_rigidity());
    return;
  }
  material.bending_stiffness = given.bending_stiffness.value;
  if (given.bending_weft.given || given.bending_twist.given) {
    if (material.bending_model != element::BendingModel::patch) {
      throw InputError("options --bending-weft and --bending-twist need --bending-model patch");
    }
    auto rigidity = element::BendingRigidity::isotropic(material.bending_stiffness);
    if (given.bending_weft.given) rigidity.weft = given.bending_weft.value;
    if (given.bending_twist.given) rigidity.twist = given.bending_twist.value;
    material.bending_rigidity = rigidity;
  }
}

// The warp or weft tension curve: a given linear modulus, else the fabric's.
TensionCurve tension_curve(const GivenOr<double>& modulus, const char* option, const Fabric& fabric,
                           Direction direction, element::MembraneModel model) {
  if (modulus.given) return TensionCurve::linear(modulus.value, std::string("--") + option);
  const DirectionalMaterial& m = fabric.in(direction);
  // Table curves are stored in the Baraff-Witkin measure; stvk reads Green strain.
  if (!m.elastic_given && model == element::MembraneModel::saint_venant_kirchhoff) {
    return table_tension_curve(fabric.stretching->table(), direction == Direction::weft, true,
                               fabric.source);
  }
  return m.elastic;
}

// Poisson coupling and shear modulus: given, else a measured table's c12 =
// k1 at zero strain and the fabric's shear modulus (0.1 sqrt(k_warp k_weft)
// when it has none).
void set_coupling(const MaterialCase& given, const Fabric& fabric,
                  element::MembraneMaterial& membrane) {
  const double geometric_modulus =
      std::sqrt(membrane.warp.initial_modulus() * membrane.weft.initial_modulus());
  if (fabric.stretching && !given.poisson.given) {
    membrane.poisson =
        table_stiffness(fabric.stretching->table(), 0.0, 0.0, 0.0)[1] / geometric_modulus;
  }
  const double automatic_shear =
      fabric.shear_modulus ? *fabric.shear_modulus : 0.1 * geometric_modulus;
  membrane.shear_modulus = given.shear_modulus.given ? given.shear_modulus.value : automatic_shear;
}

} // namespace

// The cloth's material: fabric, membrane and bending models (as registered:
// element/membrane_models.hpp, fem/bending_models.hpp).
const std::vector<OptionSpec>& material_option_specs() {
  static const std::vector<OptionSpec> specs = with_module_prefix(
      {
          {"fabric", "SPEC", "cotton_twill",
           "preset, FILE.yaml or measured FILE.json: membrane, bending, density (docs/fabrics.md)"},
          {"warp-modulus", "N/M", "", "linear warp modulus, N/m (replaces the fabric's curve)"},
          {"weft-modulus", "N/M", "", "linear weft modulus, N/m (replaces the fabric's curve)"},
          {"shear-modulus", "N/M", "",
           "in-plane shear modulus, N/m [the fabric's, else 0.1 sqrt(k_warp k_weft)]"},
          {"poisson", "NU", "0", "warp-weft Poisson coupling (stvk model)"},
          {"membrane-model", "M", "baraff_witkin",
           alternatives(element::membrane_model_names()) +
               " [measured (a Wang et al. table) for a fabric with one]"},
          {"membrane-psd", "", "",
           "project membrane (and contact) Hessians to PSD (compression stabilisation)"},
          {"bending-model", "M", "patch",
           bending_model_help() + " [discrete_shell for a mesh with creases]"},
          {"bending-stiffness", "N*M", "1e-6",
           "bending stiffness (warp, patch), N m (0: no bending) [the fabric's curves if any]"},
          {"bending-weft", "N*M", "", "patch model: weft rigidity, N m [--bending-stiffness]"},
          {"bending-twist", "N*M", "", "patch model: twist rigidity, N m [half the warp's]"},
          {"bending-psd", "", "", "project bending Hessians to PSD"},
          {"bending-psd-method", "eigenvalues|gauss-newton", "eigenvalues",
           "patch model under --bending-psd: the exact Hessian with its negative eigenvalues "
           "clamped, or the Gauss-Newton one (faster, less robust to round-off)"},
          {"density", "KG/M2", "0.2", "areal density, kg/m^2 [the fabric's if it has one]"},
      },
      {"material"});
  return specs;
}

MaterialCase read_material_case(const Options& options) {
  const auto positive = [&](const std::string& name) { return options.positive_real(name); };
  const auto nonnegative = [&](const std::string& name) { return options.nonnegative_real(name); };
  MaterialCase material;
  material.fabric = options.text("fabric");
  material.membrane = given_or(options, "membrane-model", [&](const std::string& name) {
    return element::membrane_model_named(options.text(name), "option --" + name);
  });
  material.warp_modulus = given_or(options, "warp-modulus", positive);
  material.weft_modulus = given_or(options, "weft-modulus", positive);
  material.poisson =
      given_or(options, "poisson", [&](const std::string& name) { return options.real(name); });
  material.shear_modulus = given_or(options, "shear-modulus", nonnegative);
  material.bending = given_or(options, "bending-model", [&](const std::string& name) {
    return fem::bending_model_named(options.text(name), "option --" + name);
  });
  material.bending_stiffness = given_or(options, "bending-stiffness", nonnegative);
  material.bending_weft = given_or(options, "bending-weft", nonnegative);
  material.bending_twist = given_or(options, "bending-twist", nonnegative);
  material.density = given_or(options, "density", nonnegative);
  material.project_membrane = options.flag("membrane-psd");
  material.project_bending = options.flag("bending-psd");
  const std::string method = options.text("bending-psd-method");
  if (method != "gauss-newton" && method != "eigenvalues") {
    throw InputError("option --bending-psd-method: '" + method +
                     "' is neither gauss-newton nor eigenvalues");
  }
  material.patch_gauss_newton = method == "gauss-newton";
  return material;
}

ClothMaterial build_material(const MaterialCase& given, const std::string& fabric_spec,
                             bool mesh_has_creases) {
  const auto choices = resolve_fabrics(fabric_spec);
  const Fabric& fabric = choices.front().fabric;
  print_warnings(fabric.warnings);
  const element::MembraneModel model = !given.membrane.given && fabric.stretching
                                           ? element::MembraneModel::measured
                                           : given.membrane.value;
  ClothMaterial material(
      {tension_curve(given.warp_modulus, "warp-modulus", fabric, Direction::warp, model),
       tension_curve(given.weft_modulus, "weft-modulus", fabric, Direction::weft, model), 0.0,
       given.poisson.value});
  material.membrane_model = model;
  material.membrane.stretching = fabric.stretching;
  set_coupling(given, fabric, material.membrane);
  material.bending_model = mesh_has_creases && !given.bending.given
                               ? element::BendingModel::discrete_shell
                               : given.bending.value;
  set_bending(given, fabric, material);
  material.areal_density =
      !given.density.given && fabric.areal_density ? *fabric.areal_density : given.density.value;
  material.project_membrane = given.project_membrane;
  material.project_bending = given.project_bending;
  material.patch_gauss_newton = given.patch_gauss_newton;
  return material;
}

std::vector<ClothMaterial> case_materials(const MaterialCase& material,
                                          const std::vector<std::string>& fabrics,
                                          std::size_t crease_edges) {
  std::vector<ClothMaterial> materials;
  for (const std::string& fabric : fabrics)
    materials.push_back(build_material(material, fabric, crease_edges > 0));
  if (crease_edges > 0 && !material.bending.given) {
    print_warnings({"the mesh has " + std::to_string(crease_edges) +
                    " crease edges: bending by the discrete shell, the model with rest angles "
                    "on edges (--bending-model discrete_shell; docs/pleats.md)"});
  }
  return materials;
}

const ClothMaterial& stiffest_material(const std::vector<ClothMaterial>& materials) {
  return *std::max_element(
      materials.begin(), materials.end(), [](const ClothMaterial& a, const ClothMaterial& b) {
        const auto stiffness = [](const ClothMaterial& m) {
          return std::max(m.membrane.warp.initial_modulus(), m.membrane.weft.initial_modulus());
        };
        return stiffness(a) < stiffness(b);
      });
}

} // namespace sartor
