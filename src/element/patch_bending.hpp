#pragma once
// Rotation-free Kirchhoff bending on a six-node patch: a triangle
// (x0, x1, x2) and the three vertices x3, x4, x5 across its edges (x3+k
// across the edge opposite corner k, i.e. the edge (k+1, k+2)), in the spirit
// of the basic shell triangles of Onate & Zarate and Flores & Onate.
//
// The patch's positions are interpolated by the quadratic in the triangle's
// material coordinates (u, v) that matches all six nodes:
//   x(u, v) = sum_k lambda_k x_k + sum_e c_e lambda_i lambda_j,
// lambda the triangle's barycentric coordinates, e = (i, j) its edges. The
// second derivatives H_ab = x_,ab are then constant and linear in the nodes,
// and the curvature (second fundamental form in material coordinates) is
//   kappa_ab = H_ab . n,
// n the current unit normal of the triangle. A quadratic field is reproduced
// exactly on any patch, so the curvature is consistent on any mesh; for a
// nearly isometric deformation H_ab is normal to the surface and kappa is
// Koiter's bending strain at any rotation.
//
// Energy per triangle, A its material area:
//   E = A/2 (k - k_rest)^T D (k - k_rest),  k = (kappa_uu, kappa_vv, 2 kappa_uv),
//   D = [[D_warp, D_coupling, 0], [D_coupling, D_weft, 0], [0, 0, D_twist]],
// the rigidities in N m (moment per unit width per curvature). An isotropic
// plate with Poisson ratio nu has D_warp = D_weft = D, D_coupling = nu D,
// D_twist = (1 - nu) D / 2; the hinge models' k_b corresponds to nu = 0.
//
// Boundary edges (one triangle) have no node across: the quadratic's
// coefficient of that edge is set instead by the free-edge condition, no
// moment about the edge, M_nn = n_a n_b (D k)_ab = 0 with n the edge's
// in-plane normal, imposed on the vector x_,ab (exact for a free edge of a
// nearly isometric plate). The missing node's slot repeats the triangle's
// corner opposite that edge, with weight zero. A clamped edge is a band of
// pinned vertices at least one element wide: the pinned nodes across the
// first free triangles' edges fix the slope (the assembly skips triangles
// whose three vertices are all fixed: their curvature is prescribed).
//
// The three edge coefficients solve a 3x3 system whose matrix depends only
// on the barycentric coordinates of the nodes across (invariant under affine
// maps: stretched cells behave as square ones). Where the six nodes nearly
// lie on a conic that system is nearly singular; below a conditioning of
// `ill_conditioned` it is solved in the least-squares sense with a small
// Tikhonov term (counted in PatchRest::regularised).

#include "element/element.hpp"

#include <Eigen/Core>

#include <array>

namespace sartor::element {

using Vector18 = Eigen::Matrix<double, 18, 1>;

// Bending rigidities in the material frame (u: warp, v: weft), N m.
struct BendingRigidity {
  double warp = 0.0;
  double weft = 0.0;
  double coupling = 0.0; // Poisson coupling, nu D for an isotropic plate
  double twist = 0.0;    // (1 - nu) D / 2 for an isotropic plate
  // nu = 0, the hinge models' k_b.
  static BendingRigidity isotropic(double stiffness, double poisson = 0.0) {
    return {stiffness, stiffness, poisson * stiffness, 0.5 * (1.0 - poisson) * stiffness};
  }
  Eigen::Matrix3d matrix() const;
};

struct PatchRest {
  double area = 0.0;                   // m^2, of the central triangle
  Eigen::Matrix<double, 3, 6> weights; // H_uu, H_vv, H_uv = sum_i w(., i) x_i, 1/m^2
  Eigen::Matrix3d rigidity;            // D, N m
  Eigen::Vector3d rest_curvature;      // (kappa_uu, kappa_vv, 2 kappa_uv), 1/m
  bool regularised = false;            // the ill-conditioned fallback was used
};

// Conditioning (smallest over largest singular value of the edge system)
// below which the patch is solved with regularisation.
constexpr double ill_conditioned = 1e-2;

// `triangle`: the central triangle's material coordinates. `across[k]`: the
// node across edge (k+1, k+2) placed in the triangle's frame, or absent
// (boundary edge) when `has_node[k]` is false. Throws InputError for a
// degenerate triangle, a node across on the triangle's side of its edge,
// negative rigidities or a non-finite rest curvature.
PatchRest patch_rest(const std::array<Eigen::Vector2d, 3>& triangle,
                     const std::array<Eigen::Vector2d, 3>& across,
                     const std::array<bool, 3>& has_node, const BendingRigidity& rigidity,
                     const Eigen::Vector3d& rest_curvature = Eigen::Vector3d::Zero());

// The node across edge (a, b) of a triangle, given in another frame (a
// neighbour in another panel): (a', b', p') there, placed in this frame with
// the same position relative to the edge, on the other side of it from `c`,
// the triangle's third corner.
Eigen::Vector2d node_across(const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                            const Eigen::Vector2d& c, const Eigen::Vector2d& a_other,
                            const Eigen::Vector2d& b_other, const Eigen::Vector2d& p_other);

// Energy, gradient and Hessian over the six nodes' positions. A triangle
// collapsed to zero area (no normal) contributes nothing.
Result<18> patch_bending(const PatchRest& rest, const Vector18& x, Want want);

} // namespace sartor::element
