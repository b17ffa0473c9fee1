#pragma once
// Rotation-free Kirchhoff bending of a triangle from the slopes at its edges'
// midpoints, the slopes reconstructed from six-node patches (a triangle and
// the three vertices across its edges), in the spirit of the basic shell
// triangles of Onate & Zarate and Flores & Onate, with Morley's shared
// mid-edge normal slopes.
//
// 1. Patch: the positions over a triangle (x0, x1, x2) and the nodes across
//    its edges (x3+k across the edge opposite corner k) are interpolated by
//    the quadratic in material coordinates (u, v) through all six,
//      x(u, v) = sum_k lambda_k x_k + sum_e c_e lambda_i lambda_j,
//    lambda the barycentric coordinates, e = (i, j) the edges. Its gradient
//    along each edge's outward normal at the edge's midpoint is the patch's
//    normal slope there (midedge_slopes).
// 2. Each interior edge takes the mean of its two triangles' patch slopes
//    (single-valued, as the normal slope of Morley's element); along the
//    edge the slope is the chord's, (x_j - x_i)/|e|.
// 3. The second derivatives by the divergence theorem over the triangle,
//      H_ab = x_,ab = (1/A) sum_k |e_k| sym(x_,a nu_b)  at edge k's midpoint,
//    linear in the twelve nodes of the triangle and its neighbours' patches
//    (patch_rest), and the curvature kappa_ab = H_ab . n, n the current unit
//    normal of the triangle.
// Every step is exact for quadratic fields, so the curvature is consistent
// on any mesh; because each edge's slope is shared by its two triangles, the
// sum of A kappa over the mesh telescopes to the boundary, so mesh-scale
// oscillations cannot pass for a mean curvature (a single patch's own second
// derivatives, without step 2, are consistent but are 50 % too soft on the
// alternating rectangle mesh and five times on cells of aspect 4).
// For a nearly isometric deformation H_ab is normal to the surface and kappa
// is Koiter's bending strain at any rotation.
//
// Energy per triangle, A its material area:
//   E = A/2 (k - k_rest)^T D (k - k_rest),  k = (kappa_uu, kappa_vv, 2 kappa_uv),
//   D = [[D_warp, D_coupling, 0], [D_coupling, D_weft, 0], [0, 0, D_twist]],
// the rigidities in N m (moment per unit width per curvature). With
// moment-curvature curves (measured fabrics) the diagonal terms become the
// curves' energies, E = A [W_warp(s0) + W_weft(s1) + W_twist(s2) +
// D_coupling s0 s1], s = k - k_rest, W the integral of each curve; the
// free-edge condition keeps the curves' initial rigidities. An isotropic
// plate with Poisson ratio nu has D_warp = D_weft = D, D_coupling = nu D,
// D_twist = (1 - nu) D / 2; the hinge models' k_b corresponds to nu = 0.
//
// Boundary edges (one triangle) have no node across: the patch quadratic's
// coefficient of that edge is set instead by the free-edge condition, no
// moment about the edge, M_nn = n_a n_b (D k)_ab = 0 with n the edge's
// in-plane normal, imposed on the vector x_,ab (exact for a free edge of a
// nearly isometric plate), and the edge's slope is its one patch's. A
// clamped edge is a band of pinned vertices at least one element wide: the
// pinned nodes across the first free triangles' edges fix the slope (the
// assembly skips triangles whose three vertices are all fixed: their
// curvature is prescribed).
//
// The patch's three edge coefficients solve a 3x3 system whose matrix
// depends only on the barycentric coordinates of the nodes across
// (invariant under affine maps). Where the six nodes nearly lie on a conic
// that system is nearly singular; below a conditioning of `ill_conditioned`
// it is solved in the least-squares sense with a small Tikhonov term.

#include "element/element.hpp"
#include "material/fabric.hpp"

#include <Eigen/Core>

#include <array>
#include <memory>

namespace sartor::element {

using Vector36 = Eigen::Matrix<double, 36, 1>;

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

// Twelve nodes: the triangle's corners 0..2, the nodes across its edges 3..5,
// then for edge k the two further nodes of the neighbour's patch at 6 + 2k,
// 7 + 2k (slots without a node repeat a corner with weight zero).
struct PatchRest {
  double area = 0.0;                    // m^2, of the triangle
  Eigen::Matrix<double, 3, 12> weights; // H_uu, H_vv, H_uv = sum_i w(., i) x_i, 1/m^2
  Eigen::Matrix3d rigidity;             // D, N m
  Eigen::Vector3d rest_curvature;       // (kappa_uu, kappa_vv, 2 kappa_uv), 1/m
  // Moment-curvature curves replacing the diagonal of `rigidity`; none: linear.
  std::shared_ptr<const FabricBending> curves;
};

// Conditioning (smallest over largest singular value of the patch's edge
// system) below which it is solved with regularisation.
constexpr double ill_conditioned = 1e-2;

// The patch's geometry on the material coordinates (steps 1-3 below) is
// written once for either scalar: double for the rest data, AutoDiff
// (common/autodiff.hpp) for their exact derivative along a change of the
// material coordinates, which the design sensitivity needs
// (docs/sensitivity.md). Both are instantiated.
template <typename Scalar>
using PatchPoint = Eigen::Matrix<Scalar, 2, 1>;
template <typename Scalar>
using PatchTriangle = std::array<PatchPoint<Scalar>, 3>;
template <typename Scalar>
using EdgeSlopes = std::array<Eigen::Matrix<Scalar, 1, 6>, 3>;

// Step 1: for each edge k, the weights over the patch's six nodes of the
// quadratic's slope along the edge's outward normal at its midpoint.
// `triangle`: material coordinates; `across[k]`: the node across edge
// (k+1, k+2) placed in the triangle's frame, absent (boundary edge) when
// `has_node[k]` is false. Throws InputError for a degenerate triangle, a
// node across on the triangle's side of its edge, or bad rigidities.
template <typename Scalar>
EdgeSlopes<Scalar>
midedge_slopes(const PatchTriangle<Scalar>& triangle, const PatchTriangle<Scalar>& across,
               const std::array<bool, 3>& has_node, const BendingRigidity& rigidity);

// The slopes of the triangle's own plane (the linear interpolation of its
// corners; zero weight on the nodes across): what a clamped (fixed) triangle
// imposes on the edges it shares with free ones.
template <typename Scalar>
EdgeSlopes<Scalar> plane_slopes(const PatchTriangle<Scalar>& triangle);

// Steps 2-3, the geometric part of the rest data: the triangle's area and
// the weights of its second derivatives over the twelve nodes, from each
// edge's (shared) outward normal slope. Throws InputError for a degenerate
// triangle.
template <typename Scalar>
struct PatchWeights {
  Scalar area;                          // m^2
  Eigen::Matrix<Scalar, 3, 12> weights; // as PatchRest's, 1/m^2
};
template <typename Scalar>
PatchWeights<Scalar>
patch_weights(const PatchTriangle<Scalar>& triangle,
              const std::array<Eigen::Matrix<Scalar, 1, 12>, 3>& normal_slopes);

// The rest data: patch_weights with the rigidity and rest curvature. Throws
// InputError also for negative rigidities or a non-finite rest curvature.
PatchRest patch_rest(const std::array<Eigen::Vector2d, 3>& triangle,
                     const std::array<Eigen::Matrix<double, 1, 12>, 3>& normal_slopes,
                     const BendingRigidity& rigidity,
                     const Eigen::Vector3d& rest_curvature = Eigen::Vector3d::Zero());

// The node across edge (a, b) of a triangle, given in another frame (a
// neighbour in another panel): (a', b', p') there, placed in this frame with
// the same position relative to the edge, on the other side of it from `c`,
// the triangle's third corner.
template <typename Scalar>
PatchPoint<Scalar> node_across(const PatchPoint<Scalar>& a, const PatchPoint<Scalar>& b,
                               const PatchPoint<Scalar>& c, const PatchPoint<Scalar>& a_other,
                               const PatchPoint<Scalar>& b_other,
                               const PatchPoint<Scalar>& p_other);

// Energy density (J/m^2), moments (dW/ds) and tangent (d2W/ds2) at the
// bending strain s = k - k_rest: the quadratic form of the rigidity matrix,
// or the curves' energies with its Poisson coupling.
struct PatchResponse {
  double energy_density = 0.0;
  Eigen::Vector3d moment = Eigen::Vector3d::Zero();
  Eigen::Matrix3d tangent = Eigen::Matrix3d::Zero();
};
PatchResponse patch_response(const PatchRest& rest, const Eigen::Vector3d& strain);

// Energy, gradient and Hessian over the twelve nodes' positions. A triangle
// collapsed to zero area (no normal) contributes nothing.
Result<36> patch_bending(const PatchRest& rest, const Vector36& x, Want want);

// The Gauss-Newton Hessian at x: area B^T T+ B, B the strain's derivative
// and T+ the response's tangent projected to PSD. Positive semi-definite by
// construction, without an eigenproblem of the 36 x 36 Hessian: it leaves
// out sum_r M_r d^2 s_r, the moments' share, which vanishes where the
// moments do (--bending-psd-method gauss-newton; docs/finite-elements.md).
Eigen::Matrix<double, 36, 36> patch_gauss_newton_hessian(const PatchRest& rest, const Vector36& x);

// project_to_psd<36> of the patch's Hessian at x, by an eigenproblem of 14
// rather than 36. The Hessian's range lies in the corners' nine dofs and in
// five directions of the nine other nodes: the curvatures see those nodes
// only through sum_i w_ri x_i . n (three directions, along n), and the
// moments turn n only along one combination of them in the tangent plane
// (two). Projected in that subspace it is the same matrix (to round-off), at
// about a fifth of the cost; the full eigenproblem took a quarter of a static
// drape's time.
void project_patch_hessian_to_psd(const PatchRest& rest, const Vector36& x,
                                  Eigen::Matrix<double, 36, 36>& hessian);

} // namespace sartor::element
