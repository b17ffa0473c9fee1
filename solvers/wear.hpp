#pragma once
// A garment worn for hours, then taken off (docs/wear.md).
//
// Wear: from a static drape, the creep loop of solvers/creep_analysis.hpp runs
// over real time on the worn problem (body contact with friction, seams,
// per-panel fabrics each with its creep parameters per direction): adaptive
// steps from seconds to hours, each a static solve warm-started from the last
// state, the creep state of every triangle advanced after it (staggered) or
// inside it (monolithic). The body may change over time: a TimedShape is
// queried at the problem's clock, so a pose history plugs in as a shape.
//
// Take-off, at given wear times: the garment is hung by its held vertices
// (the waistband: the vertices near the top of the draped garment, at their
// draped places) with the body removed, under its own weight, and recovers
// for a given time (viscoelastic strain decaying with lambda_unload towards
// what the small hanging tension sustains; permanent strain stays). It is
// compared with the fresh garment (no creep) hung the same way: the hem
// drop and the bagging height are the recovered garment's displacement
// from the fresh one.
//
// Hung, not laid on a plane: the held vertices remove the rigid motions, so
// the take-off equilibrium is unique and certifiable; a garment laid on a
// frictionless plane keeps its in-plane rigid motions and, without
// cloth-cloth contact, folds through itself. Hanging by the waist is also
// how hem drop is judged.

#include "contact/shape.hpp"
#include "fem/cloth_problem.hpp"
#include "fem/creep_coupling.hpp"
#include "solvers/certificate.hpp"
#include "solvers/creep_analysis.hpp"

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace sartor {

// A body whose shape changes with time (a mannequin following a pose
// history: joint angles over time), in its own frame.
class TimedShape {
public:
  virtual ~TimedShape() = default;
  virtual contact::SurfaceQuery query(const Eigen::Vector3d& p, double time) const = 0;
  // Only what `needs` asks for, as contact::Shape::partial_query.
  virtual contact::SurfaceQuery partial_query(const Eigen::Vector3d& p, double time,
                                              contact::QueryNeeds /*needs*/) const {
    return query(p, time);
  }
  virtual std::string describe() const = 0;
  virtual double slope_bound() const { return 1.0; }
  // The surface's reference frame at `time`, as contact::Shape's (the
  // identity unless the surface moves in the shape's frame).
  virtual Eigen::Vector3d to_reference(const Eigen::Vector3d& p, double /*time*/) const {
    return p;
  }
  virtual Eigen::Vector3d from_reference(const Eigen::Vector3d& q, double /*time*/) const {
    return q;
  }
  virtual Eigen::Vector3d direction_to_reference(const Eigen::Vector3d& /*p*/,
                                                 const Eigen::Vector3d& d, double /*time*/) const {
    return d;
  }
  virtual Eigen::Vector3d direction_from_reference(const Eigen::Vector3d& /*q*/,
                                                   const Eigen::Vector3d& d,
                                                   double /*time*/) const {
    return d;
  }
  // Times where the shape's history has knots: the wear steps land on them.
  virtual std::vector<double> knots() const { return {}; }
};

// A TimedShape as a contact::Shape at the time `*clock` holds (a
// ClothProblem's time: the creep loop sets it to each step's end time
// before solving, and the contact cache is keyed on it).
class ShapeOnClock : public contact::Shape {
public:
  ShapeOnClock(std::shared_ptr<const TimedShape> shape, const double* clock)
      : shape_(std::move(shape)), clock_(clock) {}
  contact::SurfaceQuery query(const Eigen::Vector3d& p) const override {
    return shape_->query(p, *clock_);
  }
  contact::SurfaceQuery partial_query(const Eigen::Vector3d& p,
                                      contact::QueryNeeds needs) const override {
    return shape_->partial_query(p, *clock_, needs);
  }
  std::string describe() const override { return shape_->describe(); }
  double slope_bound() const override { return shape_->slope_bound(); }
  Eigen::Vector3d to_reference(const Eigen::Vector3d& p) const override {
    return shape_->to_reference(p, *clock_);
  }
  Eigen::Vector3d from_reference(const Eigen::Vector3d& q) const override {
    return shape_->from_reference(q, *clock_);
  }
  Eigen::Vector3d direction_to_reference(const Eigen::Vector3d& p,
                                         const Eigen::Vector3d& d) const override {
    return shape_->direction_to_reference(p, d, *clock_);
  }
  Eigen::Vector3d direction_from_reference(const Eigen::Vector3d& q,
                                           const Eigen::Vector3d& d) const override {
    return shape_->direction_from_reference(q, d, *clock_);
  }

private:
  std::shared_ptr<const TimedShape> shape_;
  const double* clock_;
};

// A limb bent at a joint: two capsules of one radius, the upper from
// `shoulder` to `joint`, the lower from `joint` along `straight` (the
// forearm's or shin's direction when straight, unit) rotated about
// `hinge_axis` through the joint by an angle going piecewise linearly
// through `angle_knots` (time s, angle rad). The distance is the smaller of
// the two capsules' (exact outside both, a kink on the bisecting plane).
class BentLimb : public TimedShape {
public:
  BentLimb(Eigen::Vector3d shoulder, Eigen::Vector3d joint, Eigen::Vector3d straight,
           double lower_length, double radius, Eigen::Vector3d hinge_axis,
           std::vector<std::pair<double, double>> angle_knots);
  contact::SurfaceQuery query(const Eigen::Vector3d& p, double time) const override;
  std::string describe() const override;
  std::vector<double> knots() const override;
  double angle(double time) const;

private:
  Eigen::Vector3d shoulder_, joint_, straight_, axis_;
  double lower_length_, radius_;
  std::vector<std::pair<double, double>> knots_;
};

// What the take-off needs to rebuild the garment without the body.
struct WearGarment {
  std::vector<ClothMaterial> materials; // per mesh material id, as the worn problem's
  std::vector<CreepMaterial> creep;     // per mesh material id
  std::vector<SeamSpring> springs;      // the worn problem's seams
  Eigen::Vector3d gravity = Eigen::Vector3d::Zero();
  std::vector<int> held;    // vertices held at take-off (mesh numbering)
  std::vector<int> hem;     // vertices whose mean height is the hem height
  std::vector<int> bagging; // vertices where the bagging height is measured (empty: all)
  // Cloth self-contact of the take-off's hanging garment (as the worn one's):
  // a trouser leg's front and back collapse onto each other there.
  fem::SelfContactSettings self_contact;
};

struct WearOptions {
  CreepOptions wear;                  // time_end: the wear time; its scheme is the recovery's too
  std::vector<double> take_off_times; // s, increasing, within (0, wear.time_end]
  double recovery_time = 3600.0;      // s
  bool certify_steps = true;          // certify every accepted wear step (no inertia check)
  // More times the steps land on: a moving body's knots (TimedShape::knots).
  std::vector<double> landings;
};

// One take-off: the garment after `recovery_time` hanging, against the fresh one.
struct TakeOffReport {
  double wear_time = 0.0;                 // s, when the body was removed
  bool converged = false;                 // the hanging equilibrium and recovery
  std::string reason;                     // when not
  double hem_height = 0.0;                // m, mean height of the hem vertices, recovered
  double hem_drop = 0.0;                  // m, fresh hem height minus recovered (> 0: dropped)
  double bagging_height = 0.0;            // m, largest displacement normal to the fresh surface
  long bagging_vertex = -1;               // where
  double dome_height = 0.0;               // m, permanent_dome_height over the bagging region
  double excess_area = 0.0;               // m^2, the permanent strains' added area there
  double max_permanent = 0.0;             // largest permanent strain of any triangle and direction
  double max_viscoelastic = 0.0;          // left after the recovery
  PetscInt newton_iterations = 0;         // of the hanging solve and the recovery
  long recovery_steps = 0;                // accepted
  long rejected_steps = 0;                // of the recovery
  long saddle_escapes = 0;                // pushes off a saddle the hanging stopped in
  Certificate certificate;                // of the recovered state
  std::vector<Eigen::Vector3d> positions; // recovered (rank 0)
  std::vector<ElementCreep> creep;        // recovered state (rank 0)
};

struct WearStep {
  CreepStepReport step;
  double hem_height = 0.0;  // m, on the body
  double max_elastic = 0.0; // largest elastic strain of any triangle and direction
  double max_viscoelastic = 0.0;
  double max_permanent = 0.0;
  // m: the permanent dome height of the bagging region in the worn creep
  // state (TakeOffReport::dome_height; it depends on the creep state alone).
  double dome_height = 0.0;
  bool certified = false; // the step's certificate (without the inertia check)
  // Its verdict ("certified", or the first failed check); "" when steps are
  // not certified (--no-step-certificate).
  std::string verdict;
};

struct WearReport {
  CreepReport wear;
  std::vector<WearStep> steps;
  long certified_steps = 0;
  double fresh_hem_height = 0.0; // m, the fresh garment hung
  bool fresh_converged = false;
  std::vector<Eigen::Vector3d> fresh_positions; // rank 0
  std::vector<TakeOffReport> take_offs;
  Certificate final_certificate; // the worn state at the end of the wear, with inertia
};

// Called collectively with each accepted wear state (the initial one too).
using WearObserver =
    std::function<void(ClothProblem& problem, Vec x, const CreepCoupling& creep, double time)>;

// Where a wear resumes from, and its checkpoints (docs/reliability.md).
struct WearRestart {
  // The worn state after an accepted wear step (time, step, next step,
  // positions, creep, friction anchors), and what the wear had done by then
  // (its steps and take-offs) with the contact stiffness scale it had.
  const RunCheckpoint* resume = nullptr;
  const WearReport* resumed = nullptr;
  double contact_stiffness_scale = 1.0;
  // Collective, after every accepted wear step (and its take-off, if any):
  // writes a checkpoint of x, the report so far, the next step size.
  std::function<PetscErrorCode(ClothProblem& worn, Vec x, const CreepCoupling& creep,
                               const CreepStepReport& step, double next_step,
                               const WearReport& report)>
      write;
};

// Collective. `worn`: the draped problem, x its static equilibrium (advanced
// in place to the end of the wear). The garment taken off is measured
// against the fresh garment hung from x, so a resumed wear passes the same
// draped x. Throws InputError for bad options.
PetscErrorCode solve_wear(ClothProblem& worn, Vec x, const WearGarment& garment,
                          const WearOptions& options, WearReport* report,
                          const WearObserver& observe = {}, const WearRestart& restart = {});

// Mean height of `vertices` (positions in mesh numbering), m.
double mean_height(const std::vector<Eigen::Vector3d>& positions, const std::vector<int>& vertices);

// The largest |(recovered - fresh) . n| over `vertices` (all when empty), n
// the fresh surface's unit vertex normal (area-weighted triangle normals, the
// triangles' orientation made consistent within each panel by the material
// coordinates); returns the vertex through `where`.
double bagging_height(const TriangleMesh& mesh, const std::vector<Eigen::Vector3d>& fresh,
                      const std::vector<Eigen::Vector3d>& recovered,
                      const std::vector<int>& vertices, long* where);

// The permanent stretch of a region as the dome it would bulge into: the
// area the permanent strains add to the triangles whose corners are all in
// `vertices` (all triangles when empty), sum of A (1 + ep_warp)(1 + ep_weft)
// - A over their material areas A, returned through `excess_area` (m^2), and
// the height sqrt(excess / pi) of the spherical cap that adds that area to
// the flat disk under it (a cap of height h over a disk of radius a has area
// pi (a^2 + h^2), whatever a). It depends on the creep state alone, not on
// where a hung garment folds. m.
double permanent_dome_height(const TriangleMesh& mesh, const std::vector<ElementCreep>& states,
                             const std::vector<int>& vertices, double* excess_area);

} // namespace sartor
