#pragma once
// Contact of the cloth with rigid bodies (docs/contact.md): a penalty on the
// signed distance of every free vertex and, where ContactSettings asks, of
// sample points along the edges; Coulomb friction by anchor springs whose
// anchors move between steps (accept_step) and, in the static minimiser's
// contact rounds, bounded by the cone of the lagged normal force. Each
// owned free vertex meets each body on the rank that owns it, and each edge
// on the rank that owns the lowest-numbered triangle holding it, so sums
// over ranks count everything once and do not depend on the partition.
//
// The bodies and settings are the problem's (ClothProblem::bodies,
// ::contact), read at every evaluation; the form keeps the anchors, the
// edge samples and the caches of where each point was last queried.

#include "contact/body.hpp"
#include "contact/edge_penalty.hpp"
#include "contact/penalty.hpp"
#include "fem/cloth_model.hpp"
#include "fem/form.hpp"
#include "mesh/triangle_mesh.hpp"

#include <limits>
#include <vector>

namespace sartor {
class ClothProblem;
}

namespace sartor::fem {

class ContactForm final : public Form {
public:
  // `vertex_dof`, `vertex_owned` are the problem's layout; `moves`: per mesh
  // vertex, free or a pin that will be let go; `triangle_owned`: the mesh
  // triangles this rank assembles; `modulus`: the largest initial membrane
  // modulus (N/m), for the automatic penalty stiffness.
  ContactForm(const ClothProblem& problem, const std::vector<PetscInt>& vertex_dof,
              const std::vector<bool>& vertex_owned, const std::vector<bool>& moves,
              std::vector<bool> triangle_owned, double modulus);

  const char* name() const override { return "contact"; }
  EnergyPart part() const override { return EnergyPart::contact; }
  void add_energy(const FormPoint& at, double* sum) const override;
  void add_gradient(const FormPoint& at, PetscScalar* f) const override;
  PetscErrorCode add_hessian(const FormPoint& at, Mat J) const override;
  // Friction (Sensitive Couture §7): vertices that came into contact get an
  // anchor where they touched, anchors pulled past mu_s of the normal force
  // slide to mu_k of it, vertices that left contact lose theirs.
  PetscErrorCode accept_step(const FormPoint& at) override;
  bool projects() const override;
  // The pattern enters through the automatic penalty stiffness, c E A_v /
  // h^2 (A_v the vertex's share of the material area, h the longest rest
  // edge): every force of the form is linear in its stiffness (an anchor
  // past its friction bound excepted, whose force is the bound), so each
  // changes by its own relative change dA_v / A_v - 2 dh / h. The edge
  // samples' parameters and counts are held (their count is a step
  // function of the rest lengths). Where several edges are the longest, dh
  // is the largest of their changes: the derivative for a step forwards.
  bool has_rest_derivative() const override { return true; }
  void add_rest_derivative(const FormPoint& at, const RestChange& change,
                           PetscScalar* changes) const override;

  // The largest t in (0, 1] that no point of this rank bounds the step from
  // x along `motions` at (ClothProblem::contact_step_bound).
  double step_bound(const PetscScalar* x, const PetscScalar* motions) const;
  // Collective: per body, forces and state at x (ClothProblem::contact_report).
  PetscErrorCode report(const PetscScalar* x, std::vector<BodyContact>* report) const;
  // Adds per owned free vertex, in the slots of its triple of the local
  // array `per_vertex`: the vertex's own normal force, the friction force of
  // the anchors the last solve used, and that force over the cone mu_s f_n,
  // f_n with the vertex's share of the edge samples' normal force
  // (`sample_loads`, per body as edge_sample_loads gives them).
  void add_vertex_loads(const PetscScalar* x,
                        const std::vector<std::vector<Eigen::Vector3d>>& sample_loads,
                        PetscScalar* per_vertex) const;
  // Sets, per owned free vertex, in its triple of the local array
  // `per_vertex`, the force of `body`'s own contact with the vertex at x: its
  // penalty and its friction anchor's spring, without the edge samples'.
  void vertex_contact_forces(std::size_t body, const PetscScalar* x, PetscScalar* per_vertex) const;
  // Collective: per mesh vertex (those local to this rank), the normal
  // forces of `body` on the samples of its edges, shared by the lever rule.
  PetscErrorCode edge_sample_loads(std::size_t body, const PetscScalar* x,
                                   std::vector<Eigen::Vector3d>* per_vertex) const;
  // ClothProblem::level_friction_anchors, at the local array x (the
  // anchors of the last solve too, which the reports read).
  void level_anchors(const PetscScalar* x);
  // This rank's anchors as checkpoint rows (owned vertices only), and the
  // rows of every rank restored.
  std::vector<double> anchor_rows() const;
  void restore_anchors(const std::vector<AnchorRow>& rows);
  // m^2: a vertex's share of the material area.
  double vertex_area(std::size_t vertex) const { return vertex_area_[vertex]; }

private:
  struct FrictionAnchor {
    bool active = false;
    Eigen::Vector3d point = Eigen::Vector3d::Zero();   // on the body surface
    Eigen::Vector3d normal = Eigen::Vector3d::UnitZ(); // of the frozen tangent plane
    // The normal force at the last update (lagged), N; infinite where it is
    // not known (anchors restored from a checkpoint): a plain spring.
    double normal_force = std::numeric_limits<double>::infinity();
    bool sliding = false; // slid at the last update: bounded by mu_k, else mu_s
  };
  // The anchor spring's force bound: Coulomb's cone at the lagged normal
  // force; infinite (a plain spring) unless bounded friction.
  static double friction_bound(const FrictionAnchor& anchor, const contact::Friction& friction,
                               bool bounded) {
    if (!bounded || std::isinf(anchor.normal_force)) return std::numeric_limits<double>::infinity();
    return (anchor.sliding ? friction.kinetic_coefficient : friction.static_coefficient) *
           anchor.normal_force;
  }
  const std::vector<contact::Body>& bodies() const;
  const ContactSettings& settings() const;
  double clock() const;
  double stiffness(int vertex) const;
  static Eigen::Vector3d unit_normal(const contact::SurfaceQuery& q);
  // The penalty's onset band, m (contact::penalty_law).
  double band() const;
  // The penalty law's normal force at `depth` into the offset layer.
  double normal_force(double stiffness, double depth) const;
  // The penalty's normal force on `vertex` where the body was queried (q).
  double penalty_normal_force(int vertex, const contact::SurfaceQuery& q) const;
  // The normal force that bounds the vertex's friction anchor: the
  // penalty's and its share of the body's edge samples' force (`samples`)
  // along the body's normal; the samples themselves are frictionless.
  double anchor_normal_force(int vertex, const contact::SurfaceQuery& q,
                             const Eigen::Vector3d& samples) const;
  // Per mesh vertex, d(stiffness) / stiffness under the rest change.
  std::vector<double> relative_stiffness_changes(const RestChange& change) const;
  contact::PointResult vertex_contact(std::size_t body, int vertex, const Eigen::Vector3d& x,
                                      element::Want want) const;
  // The anchor spring of `anchor` on vertex x with bound `bound`, in the
  // plane ContactSettings::friction_plane_at_vertex picks; `here` is the
  // body's query at x (read only for the plane at the vertex).
  contact::PointResult friction_spring(const contact::Body& body, const FrictionAnchor& anchor,
                                       double stiffness, const Eigen::Vector3d& x,
                                       const contact::SurfaceQuery& here, double bound,
                                       element::Want want) const;
  double vertex_step_bound(std::size_t body, const Eigen::Vector3d& p,
                           const Eigen::Vector3d& motion) const;

  // Per body and point, the last place it was queried at and its signed
  // distance there. The distance moves no faster than the body's slope
  // bound times the point, so a point that has moved less than (distance -
  // offset) / slope bound since, on the same clock, is still out of
  // contact: energy, residual and Jacobian skip its query (most of a
  // garment, most of the time; the mannequin's query is the costliest part
  // of an evaluation).
  struct QueriedPlace {
    Eigen::Vector3d point = Eigen::Vector3d::Zero();
    double distance = -1.0; // m; below the offset: query again
    double clock = 0.0;
  };
  bool surely_apart(std::size_t body, int vertex, const Eigen::Vector3d& x) const;

  // Edges (the sample point at parameter s of the edge from mesh vertex a to
  // b), built on first use, again when the spacing setting changes.
  struct EdgeSample {
    int a, b;
    double s;
  };
  const std::vector<EdgeSample>& edge_samples() const;
  double edge_sample_stiffness(const EdgeSample& sample) const;
  contact::EdgeSampleResult edge_sample_contact(std::size_t body, std::size_t index,
                                                const PetscScalar* x, element::Want want,
                                                bool project) const;
  double edge_energy(const PetscScalar* x) const;
  void add_edge_forces(const PetscScalar* x, PetscScalar* f) const;
  PetscErrorCode add_edge_hessian(const PetscScalar* x, bool project, Mat J) const;
  double edge_step_bound(const PetscScalar* x, const PetscScalar* motions) const;
  void add_edge_report(std::size_t body, const PetscScalar* x, double force_sum[3],
                       double* contacting, double* deepest) const;

  const ClothProblem& problem_;
  const TriangleMesh& mesh_;
  const std::vector<PetscInt>& vertex_dof_;
  const std::vector<bool>& vertex_owned_;
  std::vector<bool> moves_;
  std::vector<bool> triangle_owned_;
  double modulus_;
  std::vector<int> vertices_; // owned free (or releasable) vertices
  std::vector<double> vertex_area_;
  double mesh_size_ = 0.0;
  std::vector<std::vector<FrictionAnchor>> anchors_;
  // The anchors before the last update: those the last solved state is in
  // equilibrium with, for the reported friction forces.
  std::vector<std::vector<FrictionAnchor>> solved_anchors_;
  bool solved_bounded_ = false; // the bounded_friction setting of that solve
  std::vector<long> sliding_;
  mutable std::vector<std::vector<QueriedPlace>> queried_;
  mutable std::vector<EdgeSample> edge_samples_;
  mutable double edge_samples_spacing_ = -1.0;
  mutable std::vector<std::vector<QueriedPlace>> sample_queried_; // per body and sample
};

} // namespace sartor::fem
