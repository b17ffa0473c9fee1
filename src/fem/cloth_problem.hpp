#pragma once
// A cloth on PETSc: the triangle mesh as a distributed DMPlex with three
// position dofs per vertex, pinned vertices as section constraints, and the
// assembly of energy, residual and Jacobian from the element kernels.
//
// The unknowns are the vertex positions x (not displacements). The residual
// is F(x) = grad E(x) - f_ext(x): membrane and bending energies minus gravity,
// point forces and follower pressure, the loads scaled by a load factor.
//
// Every rank holds the whole TriangleMesh (it is the serial front end's
// output); the DMPlex decides which triangles each rank assembles. Results
// are gathered in the mesh's own vertex and triangle numbering, so they do not
// depend on the number of ranks.

#include "contact/body.hpp"
#include "contact/edge_penalty.hpp"
#include "contact/penalty.hpp"
#include "element/bending.hpp"
#include "element/membrane.hpp"
#include "element/patch_bending.hpp"
#include "fem/cloth_output.hpp"
#include "fem/pin_motion.hpp"
#include "fem/seam_coupling.hpp"
#include "mesh/triangle_mesh.hpp"

#include <petscdmplex.h>
#include <petscmat.h>
#include <petscsf.h>

#include <Eigen/Core>

#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <vector>

namespace sartor {

// One friction anchor as checkpoints hold it: body, vertex, point (3),
// normal (3), the lagged normal force (N; inf: not known), slid (0 or 1).
using AnchorRow = std::array<double, 10>;

namespace fem {
struct BlockLayout;
}

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
  // too deep in the offset layer (fem/statics.hpp, adaptive penalty).
  double stiffness_scale = 1.0;
  // PSD-project each vertex's contact Hessian (its curvature term
  // -k (offset - d) H_d is negative on convex bodies).
  bool project_hessian = false;
  // Friction anchor springs bounded by Coulomb's cone (contact::anchor_spring):
  // a vertex slides within a solve. The static minimiser's contact rounds
  // turn it on (fem/statics.hpp); plain springs otherwise, whose anchors
  // slide between solves only.
  bool bounded_friction = false;
  // m: sample points on every edge longer than this, no further apart than
  // it, carry the penalty too (fem/cloth_edge_contact.cpp), so that edges do
  // not cut through curved bodies between vertices; 0: vertices only
  // (static drapes: 0.015, solvers/drape_command.cpp).
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
  };
  // The strains of mesh triangle `triangle` at element positions `x` (NaN
  // when there are none), and their derivative when `want_derivative`.
  virtual Answer respond(int triangle, const ClothMaterial& material,
                         const element::TriangleRest& rest, const element::Vector9& x,
                         bool want_derivative) const = 0;
  // Whether the strains depend on the positions now (else they are held).
  virtual bool moves_with_positions() const = 0;
};

// Per-triangle results in mesh numbering.
struct TriangleField {
  std::vector<element::MembraneStrain> strain;
};

class ClothProblem {
public:
  // Collective. `mesh`, `pinned` (vertex indices) must be the same on every rank.
  ClothProblem(MPI_Comm comm, const TriangleMesh& mesh, const ClothMaterial& material,
               const std::vector<int>& pinned);
  // Several materials: triangle t uses materials[mesh.material_ids[t]] (all
  // materials[0] when the mesh has no ids). They must share the bending
  // model; a hinge between two materials takes the mean of their stiffnesses.
  // `release_times` (s; one per pin, or empty: none): a pin with a finite
  // one is let go then, in time stepping (pins_follow_time): until then its
  // vertex is a free dof whose equations are x = its place, after that it is
  // free. Statics hold it throughout.
  ClothProblem(MPI_Comm comm, const TriangleMesh& mesh, std::vector<ClothMaterial> materials,
               const std::vector<int>& pinned, const std::vector<double>& release_times = {});
  ~ClothProblem();
  ClothProblem(const ClothProblem&) = delete;
  ClothProblem& operator=(const ClothProblem&) = delete;

  MPI_Comm comm() const { return comm_; }
  DM dm() const { return dm_; }
  const TriangleMesh& mesh() const { return mesh_; }
  ClothLoads loads;
  double load_factor = 1.0;
  // Time, s: the clock of prescribed motions (pins, bodies). Statics keep it
  // fixed; time stepping advances it.
  double time = 0.0;
  std::vector<element::NonelasticStrain> nonelastic; // per mesh triangle (creep state)
  // When set, residual and Jacobian take each triangle's non-elastic strains
  // from it instead of `nonelastic`, and the Jacobian includes their
  // dependence on the positions (then there is no potential energy).
  const NonelasticResponse* nonelastic_response = nullptr;

  // A global vector of the free positions, filled from the mesh's placement.
  PetscErrorCode create_solution(Vec* x) const;
  // Fills the solution vector x from positions of every mesh vertex (mesh
  // numbering, the same on every rank).
  PetscErrorCode set_solution(const std::vector<Eigen::Vector3d>& positions, Vec x) const;
  // Moves pinned vertex `index` (in the order given to the constructor).
  void set_pin_position(std::size_t index, const Eigen::Vector3d& position);
  // Every pin is displaced by load_factor * pin_motion from its position.
  Eigen::Vector3d pin_motion = Eigen::Vector3d::Zero();
  // Prescribed motion histories of groups of pins (pin_motion.hpp), on top
  // of pin_motion. Their clock is the load factor, or `time` when
  // pins_follow_time (time stepping). A pin in several groups follows the last.
  std::vector<PinGroupMotion> pin_groups;
  bool pins_follow_time = false;
  const std::vector<int>& pinned() const { return pinned_; }
  const std::vector<double>& release_times() const { return release_times_; }
  // Whether pin `pin` (an index into pinned()) holds its vertex now: before
  // its release time, and at it while hold_at_release (a solve at the left
  // limit of the release, as creep steps that end there do).
  bool holds(std::size_t pin) const;
  bool hold_at_release = false;
  // Collective. Released pins (those with a release time) that still hold:
  // moves their vertices in x to their places (before a solve), and replaces
  // their rows of a residual f at x, or of an assembled Jacobian, by the
  // equations x = place, scaled by the membrane's stiffness. Solvers call
  // the last two after adding their own terms.
  PetscErrorCode hold(Vec x);
  PetscErrorCode replace_held_rows(Vec x, Vec f);
  PetscErrorCode replace_held_rows(Mat J);

  // Called once a load or time step is accepted at state x: updates the state
  // carried from step to step (friction anchors, creep), never inside Newton.
  PetscErrorCode accept_step(Vec x);

  // Rigid bodies the cloth rests on, moving on the clock of the pin
  // histories (the load factor in statics, `time` when time stepping), and
  // the penalty and friction settings. Set them before solving.
  std::vector<contact::Body> bodies;
  ContactSettings contact;
  // Coulomb friction between steps (Sensitive Couture §7): vertices that came
  // into contact get an anchor at their closest surface point, anchors whose
  // spring force exceeds mu_s times the normal force slide to mu_k times it,
  // vertices that left contact lose theirs. Part of accept_step; statics also
  // call it at the start, to anchor what touches a body there.
  PetscErrorCode update_contact(Vec x);
  // Per body, the forces on the cloth and the contact state at x, the
  // friction forces from the anchors the solve used (before the last update).
  PetscErrorCode contact_report(Vec x, std::vector<BodyContact>* report);
  // Collective. Per-vertex loads at x, in mesh numbering, on rank 0 (empty
  // elsewhere), for the result files (fem/cloth_vertex_loads.cpp): with bodies,
  // contact_pressure (Pa), contact_normal_force and friction_force (N) and
  // friction_utilisation |f_t| / (mu_s |f_n|) (1: on the Coulomb cone); with
  // seams, seam_force (N).
  PetscErrorCode gather_vertex_loads(Vec x, std::vector<ClothNodeField>* fields);
  // Collective. The largest t in (0, 1] such that no vertex moving from x
  // towards x + t d comes closer to a body than the smaller of half its
  // distance at x and a tenth of the contact offset, found by conservative advancement
  // on the signed distance and the shape's slope bound (IPC's CCD filter,
  // with the body's distance in place of CCD). Vertices already inside a
  // body (d <= 0) do not bound the step: the penalty pushes them out.
  PetscErrorCode contact_step_bound(Vec x, Vec direction, double* bound);

  // Seam springs (mesh/seams.hpp) between any vertices of the mesh, on any
  // ranks (fem/seam_coupling.hpp). Collective, with the same springs on every
  // rank; call before create_jacobian. Energy, residual, Jacobian and pin
  // reaction include them.
  void set_seams(const std::vector<SeamSpring>& springs);
  const SeamCoupling* seam_coupling() const { return seams_.get(); }
  // Collective: the largest gap of a seam spring at x, m (0 without seams).
  PetscErrorCode seam_gap(Vec x, double* gap);
  // The sewing stage of time stepping: at time 0 each seam spring is only
  // as stiff as pulls with `sewing_tension` (N/m) times the seam length it
  // sews across its gap in the mesh's placement, and it stiffens
  // geometrically to its own stiffness at `sewing_end_time` (s), so that
  // seams far apart close gradually instead of dragging the cloth through
  // a body; the bodies have no friction meanwhile, so that the panels slide
  // into place (docs/seams.md). Set both before set_seams; sewing_tension 0
  // (or statics) sews with the springs' own stiffness throughout.
  // Statics sew by continuation instead (fem/statics.hpp): `sewing_stage`
  // is the progress of the stage being solved, 0 to 1; below 1 the bodies
  // have no friction.
  double sewing_tension = 0.0;
  double sewing_end_time = 0.0;
  double sewing_stage = 1.0;
  bool sewing() const {
    if (sewing_tension <= 0.0) return false;
    return pins_follow_time ? time <= sewing_end_time : sewing_stage < 1.0;
  }

  PetscErrorCode residual(Vec x, Vec f);
  PetscErrorCode jacobian(Vec x, Mat J);
  // The Jacobian without the PSD projections the materials and contact ask
  // for: the true Hessian, whose inertia certifies stability
  // (fem/certificate.hpp), and which the static minimiser tries near a
  // solution, where the projected one converges only linearly.
  bool exact_hessian = false;
  bool projects_hessians() const {
    for (const ClothMaterial& m : materials_) {
      if (m.project_membrane || m.project_bending) return true;
    }
    return contact.project_hessian;
  }
  PetscErrorCode energy(Vec x, ClothEnergy* energy);
  // Preallocated exactly for the element couplings (membrane and hinges).
  PetscErrorCode create_jacobian(Mat* J);
  bool has_follower_load() const { return loads.pressure != 0.0; }
  // The residual is the gradient of energy(): no follower load, no
  // position-dependent unloaded lengths.
  bool has_potential() const {
    return !has_follower_load() &&
           !(nonelastic_response && nonelastic_response->moves_with_positions());
  }

  // All vertex positions, in mesh numbering, on rank 0 (empty elsewhere).
  PetscErrorCode gather_positions(Vec x, std::vector<Eigen::Vector3d>* positions);
  // Per body, the normal forces of its edge samples at x shared to the
  // edges' vertices by the lever rule, in mesh numbering, on rank 0 (empty
  // elsewhere).
  PetscErrorCode gather_edge_sample_loads(Vec x,
                                          std::vector<std::vector<Eigen::Vector3d>>* per_body);
  // Strains and tensions of every triangle, in mesh numbering, on rank 0.
  PetscErrorCode gather_strains(Vec x, std::vector<element::MembraneStrain>* strains);
  // Mesh indices of the triangles this rank assembles.
  std::vector<int> owned_triangles() const;
  // Calls visit(mesh index, material, rest data, element positions) for every
  // triangle this rank assembles (no communication: what the creep update needs).
  using TriangleVisitor = std::function<void(
      int, const ClothMaterial&, const element::TriangleRest&, const element::Vector9&)>;
  PetscErrorCode visit_owned_triangles(Vec x, const TriangleVisitor& visit);
  // The friction anchors as (body, vertex, point xyz, normal xyz) rows, all
  // ranks' on rank 0, for checkpoints; restore_anchors takes the same rows on
  // every rank.
  PetscErrorCode gather_anchors(std::vector<AnchorRow>* rows);
  void restore_anchors(const std::vector<AnchorRow>& rows);
  // Sum over all vertices of the force the pins exert on the cloth, N.
  PetscErrorCode pin_reaction(Vec x, Eigen::Vector3d* reaction);

  // Lumped vertex masses (areal density x area / 3 from each triangle; unit
  // density when the cloth has none) on the free dofs, kg.
  PetscErrorCode lumped_mass(Vec mass);

  // A force typical of the membrane, N: the largest initial modulus times the
  // square root of the material area. Residuals below ~1e-12 of it are round-off.
  double force_scale() const;

  PetscInt owned_triangle_count() const { return PetscInt(triangles_.size()); }
  PetscInt global_dof_count() const { return global_dofs_; }

private:
  // The per-vertex triples of `local` (laid out as the local vector of
  // positions) in mesh numbering, on rank 0. Collective.
  PetscErrorCode gather_vertex_triples(const PetscScalar* local,
                                       std::vector<Eigen::Vector3d>* triples);
  struct LocalTriangle {
    std::array<PetscInt, 9> dofs; // local-vector indices, corner by corner
    element::TriangleRest rest;
    int index;                     // in the mesh
    const ClothMaterial* material; // in materials_
  };
  struct LocalHinge {
    std::array<PetscInt, 12> dofs;
    element::HingeRest rest;
    double stiffness; // N m
    bool project;     // PSD-project its Hessian
  };
  // The patch model's triangle (element/patch_bending.hpp): its twelve-node
  // stencil as PatchRest numbers it.
  struct LocalPatch {
    std::array<PetscInt, 36> dofs;
    element::PatchRest rest;
    bool project; // PSD-project its Hessian
  };
  void set_up_dofs(const std::vector<PetscInt>& original, const std::vector<bool>& foreign,
                   const std::vector<bool>& is_pinned);
  std::vector<bool> set_up_triangles(const std::vector<PetscInt>& original,
                                     const std::vector<bool>& foreign);
  void set_up_bending(const std::vector<bool>& triangle_owned, const std::vector<bool>& is_pinned);
  void set_up_patches(const std::vector<bool>& triangle_owned, const std::vector<bool>& is_pinned);
  template <std::size_t N>
  std::array<PetscInt, N> vertex_dofs(const std::array<int, N / 3>& vertices) const;
  const ClothMaterial& triangle_material(std::size_t triangle) const;
  // The largest initial modulus of any material, N/m.
  double largest_modulus() const;

  PetscErrorCode to_local(Vec x);
  // Jacobian assembly without column searches (fem/block_assembly.hpp).
  PetscErrorCode attach_element_scatter(const fem::BlockLayout& layout, Mat J) const;
  PetscErrorCode pin_places(std::vector<Eigen::Vector3d>* places) const;
  // Seams (cloth_seams.cpp).
  void update_sewing_progress();
  PetscErrorCode prepare_seams(std::vector<Eigen::Vector3d>* places);
  PetscErrorCode seam_energy(Vec x, double* energy);
  PetscErrorCode add_seam_forces(Vec x, Vec f);
  PetscErrorCode add_seam_jacobian(Mat J);
  PetscErrorCode add_seam_pin_reaction(Vec x, Eigen::Vector3d* reaction);
  std::unique_ptr<SeamCoupling> seams_;

  MPI_Comm comm_;
  const TriangleMesh& mesh_;
  std::vector<ClothMaterial> materials_;
  std::vector<int> pinned_;
  std::vector<double> release_times_; // per pin, infinity: never released
  // Pins with a release time whose vertex this rank owns, and the vertex's
  // first row in the global vector.
  struct ReleasableRow {
    std::size_t pin;
    PetscInt row;
  };
  std::vector<ReleasableRow> releasable_rows_;
  // The releasable pins that hold now: first global row, place.
  struct HeldRow {
    PetscInt first;
    Eigen::Vector3d place;
  };
  PetscErrorCode holding_rows(std::vector<HeldRow>* rows) const;
  bool releasable(std::size_t pin) const { return std::isfinite(release_times_[pin]); }
  DM dm_ = nullptr;
  Vec local_x_ = nullptr;
  Vec local_f_ = nullptr;
  PetscInt global_dofs_ = 0;
  std::vector<PetscInt> vertex_dof_; // local-vector offset of each mesh vertex, -1 if absent
  std::vector<bool> vertex_owned_;   // this rank owns the vertex (for point forces, outputs)
  std::vector<LocalTriangle> triangles_;
  std::vector<LocalHinge> hinges_;
  std::vector<LocalPatch> patches_;
  std::vector<Eigen::Vector3d> pin_positions_;

  // Contact: the owned free vertices, their material areas, the mesh size, and
  // the friction anchors (in the body's frame) per body and mesh vertex.
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
  // force; infinite (a plain spring) unless contact.bounded_friction.
  static double friction_bound(const FrictionAnchor& anchor, const contact::Friction& friction,
                               bool bounded) {
    if (!bounded || std::isinf(anchor.normal_force)) return std::numeric_limits<double>::infinity();
    return (anchor.sliding ? friction.kinetic_coefficient : friction.static_coefficient) *
           anchor.normal_force;
  }
  void set_up_contact();
  // The clock of body motions: like the pin histories', the load factor in
  // statics and `time` when time stepping (pins_follow_time).
  double contact_clock() const { return pins_follow_time ? time : load_factor; }
  double contact_stiffness(int vertex) const;
  contact::PointResult vertex_contact(std::size_t body, int vertex, const Eigen::Vector3d& x,
                                      element::Want want) const;
  // The contact terms of every owned free vertex, added to local arrays.
  double contact_energy(const PetscScalar* x) const;
  void add_contact_forces(const PetscScalar* x, PetscScalar* f) const;
  PetscErrorCode add_contact_jacobian(const PetscScalar* x, Mat J) const;
  // The step bound of one vertex moving from p by `motion` past `body`.
  double vertex_step_bound(std::size_t body, const Eigen::Vector3d& p,
                           const Eigen::Vector3d& motion) const;
  std::vector<int> contact_vertices_;
  std::vector<double> vertex_area_;
  double mesh_size_ = 0.0;
  std::vector<std::vector<FrictionAnchor>> anchors_;
  // The anchors before the last update: those the last solved state is in
  // equilibrium with, for the reported friction forces.
  std::vector<std::vector<FrictionAnchor>> solved_anchors_;
  bool solved_bounded_ = false; // contact.bounded_friction of that solve
  std::vector<long> sliding_;
  // Per body and mesh vertex, the last place it was queried at and its
  // signed distance there. The distance moves no faster than the body's
  // slope bound times the point, so a vertex that has moved less than
  // (distance - offset) / slope bound since, on the same clock, is still out
  // of contact: energy, residual and Jacobian skip its
  // query (most of a garment, most of the time; the mannequin's query is
  // the costliest part of an evaluation).
  struct QueriedPlace {
    Eigen::Vector3d point = Eigen::Vector3d::Zero();
    double distance = -1.0; // m; below the offset: query again
    double clock = 0.0;
  };
  mutable std::vector<std::vector<QueriedPlace>> queried_;
  bool surely_apart(std::size_t body, int vertex, const Eigen::Vector3d& x) const;

  // Edge contact (cloth_edge_contact.cpp): the sample point at parameter s
  // of the edge from mesh vertex a to b, on the edges this rank assembles.
  struct EdgeSample {
    int a, b;
    double s;
  };
  // Built on first use, again when the spacing setting changes.
  const std::vector<EdgeSample>& edge_samples() const;
  double edge_sample_stiffness(const EdgeSample& sample) const;
  contact::EdgeSampleResult edge_sample_contact(std::size_t body, std::size_t index,
                                                const PetscScalar* x, element::Want want) const;
  double edge_contact_energy(const PetscScalar* x) const;
  void add_edge_contact_forces(const PetscScalar* x, PetscScalar* f) const;
  PetscErrorCode add_edge_contact_jacobian(const PetscScalar* x, Mat J) const;
  // The largest t in (0, 1] no sample point bounds the step at (as vertices).
  double edge_step_bound(const PetscScalar* x, const PetscScalar* motions) const;
  // Collective: per mesh vertex (those local to this rank), the normal
  // forces of `body` on the samples of its edges, shared by the lever rule.
  PetscErrorCode edge_sample_loads(std::size_t body, const PetscScalar* x,
                                   std::vector<Eigen::Vector3d>* per_vertex);
  // Adds the samples' normal force, count in contact and deepest depth.
  void add_edge_contact_report(std::size_t body, const PetscScalar* x, double normal_force[3],
                               double* contacting, double* deepest) const;
  mutable std::vector<EdgeSample> edge_samples_;
  mutable double edge_samples_spacing_ = -1.0;
  mutable std::vector<std::vector<QueriedPlace>> sample_queried_; // per body and sample
};

} // namespace sartor
