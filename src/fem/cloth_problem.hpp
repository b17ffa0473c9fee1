#pragma once
// A cloth on PETSc: the triangle mesh as a distributed DMPlex with three
// position dofs per vertex, pinned vertices as section constraints, and the
// discrete problem as a sum of energy forms (fem/form.hpp): energy, residual
// and Jacobian are the sums of the forms' values, gradients and Hessians.
//
// The unknowns are the vertex positions x (not displacements). The residual
// is F(x) = grad E(x) - f_ext(x): membrane and bending energies minus gravity,
// point forces and follower pressure, the loads scaled by a load factor, plus
// contact, friction and seams. The forms, in the order they are summed:
// membrane and surface loads (per triangle), bending (hinges or patches),
// point loads, contact, the forms added by add_form, and seams.
//
// Every rank holds the whole TriangleMesh (it is the serial front end's
// output); the DMPlex decides which triangles each rank assembles. Results
// are gathered in the mesh's own vertex and triangle numbering, so they do not
// depend on the number of ranks.

#include "contact/body.hpp"
#include "element/bending.hpp"
#include "element/membrane.hpp"
#include "element/patch_bending.hpp"
#include "fem/cloth_model.hpp"
#include "fem/cloth_output.hpp"
#include "fem/form.hpp"
#include "fem/forms/seam_coupling.hpp"
#include "fem/forms/self_contact_form.hpp"
#include "fem/pin_motion.hpp"
#include "mesh/triangle_mesh.hpp"

#include <petscdmplex.h>
#include <petscmat.h>
#include <petscsf.h>

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace sartor {

namespace fem {
struct BlockLayout;
class ContactForm;
class SeamForm;
struct SeamDesign;
} // namespace fem

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
  // When set (a monolithically coupled creep step), the creep coupling form
  // stands in for the membrane form: residual and Jacobian take each
  // triangle's non-elastic strains from it instead of `nonelastic`, and the
  // Jacobian includes their dependence on the positions (then there is no
  // potential energy).
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
  // The times at which what is prescribed changes course, which time steps
  // end on: the knots of the pin groups' and the bodies' motions and the
  // pins' release times (unsorted, repeats kept).
  std::vector<double> event_times() const;
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
  // Moves every friction anchor to its vertex's level at x, keeping its
  // spring's tangential stretch: how anchors are placed once
  // contact.friction_plane_at_vertex is on (anchors placed on the surface
  // below a vertex held off it, 5 mm under the coarse skirt's hips, would
  // change their force by the plane's turn over that height).
  PetscErrorCode level_friction_anchors(Vec x);
  // Per body, the forces on the cloth and the contact state at x, the
  // friction forces from the anchors the solve used (before the last update).
  PetscErrorCode contact_report(Vec x, std::vector<BodyContact>* report);
  // Collective. Per-vertex loads at x, in mesh numbering, on rank 0 (empty
  // elsewhere), for the result files (fem/cloth_vertex_loads.cpp): with bodies,
  // contact_pressure (Pa), contact_normal_force and friction_force (N) and
  // friction_utilisation |f_t| / (mu_s |f_n|) (1: on the Coulomb cone; f_n
  // with the vertex's share of the edge samples' normal force); with
  // seams, seam_force (N).
  PetscErrorCode gather_vertex_loads(Vec x, std::vector<ClothNodeField>* fields);
  // Collective. The largest t in (0, 1] such that no vertex moving from x
  // towards x + t d comes closer to a body than the smaller of half its
  // distance at x and a tenth of the contact offset, found by conservative advancement
  // on the signed distance and the shape's slope bound (IPC's CCD filter,
  // with the body's distance in place of CCD). Vertices already inside a
  // body (d <= 0) do not bound the step: the penalty pushes them out. With
  // self-contact, no vertex-triangle pair comes closer than the same
  // fraction of its distance (SelfContactForm::step_bound) either.
  PetscErrorCode contact_step_bound(Vec x, Vec direction, double* bound);
  // What push_out_of_bodies did (every rank): the vertices pushed, the
  // deepest (m), and the body queries asked (one per vertex and body, less
  // those the body's bone intervals place outside).
  struct PushOut {
    long pushed = 0;
    double deepest = 0.0;
    long queries = 0;
  };
  // Collective. The thesis' penetration handling before a solve (ch. 4,
  // Alg. 1): every vertex inside a body at the contact clock is moved out
  // along the body's normal to the middle of the contact offset layer. A
  // body with bone intervals (contact/bone_intervals.hpp) is asked only
  // about the vertices its index does not place outside by more than the
  // contact offset. For a start the bodies have moved into (a limb bending
  // into its trouser leg, a linear prediction through the body): from
  // inside, the penalty's force is its stiffness times the depth, far more
  // than the cloth can carry.
  PetscErrorCode push_out_of_bodies(Vec x, PushOut* report);
  // Collective. Sets `time` to `to`, and carries the cloth near the bodies
  // along with them: a vertex at distance d from a body moves by 1 - d /
  // `reach` (none beyond it, all of it on the surface) of the body's motion
  // of its nearest point's frame (contact::Body::anchor_from_world at the
  // old time, anchor_to_world at the new). A limb that moves starts the
  // step's solve with its cloth where it took it, not inside it.
  PetscErrorCode carry_with_bodies(Vec x, double to, double reach);

  // Seam springs (mesh/seams.hpp) between any vertices of the mesh, on any
  // ranks (fem/forms/seam_coupling.hpp). Collective, with the same springs on every
  // rank; call before create_jacobian. Energy, residual, Jacobian and pin
  // reaction include them.
  void set_seams(const std::vector<SeamSpring>& springs);
  // The springs seam_springs builds from `seams` (returned); these (unlike
  // given springs) have an exact rest derivative once sewn.
  std::vector<SeamSpring> set_seams(const std::vector<Seam>& seams, const SeamStiffness& stiffness);
  const SeamCoupling* seam_coupling() const;
  // Cloth self-contact (fem/forms/self_contact_form.hpp), after the seams
  // (sewn vertices are near each other) and before create_jacobian.
  // Collective. Throws InputError for an offset or stiffness that is not
  // positive and finite.
  void set_self_contact(const fem::SelfContactSettings& settings);
  bool has_self_contact() const { return self_contact_form_ != nullptr; }
  // The settings it was set with (not enabled without it).
  fem::SelfContactSettings self_contact_settings() const {
    return self_contact_form_ ? self_contact_form_->settings() : fem::SelfContactSettings{};
  }
  // Collective: the self-contact pairs of the Jacobian's structure at x;
  // `changed`: the structure differs, create the Jacobian again. Without
  // self-contact, never changed.
  PetscErrorCode refresh_couplings(Vec x, bool* changed);
  // Counts the changes of that structure (the same on every rank): a
  // Jacobian created at another count lacks pairs that are now assembled.
  long coupling_version() const { return self_contact_form_ ? self_contact_form_->refreshes() : 0; }
  // Collective: a Jacobian since the last refresh left out a pair in
  // contact (refresh and assemble again for the exact Hessian).
  PetscErrorCode couplings_stale(bool* stale) const;
  // Collective: self-contact at x (zeros without it).
  PetscErrorCode self_contact_report(Vec x, fem::SelfContactReport* report);
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
  // Statics sew by continuation instead (solvers/statics.hpp): `sewing_stage`
  // is the progress of the stage being solved, 0 to 1; below 1 the bodies
  // have no friction.
  double sewing_tension = 0.0;
  double sewing_end_time = 0.0;
  double sewing_stage = 1.0;
  bool sewing() const {
    if (sewing_tension <= 0.0) return false;
    return pins_follow_time ? time <= sewing_end_time : sewing_stage < 1.0;
  }
  // The seam springs' sewing progress of this moment, 0 to 1 (1: sewn).
  double sewing_progress() const {
    if (!sewing()) return 1.0;
    return pins_follow_time ? time / sewing_end_time : sewing_stage;
  }
  // The clock of body motions: like the pin histories', the load factor in
  // statics and `time` when time stepping (pins_follow_time).
  double contact_clock() const { return pins_follow_time ? time : load_factor; }
  // The place of every pin now (its position, pin_motion and pin_groups).
  PetscErrorCode pin_places(std::vector<Eigen::Vector3d>* places) const;

  // A further term of the energy (fem/form.hpp), summed after the built-in
  // ones (before the seams); add it before create_jacobian, whose
  // preallocation reads its elements. Collective: every rank adds its own.
  void add_form(std::unique_ptr<fem::Form> form);
  // For forms on vertices: whether this rank owns mesh vertex v (each owned
  // vertex's terms are assembled once, by its owner), and the offset of its
  // first dof in the local arrays of fem::FormPoint (-1: not local).
  bool owns_vertex(int v) const { return vertex_owned_[std::size_t(v)]; }
  PetscInt vertex_offset(int v) const { return vertex_dof_[std::size_t(v)]; }
  // Collective. The design sensitivity's mixed derivative dR/dX dX at x:
  // the change of the residual when the material coordinates move by
  // `change` (per mesh triangle corner), at fixed positions, summed from
  // the enabled forms' exact derivatives (fem/form.hpp). Fails (PETSc error
  // PETSC_ERR_SUP) when an enabled form has none: solvers/sensitivity.hpp
  // differentiates rebuilt problems instead.
  PetscErrorCode rest_derivative(Vec x, const RestChange& change, Vec derivative);
  // Whether every enabled form has a rest derivative (in the problem's
  // present state: seams being sewn have none).
  bool has_rest_derivative() const;
  // The forms' names, in the order they are summed.
  std::vector<std::string> form_names() const;
  // Leaves the form of that name out of energy, residual and Jacobian, or
  // puts it back (tests of one term, studies of a term's share). Throws
  // InputError for a name that is not a form's.
  void enable_form(const std::string& name, bool enabled);

  PetscErrorCode residual(Vec x, Vec f);
  PetscErrorCode jacobian(Vec x, Mat J);
  // The Jacobian without the PSD projections the materials and contact ask
  // for: the true Hessian, whose inertia certifies stability
  // (solvers/certificate.hpp), and which the static minimiser tries near a
  // solution, where the projected one converges only linearly.
  bool exact_hessian = false;
  bool projects_hessians() const;
  PetscErrorCode energy(Vec x, ClothEnergy* energy);
  // Preallocated exactly for the element couplings (membrane and hinges).
  PetscErrorCode create_jacobian(Mat* J);
  // The residual is the gradient of energy(): no pressure on a surface with
  // a free edge, no position-dependent unloaded lengths.
  bool has_potential() const;
  // The Jacobian is symmetric: the Hessian of a potential, on the free dofs
  // (pinned vertices are section constraints), with no releasable pin
  // (whose rows replace_held_rows replaces). Only its upper triangle need
  // be factorised. The same on every rank.
  bool symmetric_jacobian() const;

  // All vertex positions, in mesh numbering, on rank 0 (empty elsewhere).
  PetscErrorCode gather_positions(Vec x, std::vector<Eigen::Vector3d>* positions);
  // The same on every rank. Collective.
  PetscErrorCode positions_everywhere(Vec x, std::vector<Eigen::Vector3d>* positions);
  // Per body, in mesh numbering, on rank 0 (empty elsewhere): the normal
  // forces of its edge samples at x shared to the edges' vertices by the
  // lever rule, and the force of its own contact with each vertex (penalty
  // and friction anchor, not the edge samples).
  PetscErrorCode gather_body_vertex_forces(Vec x,
                                           std::vector<std::vector<Eigen::Vector3d>>* sample_loads,
                                           std::vector<std::vector<Eigen::Vector3d>>* own_contact);
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
  // Collective. All ranks' anchor rows on every rank (to restore them on
  // another problem, or later on this one).
  PetscErrorCode anchors_everywhere(std::vector<AnchorRow>* rows);
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
  // Each vertex's index in the pin list, -1 when free.
  std::vector<int> pin_indices() const;
  // Collective: each free vertex's first global dof, -1 when pinned (every rank).
  std::vector<PetscInt> first_global_dofs(const std::vector<int>& pin_index) const;
  // set_seams' work; `design`: where the springs came from, or null.
  void set_up_seams(const std::vector<SeamSpring>& springs,
                    std::unique_ptr<fem::SeamDesign> design);
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
  void set_up_dofs(const std::vector<PetscInt>& original, const std::vector<bool>& foreign,
                   const std::vector<bool>& is_pinned);
  std::vector<bool> set_up_triangles(const std::vector<PetscInt>& original,
                                     const std::vector<bool>& foreign);
  void set_up_bending(const std::vector<bool>& triangle_owned, const std::vector<bool>& is_pinned);
  const ClothMaterial& triangle_material(std::size_t triangle) const;
  // The forms at the local positions `x` (fem/form.hpp).
  fem::FormPoint form_point(const PetscScalar* x) const { return {x, load_factor, exact_hessian}; }
  fem::TriangleView triangle_view(const LocalTriangle& t, const element::Vector9& x) const {
    return {t.index, *t.material, t.rest, mesh_.material_uv[std::size_t(t.index)], x};
  }
  PetscErrorCode triangle_hessians(const fem::FormPoint& at, fem::ElementHessians& out) const;
  PetscErrorCode register_elements(fem::ElementRegistry& registry) const;
  // The largest initial modulus of any material, N/m.
  double largest_modulus() const;

  PetscErrorCode to_local(Vec x);
  // Jacobian assembly without column searches (fem/block_assembly.hpp).
  PetscErrorCode attach_element_scatter(const fem::BlockLayout& layout, Mat J) const;

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
  std::vector<Eigen::Vector3d> pin_positions_;
  // The energy forms, in the order they are summed; the contact and seam
  // forms also answer the problem's contact and seam reports.
  std::vector<std::unique_ptr<fem::TriangleForm>> triangle_forms_;
  std::vector<std::unique_ptr<fem::Form>> forms_;
  std::vector<std::unique_ptr<fem::CouplingForm>> coupling_forms_;
  fem::ContactForm* contact_form_ = nullptr;
  fem::SeamForm* seam_form_ = nullptr;
  fem::SelfContactForm* self_contact_form_ = nullptr;
  std::vector<std::pair<int, int>> seam_links_; // sewn vertex pairs, for self-contact
  std::vector<std::string> disabled_forms_;
  // Whether enable_form left out the form of that name.
  bool disabled(const char* name) const {
    return std::find(disabled_forms_.begin(), disabled_forms_.end(), name) != disabled_forms_.end();
  }
  // The forms of `all` that are enabled and active (fem/form.hpp).
  template <class F>
  std::vector<F*> enabled(const std::vector<std::unique_ptr<F>>& all) const;
};

} // namespace sartor
