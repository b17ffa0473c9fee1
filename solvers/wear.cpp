#include "solvers/wear.hpp"

#include "common/error.hpp"
#include "contact/analytic_shapes.hpp"
#include "solvers/statics.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace sartor {

BentLimb::BentLimb(Eigen::Vector3d shoulder, Eigen::Vector3d joint, Eigen::Vector3d straight,
                   double lower_length, double radius, Eigen::Vector3d hinge_axis,
                   std::vector<std::pair<double, double>> angle_knots)
    : shoulder_(std::move(shoulder)), joint_(std::move(joint)), straight_(straight.normalized()),
      axis_(hinge_axis.normalized()), lower_length_(lower_length), radius_(radius),
      knots_(std::move(angle_knots)) {
  if (!(radius > 0.0) || !(lower_length > 0.0)) {
    throw InputError("bent limb: the radius and the lower length must be positive");
  }
  for (std::size_t k = 1; k < knots_.size(); ++k) {
    if (!(knots_[k].first > knots_[k - 1].first)) {
      throw InputError("bent limb: the angle history's times must increase");
    }
  }
}

double BentLimb::angle(double time) const {
  if (knots_.empty()) return 0.0;
  if (time <= knots_.front().first) return knots_.front().second;
  if (time >= knots_.back().first) return knots_.back().second;
  const auto after = std::upper_bound(knots_.begin(), knots_.end(), time,
                                      [](double t, const auto& knot) { return t < knot.first; });
  const auto before = after - 1;
  const double s = (time - before->first) / (after->first - before->first);
  return (1.0 - s) * before->second + s * after->second;
}

contact::SurfaceQuery BentLimb::query(const Eigen::Vector3d& p, double time) const {
  const Eigen::Vector3d lower =
      Eigen::AngleAxisd(angle(time), axis_).toRotationMatrix() * straight_ * lower_length_;
  const contact::SurfaceQuery upper_query = contact::Capsule(shoulder_, joint_, radius_).query(p);
  const contact::SurfaceQuery lower_query =
      contact::Capsule(joint_, joint_ + lower, radius_).query(p);
  return upper_query.distance <= lower_query.distance ? upper_query : lower_query;
}

std::string BentLimb::describe() const {
  std::ostringstream out;
  out << "bent limb radius=" << radius_ << " lower length=" << lower_length_ << " ("
      << knots_.size() << " angle knots)";
  return out.str();
}

std::vector<double> BentLimb::knots() const {
  std::vector<double> times;
  for (const auto& knot : knots_)
    times.push_back(knot.first);
  return times;
}

double mean_height(const std::vector<Eigen::Vector3d>& positions,
                   const std::vector<int>& vertices) {
  if (vertices.empty() || positions.empty()) return 0.0;
  double sum = 0.0;
  for (int v : vertices)
    sum += positions[std::size_t(v)].z();
  return sum / double(vertices.size());
}

double bagging_height(const TriangleMesh& mesh, const std::vector<Eigen::Vector3d>& fresh,
                      const std::vector<Eigen::Vector3d>& recovered,
                      const std::vector<int>& vertices, long* where) {
  std::vector<Eigen::Vector3d> normal(fresh.size(), Eigen::Vector3d::Zero());
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    const auto& tri = mesh.triangles[t];
    const auto& uv = mesh.material_uv[t];
    const Eigen::Vector2d a = uv[1] - uv[0], b = uv[2] - uv[0];
    const double orientation = a.x() * b.y() - a.y() * b.x() >= 0.0 ? 1.0 : -1.0;
    const Eigen::Vector3d n =
        orientation * (fresh[std::size_t(tri[1])] - fresh[std::size_t(tri[0])])
                          .cross(fresh[std::size_t(tri[2])] - fresh[std::size_t(tri[0])]);
    for (int c : tri)
      normal[std::size_t(c)] += n;
  }
  double largest = 0.0;
  *where = -1;
  const auto visit = [&](std::size_t v) {
    const double length = normal[v].norm();
    if (length == 0.0) return;
    const double height = std::abs((recovered[v] - fresh[v]).dot(normal[v] / length));
    if (height > largest) {
      largest = height;
      *where = long(v);
    }
  };
  if (vertices.empty()) {
    for (std::size_t v = 0; v < fresh.size(); ++v)
      visit(v);
  } else {
    for (int v : vertices)
      visit(std::size_t(v));
  }
  return largest;
}

double permanent_dome_height(const TriangleMesh& mesh, const std::vector<ElementCreep>& states,
                             const std::vector<int>& vertices, double* excess_area) {
  std::vector<bool> in_region(mesh.positions.size(), vertices.empty());
  for (int v : vertices)
    in_region[std::size_t(v)] = true;
  double excess = 0.0;
  for (std::size_t t = 0; t < states.size(); ++t) {
    const auto& tri = mesh.triangles[t];
    if (!(in_region[std::size_t(tri[0])] && in_region[std::size_t(tri[1])] &&
          in_region[std::size_t(tri[2])]))
      continue;
    excess += material_area(mesh.material_uv[t]) *
              ((1.0 + states[t].warp.permanent) * (1.0 + states[t].weft.permanent) - 1.0);
  }
  *excess_area = excess;
  return std::sqrt(std::max(0.0, excess) / M_PI);
}

namespace {

PetscErrorCode broadcast(MPI_Comm comm, std::vector<double>* values) {
  PetscFunctionBeginUser;
  unsigned long size = values->size();
  PetscCallMPI(MPI_Bcast(&size, 1, MPI_UNSIGNED_LONG, 0, comm));
  values->resize(size);
  PetscCallMPI(MPI_Bcast(values->data(), int(size), MPI_DOUBLE, 0, comm));
  PetscFunctionReturn(0);
}

// The committed creep state of every triangle on every rank.
PetscErrorCode creep_everywhere(MPI_Comm comm, const CreepCoupling& creep,
                                std::vector<ElementCreep>* states) {
  PetscFunctionBeginUser;
  PetscCall(creep.gather(states));
  std::vector<double> flat = creep_rows(*states);
  PetscCall(broadcast(comm, &flat));
  *states = creep_from_rows(flat);
  PetscFunctionReturn(0);
}

double largest_permanent(const std::vector<ElementCreep>& states) {
  double largest = 0.0;
  for (const ElementCreep& s : states)
    largest = std::max({largest, s.warp.permanent, s.weft.permanent});
  return largest;
}

double largest_viscoelastic(const std::vector<ElementCreep>& states) {
  double largest = 0.0;
  for (const ElementCreep& s : states)
    largest = std::max({largest, s.warp.viscoelastic, s.weft.viscoelastic});
  return largest;
}

void check(const WearGarment& garment, const WearOptions& options) {
  if (garment.held.empty()) {
    throw InputError("wear: no vertex is held at take-off (the garment would fall)");
  }
  if (!(options.recovery_time > 0.0)) {
    throw InputError("wear: the recovery time must be positive");
  }
  double last = 0.0;
  for (double t : options.take_off_times) {
    if (!(t > last) || t > options.wear.time_end) {
      throw InputError("wear: take-off times must increase within (0, " +
                       std::to_string(options.wear.time_end) + "] s, got " + std::to_string(t));
    }
    last = t;
  }
  if (!options.wear.load.empty()) {
    throw InputError("wear: the garment's weight is not ramped in time (no load history)");
  }
}

// The garment without the body, hung by its held vertices at their draped
// places: one problem for the fresh garment and every take-off.
class Hanger {
public:
  Hanger(MPI_Comm comm, const TriangleMesh& worn_mesh, const std::vector<Eigen::Vector3d>& draped,
         const WearGarment& garment)
      : mesh_(with_positions(worn_mesh, draped)), garment_(garment),
        problem_(comm, mesh_, garment.materials, garment.held), creep_(problem_, garment.creep) {
    problem_.loads.gravity = garment.gravity;
    if (!garment.springs.empty()) problem_.set_seams(garment.springs);
    if (garment.self_contact.enabled) problem_.set_self_contact(garment.self_contact);
  }

  // The fresh garment (no creep) hung: its positions on every rank.
  PetscErrorCode hang_fresh(const StaticOptions& solve, std::vector<Eigen::Vector3d>* fresh,
                            bool* converged) {
    Vec x = nullptr;
    PetscFunctionBeginUser;
    creep_.restore(std::vector<ElementCreep>(mesh_.triangle_count()));
    PetscCall(problem_.create_solution(&x));
    StaticReport report;
    PetscCall(solve_static(problem_, x, solve, &report));
    *converged = report.converged;
    PetscCall(problem_.positions_everywhere(x, fresh));
    PetscCall(VecDestroy(&x));
    PetscFunctionReturn(0);
  }

  // From the worn state at `time`, hung and recovering for the recovery time.
  PetscErrorCode take_off(double time, const std::vector<Eigen::Vector3d>& worn,
                          const std::vector<ElementCreep>& states, const WearOptions& options,
                          const std::vector<Eigen::Vector3d>& fresh, TakeOffReport* report) {
    Vec x = nullptr;
    PetscFunctionBeginUser;
    report->wear_time = time;
    creep_.restore(states);
    problem_.time = time;
    PetscCall(problem_.create_solution(&x));
    PetscCall(problem_.set_solution(worn, x));
    StaticReport hung;
    PetscCall(hang_worn(x, options.wear.equilibrium, &hung, &report->saddle_escapes));
    report->newton_iterations = hung.newton_iterations;
    if (hung.converged) {
      CreepOptions recovery = options.wear;
      recovery.time_end = time + options.recovery_time;
      recovery.output_interval = 0.0;
      recovery.print_progress = false;
      CreepReport solved;
      PetscCall(solve_creep(problem_, creep_, x, recovery, &solved));
      report->converged = solved.completed;
      report->reason = solved.reason;
      report->newton_iterations += solved.newton_iterations;
      report->recovery_steps = long(solved.steps.size()) - 1;
      report->rejected_steps = solved.rejected_steps;
    } else {
      report->reason = "the hanging did not converge (" + hung.reason + ")";
    }
    CertificateOptions certify_options;
    PetscCall(certify(problem_, x, certify_options, &report->certificate));
    std::vector<Eigen::Vector3d> recovered;
    PetscCall(problem_.positions_everywhere(x, &recovered));
    PetscCall(creep_everywhere(problem_.comm(), creep_, &report->creep));
    report->hem_height = mean_height(recovered, garment_.hem);
    report->hem_drop = mean_height(fresh, garment_.hem) - report->hem_height;
    report->bagging_height =
        bagging_height(mesh_, fresh, recovered, garment_.bagging, &report->bagging_vertex);
    report->dome_height =
        permanent_dome_height(mesh_, report->creep, garment_.bagging, &report->excess_area);
    report->max_permanent = largest_permanent(report->creep);
    report->max_viscoelastic = largest_viscoelastic(report->creep);
    report->positions = std::move(recovered);
    PetscCall(VecDestroy(&x));
    PetscFunctionReturn(0);
  }

private:
  // The worn garment hung from x (its creep state restored), the recovery's
  // first state. A hanging that ends in a saddle, or stops without
  // converging in one (a crumpled sleeve that could fold either way, where
  // the projected Hessian's steps crawl), is pushed along the true
  // Hessian's lowest mode by a hundredth of the garment's size and hung
  // again, at most max_saddle_escapes times (as --escape-saddles does for
  // a drape).
  PetscErrorCode hang_worn(Vec x, const StaticOptions& solve, StaticReport* hung, long* escapes) {
    PetscFunctionBeginUser;
    *escapes = 0;
    PetscCall(solve_static(problem_, x, solve, hung));
    StaticOptions again = solve;
    again.start_load_factor = problem_.load_factor;
    again.load_steps = 1;
    again.max_cutbacks = 0;
    while (*escapes < max_saddle_escapes) {
      bool pushed = false;
      PetscCall(push_off_saddle(problem_, x, CertificateOptions{}, 0.01 * garment_size(), &pushed));
      if (!pushed) break; // no direction of descent: not a saddle
      ++*escapes;
      StaticReport resolved;
      PetscCall(solve_static(problem_, x, again, &resolved));
      resolved.newton_iterations += hung->newton_iterations;
      *hung = resolved;
    }
    PetscFunctionReturn(0);
  }

  // The diagonal of the draped garment's bounding box, m.
  double garment_size() const {
    Eigen::AlignedBox3d box;
    for (const Eigen::Vector3d& p : mesh_.positions)
      box.extend(p);
    return box.isEmpty() ? 0.0 : box.diagonal().norm();
  }

  static constexpr long max_saddle_escapes = 3;

  static TriangleMesh with_positions(const TriangleMesh& mesh,
                                     const std::vector<Eigen::Vector3d>& positions) {
    TriangleMesh copy = mesh;
    copy.positions = positions;
    return copy;
  }

  TriangleMesh mesh_; // placed as draped: the held vertices' places
  const WearGarment& garment_;
  ClothProblem problem_;
  CreepCoupling creep_;
};

// The wear step's measures on the body, and its certificate (no inertia).
PetscErrorCode measure_step(ClothProblem& worn, Vec x, const CreepCoupling& creep,
                            const WearGarment& garment, bool certify_step, WearStep* step) {
  PetscFunctionBeginUser;
  std::vector<Eigen::Vector3d> positions;
  std::vector<element::MembraneStrain> strains;
  std::vector<ElementCreep> states;
  PetscCall(worn.positions_everywhere(x, &positions));
  PetscCall(worn.gather_strains(x, &strains));
  PetscCall(creep_everywhere(worn.comm(), creep, &states));
  step->hem_height = mean_height(positions, garment.hem);
  double elastic = 0.0;
  for (const element::MembraneStrain& s : strains)
    elastic = std::max({elastic, s.warp, s.weft});
  PetscCallMPI(MPI_Bcast(&elastic, 1, MPI_DOUBLE, 0, worn.comm()));
  step->max_elastic = elastic;
  step->max_viscoelastic = largest_viscoelastic(states);
  step->max_permanent = largest_permanent(states);
  double excess_area = 0.0;
  step->dome_height = permanent_dome_height(worn.mesh(), states, garment.bagging, &excess_area);
  if (certify_step) {
    CertificateOptions options;
    options.stability = false;
    Certificate certificate;
    PetscCall(certify(worn, x, options, &certificate));
    step->certified = certificate.certified();
    step->verdict = certificate.verdict();
  }
  PetscFunctionReturn(0);
}

// What the wear had done by the state it resumes from.
void resume_report(const WearRestart& restart, ClothProblem& worn, WearReport* report) {
  const WearReport& resumed = *restart.resumed;
  report->steps = resumed.steps;
  report->certified_steps = resumed.certified_steps;
  report->take_offs = resumed.take_offs;
  report->wear.newton_iterations = resumed.wear.newton_iterations;
  report->wear.rejected_steps = resumed.wear.rejected_steps;
  report->wear.steps.clear();
  for (const WearStep& step : resumed.steps)
    report->wear.steps.push_back(step.step);
  worn.contact.stiffness_scale = restart.contact_stiffness_scale;
}

// A wear step's friction is consistent at half the residual its
// certificate allows (a fraction of the weight): the friction anchors' fixed
// point converges only linearly (about halving per contact round while the
// cloth slides over a bending knee), and the equilibrium's own tolerance, a
// thousand times tighter, would cost ten more rounds a step, or cut the steps
// to milliseconds.
PetscErrorCode consistent_at_half_the_certified_residual(ClothProblem& worn, Vec x,
                                                         CreepOptions* wear) {
  PetscFunctionBeginUser;
  CertificateOptions options;
  options.stability = false;
  Certificate draped;
  PetscCall(certify(worn, x, options, &draped));
  wear->equilibrium.contact_tolerance = 0.5 * options.residual_tolerance * draped.reference_force;
  PetscFunctionReturn(0);
}

} // namespace

PetscErrorCode solve_wear(ClothProblem& worn, Vec x, const WearGarment& garment,
                          const WearOptions& options, WearReport* report,
                          const WearObserver& observe, const WearRestart& restart) {
  PetscFunctionBeginUser;
  check(garment, options);
  // The drape's sewing is over: the seams pull with their own stiffness and
  // friction holds from the first step (the creep loop's clock starts at 0).
  worn.sewing_tension = 0.0;
  worn.time = 0.0;
  // Cloth slides over the body for hours, over bending joints: the friction
  // springs pull in the tangent plane where each vertex is.
  worn.contact.friction_plane_at_vertex = true;
  PetscCall(worn.level_friction_anchors(x));
  std::vector<Eigen::Vector3d> draped;
  PetscCall(worn.positions_everywhere(x, &draped));
  Hanger hanger(worn.comm(), worn.mesh(), draped, garment);
  PetscCall(hanger.hang_fresh(options.wear.equilibrium, &report->fresh_positions,
                              &report->fresh_converged));
  report->fresh_hem_height = mean_height(report->fresh_positions, garment.hem);

  // The steps land on the take-off times and the moving bodies' knots (a
  // load history of factor 1 with knots there; the bodies' rigid motions
  // add their own).
  CreepOptions wear = options.wear;
  PetscCall(consistent_at_half_the_certified_residual(worn, x, &wear));
  // Each step starts from the last accepted state's anchors (consistent
  // there), not from anchors measured at the step's unsettled start.
  wear.equilibrium.update_anchors_at_start = false;
  std::vector<double> landings = options.take_off_times;
  for (double t : options.landings)
    if (t > 0.0 && t < options.wear.time_end) landings.push_back(t);
  std::sort(landings.begin(), landings.end());
  landings.erase(std::unique(landings.begin(), landings.end()), landings.end());
  std::vector<LoadKnot> knots;
  for (double t : landings)
    knots.push_back({t, 1.0});
  if (!knots.empty()) wear.load = LoadHistory(knots, "wear: take-off times and body knots");
  CreepCoupling creep(worn, garment.creep);
  if (restart.resume) resume_report(restart, worn, report);
  std::size_t next_take_off = report->take_offs.size();
  const double tiny = 1e-9 * options.wear.time_end;
  const CreepObserver follow = [&](const CreepStepReport& step, Vec state) -> PetscErrorCode {
    PetscFunctionBeginUser;
    WearStep measured;
    measured.step = step;
    PetscCall(measure_step(worn, state, creep, garment, options.certify_steps, &measured));
    report->certified_steps += measured.certified ? 1 : 0;
    report->steps.push_back(measured);
    if (observe) observe(worn, state, creep, step.time);
    while (next_take_off < options.take_off_times.size() &&
           std::abs(step.time - options.take_off_times[next_take_off]) <= tiny) {
      std::vector<Eigen::Vector3d> positions;
      std::vector<ElementCreep> states;
      PetscCall(worn.positions_everywhere(state, &positions));
      PetscCall(creep_everywhere(worn.comm(), creep, &states));
      TakeOffReport taken;
      PetscCall(
          hanger.take_off(step.time, positions, states, options, report->fresh_positions, &taken));
      report->take_offs.push_back(std::move(taken));
      ++next_take_off;
    }
    PetscFunctionReturn(0);
  };
  CreepRestart checkpoints;
  checkpoints.resume = restart.resume;
  if (restart.write) {
    checkpoints.every_step = true;
    checkpoints.write = [&](const CreepStepReport& step, Vec state, Vec, double next_step) {
      return restart.write(worn, state, creep, step, next_step, *report);
    };
  }
  PetscCall(solve_creep(worn, creep, x, wear, &report->wear, follow, checkpoints));
  CertificateOptions final_options;
  PetscCall(certify(worn, x, final_options, &report->final_certificate));
  PetscFunctionReturn(0);
}

} // namespace sartor
