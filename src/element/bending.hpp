#pragma once
// Bending across an interior edge (a hinge) shared by triangles (x0, x1, x2)
// and (x1, x0, x3): the edge is x0-x1, x2 and x3 are the opposite vertices.
// Both triangles listed counter-clockwise seen from the same side, so that
// their normals n1 = (x1 - x0) x (x2 - x0) and n2 = (x3 - x0) x (x1 - x0)
// agree when the hinge is flat.
//
//  * discrete_shell (Grinspun et al. 2003): E = k_b w (theta - theta_rest)^2 / 2,
//    theta the dihedral angle (0 when flat, signed), w a rest weight
//    3|e|^2/(A1 + A2) scaled so that a fine regular mesh bent into a cylinder
//    of radius R stores k_b A / (2 R^2).
//  * quadratic (Bergou et al. 2006): E = x^T Q x / 2 with a constant 12x12 Q
//    from the rest cotangent weights, for flat rest shapes; the same
//    normalisation.
// k_b is the bending stiffness in N m (J). Rest lengths and areas come from
// the material coordinates, so flat panels have theta_rest = 0.
//
// Sign: theta = atan2((n1 x n2).e/|e|, n1.n2), in (-pi, pi]; theta > 0 when
// the hinge folds away from the normals' side (a ridge seen from there).
//
// Normalisation: w = |e|^2 / (A1 + A2), a third of Grinspun's weight. With it
// a mesh of equilateral triangles bent isometrically onto a cylinder stores
// k_b A / (2 R^2) as the mesh is refined, whatever the direction of bending.
// The hinge energy is mesh-pattern dependent: on the structured right-triangle
// grid (squares cut along their (1, 1) diagonals) it tends to
// k_b A / (2 R^2) (1 + sin 2phi + sin^2 2phi), phi the angle of the direction
// of curvature from the (1, 0) grid line towards (0, 1): exact for curvature
// along a grid line (phi = 0, 90 deg) or across the cut diagonals
// (phi = -45 deg), 3 times too stiff along them (phi = 45 deg), between 0.75
// and 3 times in general. Measured, discrete shell, R = 1/2 on a unit domain,
// n x n cells (the deficit is the O(1/n) of the missing boundary hinges):
//   equilateral, phi = 90 deg:   n = 12, 24, 48, 96: 0.917, 0.958, 0.979, 0.990
//   equilateral, phi = 0.4 rad:  0.997, 0.998, 0.999, 0.9996
//   right-triangle, phi = 0:     0.917, 0.958, 0.979, 0.990
//   right-triangle, phi = 45 deg: 2.82, 2.91, 2.96, 2.98 (-> 3)
// The quadratic model gives the same to within 0.5 % (tests/element).
//
// Q / k_b = K K^T (x) I3 / (A1 + A2) with K = (c01 + c11, c00 + c10,
// -(c00 + c01), -(c10 + c11)) on (x0, x1, x2, x3), c0j and c1j the rest
// cotangents of triangle 1 and 2 at their corner on x_j. x^T Q x / 2 equals
// the discrete-shell energy to second order about a flat rest shape, so both
// models carry the same normalisation.

#include "common/registry_index.hpp"
#include "element/element.hpp"

#include <Eigen/Core>

#include <array>

namespace sartor::element {

using Vector12 = Eigen::Matrix<double, 12, 1>;

// A bending model: its place in the registry of bending models
// (fem/bending_models.hpp), where each is one file and one registration
// line. The built-in ones by name: the discrete shell and the quadratic
// (IBM) hinges (this file), and the patch triangles, the rotation-free
// Kirchhoff triangle of element/patch_bending.hpp (the default), assembled
// per triangle instead of per hinge.
class BendingModel : public RegistryIndex<BendingModel> {
public:
  using RegistryIndex::RegistryIndex;
  static const BendingModel discrete_shell;
  static const BendingModel quadratic;
  static const BendingModel patch;
};
// In the registry's order (register_bending_models).
inline constexpr BendingModel BendingModel::discrete_shell{0};
inline constexpr BendingModel BendingModel::quadratic{1};
inline constexpr BendingModel BendingModel::patch{2};

struct HingeRest {
  double weight = 0.0;     // discrete shell: scaled 3|e|^2/(A1 + A2), dimensionless
  double rest_angle = 0.0; // rad, discrete shell only (the quadratic model is flat at rest)
  Eigen::Matrix<double, 12, 12> quadratic; // Q / k_b, 1/m^2 (quadratic model)
};

// From the rest (material) shape of the two triangles, corners ordered as
// above: first = (u0, u1, u2), second = (u1, u0, u3). Each triangle is given
// in its own panel's coordinates, so the two copies of the edge may differ a
// little (a seam): |e| is the mean of their lengths. The cotangents and
// areas are each triangle's own. Throws InputError when a triangle is
// degenerate or rest_angle is not finite.
HingeRest hinge_rest(const std::array<Eigen::Vector2d, 3>& first,
                     const std::array<Eigen::Vector2d, 3>& second, double rest_angle = 0.0);

// A hinge whose current edge or triangles have collapsed (zero length or
// area: no dihedral angle) contributes nothing to the discrete-shell model.
Result<12> bending(BendingModel model, double stiffness, const HingeRest& rest, const Vector12& x,
                   Want want);

} // namespace sartor::element
