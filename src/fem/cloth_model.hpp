#pragma once
// What a cloth is made of and what acts on it: materials, loads, contact
// settings and the reports of energy and contact, shared by ClothProblem
// and its energy forms (fem/form.hpp).

#include "contact/body.hpp"
#include "element/bending.hpp"
#include "element/membrane.hpp"
#include "element/patch_bending.hpp"
#include "material/fabric.hpp"

#include <Eigen/Core>

#include <array>
#include <memory>
#include <optional>
#include <vector>

namespace sartor {

// One friction anchor as checkpoints hold it: body, vertex, point (3),
// normal (3), the lagged normal force (N; inf: not known), slid (0 or 1).
using AnchorRow = std::array<double, 10>;

struct ClothMaterial {
  explicit ClothMaterial(element::MembraneMaterial membrane_material)
      : membrane(std::move(membrane_material)) {}
  element::MembraneModel membrane_model = element::MembraneModel::baraff_witkin;
  element::MembraneMaterial membrane;
  // The patch model converges to plate theory (docs/finite-elements.md); the
  // hinges (discrete shell, quadratic) are the thesis' and Sensitive
  // Couture's models, and only the discrete shell honours creases.
  element::BendingModel bending_model = element::BendingModel::patch;
  double bending_stiffness = 0.0; // N m
  // Orthotropic rigidities of the patch model (warp along u, weft along v);
  // unset: isotropic with nu = 0 from bending_stiffness.
  std::optional<element::BendingRigidity> bending_rigidity;
  // Rest curvature of the patch model, per mesh triangle (kappa_uu, kappa_vv,
  // 2 kappa_uv in 1/m); empty: flat panels.
  std::vector<Eigen::Vector3d> rest_curvature;
  // Moment-curvature curves of the patch model (a measured fabric); they
  // replace the rigidities' diagonal, whose initial values they give.
  std::shared_ptr<const FabricBending> bending_curves;
  element::BendingRigidity patch_rigidity() const {
    if (bending_curves) {
      const double coupling = bending_rigidity ? bending_rigidity->coupling : 0.0;
      return {bending_curves->warp.initial_rigidity(), bending_curves->weft.initial_rigidity(),
              coupling, bending_curves->twist.initial_rigidity()};
    }
    return bending_rigidity ? *bending_rigidity
                            : element::BendingRigidity::isotropic(bending_stiffness);
  }
  bool has_bending() const {
    const element::BendingRigidity d = patch_rigidity();
    return bending_stiffness > 0.0 || d.warp > 0.0 || d.weft > 0.0 || d.twist > 0.0;
  }
  double areal_density = 0.0;    // kg/m^2
  bool project_membrane = false; // PSD-project element Hessians (compression stabilisation)
  bool project_bending = false;
  // The patch model's PSD Hessian where project_bending asks: the exact
  // Hessian with its negative eigenvalues clamped, or Gauss-Newton's (its
  // strain's derivative through the projected tangent: no eigenproblem, a
  // third less CPU over the sample garments' drapes, but the coarse dress
  // then ends 5 mm apart under another CPU's BLAS kernels;
  // docs/drape.md#the-patch-models-gauss-newton-hessian).
  bool patch_gauss_newton = false;
};

struct ClothLoads {
  Eigen::Vector3d gravity = Eigen::Vector3d::Zero();         // m/s^2
  double pressure = 0.0;                                     // Pa, follower
  std::vector<std::pair<int, Eigen::Vector3d>> point_forces; // vertex, N
};

// Energy, split for reports.
struct ClothEnergy {
  double membrane = 0.0;
  double bending = 0.0;
  double external = 0.0; // of gravity and point forces from the initial placement (no pressure)
  double contact = 0.0;  // body penalty and friction anchor springs
  double seam = 0.0;     // seam springs
  double total() const { return membrane + bending + external + contact + seam; }
};

// Contact between the cloth's vertices and rigid bodies (docs/contact.md).
struct ContactSettings {
  double offset = 1e-3;          // m: the distance kept from bodies (half the cloth thickness)
  double stiffness = 0.0;        // N/m per vertex; 0: automatic, see contact::penalty_stiffness
  double stiffness_factor = 1.0; // the automatic rule's factor
  // Multiplies the stiffness above: statics raise it where the cloth ends
  // too deep in the offset layer (solvers/statics.hpp, adaptive penalty).
  double stiffness_scale = 1.0;
  // The band over which the normal force sets in smoothly, as a fraction of
  // the offset (contact::penalty_law); 0: the plain quadratic penalty.
  double penalty_onset = 0.0;
  // PSD-project each vertex's contact Hessian (its curvature term
  // -k (offset - d) H_d is negative on convex bodies).
  bool project_hessian = false;
  // Friction anchor springs bounded by Coulomb's cone (contact::anchor_spring):
  // a vertex slides within a solve. The static minimiser's contact rounds
  // turn it on (solvers/statics.hpp), and a wear whose bodies move keeps it on
  // (CreepOptions::follow_bodies); plain springs otherwise, whose anchors
  // slide between solves only.
  bool bounded_friction = false;
  // The anchor springs in the body's tangent plane at the vertex
  // (contact::surface_anchor_spring) instead of the plane frozen at the
  // anchor, and anchors placed at the vertex's level: the wear turns it on
  // (solvers/wear.hpp), where cloth slides over a bending knee and the frozen
  // plane's force turned at every update.
  bool friction_plane_at_vertex = false;
  // m: sample points on every edge longer than this, no further apart than
  // it, carry the penalty too (fem/cloth_edge_contact.cpp), so that edges do
  // not cut through curved bodies between vertices; 0: vertices only
  // (static drapes: 0.015, app/drape_command.cpp).
  double edge_sample_spacing = 0.0;
};

// What one body does to the cloth, summed over all vertices (every rank).
struct BodyContact {
  Eigen::Vector3d normal_force = Eigen::Vector3d::Zero();   // N, on the cloth
  Eigen::Vector3d friction_force = Eigen::Vector3d::Zero(); // N, on the cloth
  long contacting_vertices = 0;                             // inside the contact offset
  long anchored_vertices = 0;                               // holding an anchor in the solved state
  long sliding_vertices = 0;                                // whose anchor slid at the last update
  double max_penetration = 0.0;      // m: largest depth into the offset layer, offset - d
  double min_distance = 0.0;         // m: smallest signed distance of a vertex (< 0: inside)
  long contacting_edge_samples = 0;  // edge sample points inside the contact offset
  double edge_max_penetration = 0.0; // m: their largest depth into the offset layer
};

// Unloaded lengths that follow the element's own deformation within a step:
// the monolithic creep coupling (fem/creep_coupling.hpp), whose non-elastic
// strains at the end of a step depend on the tension there.
class NonelasticResponse {
public:
  virtual ~NonelasticResponse() = default;
  struct Answer {
    element::NonelasticStrain strain;
    Eigen::Matrix<double, 2, 9> per_position = Eigen::Matrix<double, 2, 9>::Zero(); // dn/dx
    // dn/dT: the strains' response to a change of the element's tensions at
    // fixed n (a move of the rest coordinates makes one); dn/dx is it times dT/dx.
    Eigen::Matrix2d per_tension = Eigen::Matrix2d::Zero();
  };
  // The strains of mesh triangle `triangle` at element positions `x` (NaN
  // when there are none), and their derivative when `want_derivative`.
  virtual Answer respond(int triangle, const ClothMaterial& material,
                         const element::TriangleRest& rest, const element::Vector9& x,
                         bool want_derivative) const = 0;
  // Whether the strains depend on the positions now (else they are held).
  virtual bool moves_with_positions() const = 0;
};

} // namespace sartor
