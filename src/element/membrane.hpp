#pragma once
// Constant-strain membrane triangles, orthotropic in warp (u) and weft (v).
//
// Kinematics (thesis eq. 5.11, DESIGN.md): F = [w_u w_v] = [dx1 dx2][du dv]^-1
// (3x2). The creep state enters through the unloaded lengths: the elastic
// part is F_e = F diag(1 + n_warp, 1 + n_weft)^-1, and energies are per unit
// unloaded area A_ul = A (1 + n_warp)(1 + n_weft), A the material area.
//
// Two strain measures behind one interface:
//  * baraff_witkin: e_u = |F_e e1| - 1, e_v = |F_e e2| - 1, shear
//    g = (F_e e1).(F_e e2);  W = W_warp(e_u) + W_weft(e_v) + G g^2 / 2.
//  * saint_venant_kirchhoff: Green strain E = (F_e^T F_e - I)/2;
//    W = W_warp(E11) + W_weft(E22) + c12 E11 E22 + 2 G E12^2,
//    c12 = poisson * sqrt(k_warp k_weft) with the curves' initial moduli.
// W_warp, W_weft are the energies of the piecewise-linear tension-strain
// curves (TensionCurve::energy_density), so tension is force per unit width
// (N/m). Energy = A_ul W. Compression stabilisation (Sensitive Couture §5) is
// the PSD projection of the Hessian, chosen by the caller.
//
//  * measured: the measured table of Wang et al. 2011 (material/measured_cloth.hpp)
//    in Green strain, W(E11, E22, E12) = MeasuredStretching::energy; the
//    curves, shear modulus and poisson are not used.
// Both of the first two models share the shear term: 2 G E12^2 = G g^2 / 2 with g = 2 E12.
// In the Baraff-Witkin model a column of F_e shorter than 1e-12 (a triangle
// collapsed along u or v) has no direction: its stretch then contributes its
// energy but no gradient and no Hessian, so the results stay finite.

#include "common/registry_index.hpp"
#include "element/element.hpp"
#include "material/measured_cloth.hpp"
#include "material/tension_curve.hpp"

#include <Eigen/Core>

#include <array>
#include <memory>
#include <string>
#include <vector>

namespace sartor::element {

using Vector9 = Eigen::Matrix<double, 9, 1>;

// Rest data of a triangle from its material coordinates (counter-clockwise or
// not: the area is taken positive). Throws InputError when degenerate.
struct TriangleRest {
  Eigen::Matrix2d inverse_material; // [u1-u0 u2-u0; v1-v0 v2-v0]^-1, 1/m
  double area = 0.0;                // material area, m^2
};
TriangleRest triangle_rest(const std::array<Eigen::Vector2d, 3>& uv);

// A membrane model: its place in the registry of membrane models
// (element/membrane_models.hpp), where each is one file of kernels and one
// registration line. The built-in ones by name: Baraff-Witkin (tensions of
// the stretches |F e_i| - 1), Saint Venant-Kirchhoff (of the Green strains,
// warp-weft coupling by the Poisson ratio) and measured (a fabric's
// stretching table, Wang et al. 2011).
class MembraneModel : public RegistryIndex<MembraneModel> {
public:
  using RegistryIndex::RegistryIndex;
  static const MembraneModel baraff_witkin;
  static const MembraneModel saint_venant_kirchhoff;
  static const MembraneModel measured;
};
// In the registry's order (register_membrane_models).
inline constexpr MembraneModel MembraneModel::baraff_witkin{0};
inline constexpr MembraneModel MembraneModel::saint_venant_kirchhoff{1};
inline constexpr MembraneModel MembraneModel::measured{2};

// The model of that name (as --membrane-model and case files name it);
// throws InputError naming `context` and the registered names.
MembraneModel membrane_model_named(const std::string& name, const std::string& context);
// Its name, and every registered name in registration order.
const std::string& membrane_model_name(MembraneModel model);
std::vector<std::string> membrane_model_names();

struct MembraneMaterial {
  TensionCurve warp;
  TensionCurve weft;
  double shear_modulus = 0.0; // G, N/m
  double poisson = 0.0;       // warp-weft coupling of the StVK model, dimensionless
  std::shared_ptr<const MeasuredStretching> stretching = nullptr; // the measured model's table
};

// The creep state of the element: non-elastic strain per direction, each
// > -1 (the unloaded length 1 + n times the material length).
struct NonelasticStrain {
  double warp = 0.0;
  double weft = 0.0;
};

Result<9> membrane(MembraneModel model, const MembraneMaterial& material, const TriangleRest& rest,
                   const NonelasticStrain& nonelastic, const Vector9& x, Want want);

// Elastic strains and tensions of the element, for output and for the creep
// law: tension_warp = dW/de_u (BW) or S11 |F_e e1| (StVK), N/m per unit
// unloaded width (S11 |F_e e1| with S11 = dW/dE11 for the measured model).
// The strains are each model's own measure, the argument of its
// tension-strain curves: e_u, e_v (BW) or E11, E22 (StVK, measured); shear is
// g = (F_e e1).(F_e e2) = 2 E12 in both (the engineering shear strain for
// small strains).
struct MembraneStrain {
  double warp = 0.0;         // e_u or E11
  double weft = 0.0;         // e_v or E22
  double shear = 0.0;        // g = 2 E12
  double tension_warp = 0.0; // N/m
  double tension_weft = 0.0; // N/m
};
MembraneStrain membrane_strain(MembraneModel model, const MembraneMaterial& material,
                               const TriangleRest& rest, const NonelasticStrain& nonelastic,
                               const Vector9& x);

// How the element answers a change of its own unloaded lengths, for the
// monolithic creep coupling, whose non-elastic strains n = (n_warp, n_weft)
// depend on the tensions: the tensions of membrane_strain and their
// derivatives with respect to the positions and to n, and the derivative of
// the element's force (the energy gradient of membrane()) with respect to n.
struct MembraneCreepSensitivity {
  Eigen::Vector2d tension = Eigen::Vector2d::Zero(); // (warp, weft), N/m
  Eigen::Matrix<double, 2, 9> tension_per_position = Eigen::Matrix<double, 2, 9>::Zero();
  Eigen::Matrix2d tension_per_nonelastic = Eigen::Matrix2d::Zero();
  Eigen::Matrix<double, 9, 2> force_per_nonelastic = Eigen::Matrix<double, 9, 2>::Zero();
};
MembraneCreepSensitivity membrane_creep_sensitivity(MembraneModel model,
                                                    const MembraneMaterial& material,
                                                    const TriangleRest& rest,
                                                    const NonelasticStrain& nonelastic,
                                                    const Vector9& x);

// The design sensitivity's mixed derivative (docs/sensitivity.md): the change
// of the element's force (the energy gradient of membrane()) when its
// material coordinates `uv` move by `delta_uv`, at fixed positions and
// non-elastic strains, d/de grad E(x; uv + e delta_uv) at e = 0. Exact: the
// columns of F_e, the area and the density's derivatives by the chain rule
// (d M^-1 = -M^-1 dM M^-1, dA = A tr(M^-1 dM)).
Vector9 membrane_rest_derivative(MembraneModel model, const MembraneMaterial& material,
                                 const std::array<Eigen::Vector2d, 3>& uv,
                                 const NonelasticStrain& nonelastic, const Vector9& x,
                                 const std::array<Eigen::Vector2d, 3>& delta_uv);

// The change of the element's tensions (membrane_strain's tension_warp and
// tension_weft) when its material coordinates move by `delta_uv`, at fixed
// positions and non-elastic strains: the monolithic creep coupling's
// strains follow the tensions (CreepCouplingForm::rest_derivative).
Eigen::Vector2d membrane_tension_rest_derivative(MembraneModel model,
                                                 const MembraneMaterial& material,
                                                 const std::array<Eigen::Vector2d, 3>& uv,
                                                 const NonelasticStrain& nonelastic,
                                                 const Vector9& x,
                                                 const std::array<Eigen::Vector2d, 3>& delta_uv);

// The change of a triangle's material area when its corners move by
// `delta_uv` (the lumped masses' and so gravity's dependence on the
// pattern), m^2.
double triangle_area_derivative(const std::array<Eigen::Vector2d, 3>& uv,
                                const std::array<Eigen::Vector2d, 3>& delta_uv);

} // namespace sartor::element
