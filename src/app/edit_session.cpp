// The edits of `sartor edit`, run in the drape's after_statics (see
// edit_case.hpp): per edit, the linear and GMLS predictions, the warm
// re-solve, its certificate, the errors and CPU times, and the files.

#include "app/certificate_case.hpp"
#include "app/commands.hpp"
#include "app/contact_case.hpp"
#include "app/edit_case.hpp"
#include "app/edit_design.hpp"
#include "app/material_case.hpp"
#include "app/seam_case.hpp"
#include "app/static_case.hpp"
#include "common/csv.hpp"
#include "common/error.hpp"
#include "common/gmls.hpp"
#include "common/output.hpp"
#include "contact/body.hpp"
#include "fem/petsc_call.hpp"
#include "garment/mesh_levels.hpp"
#include "mesh/remesh.hpp"
#include "solvers/incremental_system.hpp"
#include "solvers/sensitivity.hpp"
#include "solvers/statics.hpp"

#include <petscsys.h>

#include <Eigen/QR>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <optional>
#include <tuple>
#include <vector>

namespace sartor {

namespace {

// A drag's point farther than this from every cloth vertex is warned of, m.
constexpr double far_drag_point = 0.02;

// The bone intervals' length, m: 1 cm found vertices inside the mannequin
// exported as a mesh faster than 2 cm (fewer triangles per ray) with the
// same answers; at 5 mm the intervals beside the point's no longer hold
// every triangle its ray meets (docs/sensitivity.md#penetration-handling).
constexpr double bone_interval_length = 0.01;

// A solved design: its parameters, problem, equilibrium and, once needed,
// its sensitivity.
struct Design {
  Eigen::VectorXd p;
  const TriangleMesh* mesh = nullptr;
  std::unique_ptr<TriangleMesh> owned_mesh; // edited designs own theirs
  std::unique_ptr<ClothProblem> owned;      // edited designs own theirs
  ClothProblem* problem = nullptr;
  Vec x = nullptr;
  std::unique_ptr<DesignSensitivity> slope;
  nlohmann::json rest_mesh; // its quality, and the Delaunay smoothing's flips
  Design() = default;
  Design(const Design&) = delete;
  Design& operator=(const Design&) = delete;
  ~Design() {
    slope.reset();
    VecDestroy(&x);
  }
};

// How far one state is from another, over the vertices (rank 0 measures,
// every rank learns).
struct Distance {
  double rms = 0.0, max = 0.0;
};

std::vector<Eigen::Vector3d> gathered(ClothProblem& problem, Vec x) {
  std::vector<Eigen::Vector3d> positions;
  SartorPetscCall(problem.gather_positions(x, &positions));
  return positions;
}

Distance distance(ClothProblem& problem, Vec a, Vec b) {
  const auto pa = gathered(problem, a), pb = gathered(problem, b);
  double values[2] = {0.0, 0.0};
  for (std::size_t v = 0; v < pa.size(); ++v) {
    const double d = (pa[v] - pb[v]).norm();
    values[0] += d * d;
    values[1] = std::max(values[1], d);
  }
  if (!pa.empty()) values[0] = std::sqrt(values[0] / double(pa.size()));
  SartorPetscCall(MPI_Bcast(values, 2, MPI_DOUBLE, 0, problem.comm()));
  return {values[0], values[1]};
}

double lowest_point(ClothProblem& problem, Vec x) {
  double lowest = INFINITY;
  for (const Eigen::Vector3d& p : gathered(problem, x))
    lowest = std::min(lowest, p.z());
  SartorPetscCall(MPI_Bcast(&lowest, 1, MPI_DOUBLE, 0, problem.comm()));
  return lowest;
}

// The thesis' penetration handling before a solve (ClothProblem::
// push_out_of_bodies): a prediction is linear and may run through the body
// where the drape wraps round it; the minimiser's steps are bounded by the
// distances, so it cannot leave the body's inside by itself.
ClothProblem::PushOut push_out_of_bodies(ClothProblem& problem, Vec x) {
  ClothProblem::PushOut report;
  SartorPetscCall(problem.push_out_of_bodies(x, &report));
  return report;
}

double residual_norm(ClothProblem& problem, Vec x) {
  Vec f = nullptr;
  PetscReal norm = 0.0;
  SartorPetscCall(VecDuplicate(x, &f));
  SartorPetscCall(problem.residual(x, f));
  SartorPetscCall(VecNorm(f, NORM_2, &norm));
  SartorPetscCall(VecDestroy(&f));
  return norm;
}

// The order in which the re-solve tries its starts: the one --edit-start
// names (with `auto` the candidate of least potential energy, which the
// minimiser descends), then the others by increasing energy. Each
// candidate's energy, pushed out of the body, goes into `energies`.
std::vector<std::string> order_starts(const std::map<std::string, Vec>& candidates,
                                      const Options& options, ClothProblem& problem, Vec work,
                                      nlohmann::json* energies) {
  const std::string requested = options.text("edit-start");
  if (requested != "auto" && !candidates.count(requested))
    throw InputError("option --edit-start: unknown start '" + requested +
                     "' (auto, gmls, linear, unchanged, geometric)");
  std::vector<std::pair<double, std::string>> by_energy;
  for (const auto& [kind, candidate] : candidates) {
    SartorPetscCall(VecCopy(candidate, work));
    push_out_of_bodies(problem, work);
    ClothEnergy energy;
    SartorPetscCall(problem.energy(work, &energy));
    (*energies)[kind] = energy.total();
    by_energy.emplace_back(energy.total(), kind);
  }
  std::stable_sort(by_energy.begin(), by_energy.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<std::string> order;
  if (requested != "auto") order.push_back(requested);
  for (const auto& [energy, kind] : by_energy)
    if (kind != requested) order.push_back(kind);
  return order;
}

// The kept re-solve: the solver's report and the certificate's verdict.
nlohmann::json resolve_json(const StaticReport& report, const CertifiedState& certified) {
  return {{"converged", report.converged},
          {"reason", report.reason},
          {"newton_iterations", report.newton_iterations},
          {"contact_rounds", report.contact_rounds},
          {"residual_N", report.final_residual_norm},
          {"sliding_vertices", report.sliding_vertices},
          {"contact_round_failed", report.contact_round_failed},
          {"contact_stiffness_scale", report.contact_stiffness_scale},
          {"certificate", certified.certificate.verdict()},
          {"certified", certified.certificate.certified()}};
}

nlohmann::json distance_json(const Distance& d) {
  return {{"rms_m", d.rms}, {"max_m", d.max}};
}

// One re-solve of an edit from one start: its report, certificate and
// state (positions, friction anchors, contact penalty), kept so that the
// edit can go on from the best of its attempts.
struct Attempt {
  std::string start;
  StaticReport report;
  CertifiedState certified;
  ClothProblem::PushOut pushed; // the start's vertices pushed out of the body
  double start_residual = 0.0;
  // The Newton iterations of the stage before the last, without friction
  // (--edit-friction staged; counted in report's too).
  std::optional<PetscInt> frictionless_newton;
  double cpu = 0.0;
  Vec x = nullptr;
  std::vector<AnchorRow> anchors;
  ContactSettings contact;
  bool succeeded() const { return report.converged && certified.certificate.certified(); }
  Attempt() = default;
  Attempt(const Attempt&) = delete;
  Attempt& operator=(const Attempt&) = delete;
  ~Attempt() { VecDestroy(&x); }
};

nlohmann::json attempt_json(const Attempt& a) {
  return {{"start", a.start},
          {"converged", a.report.converged},
          {"reason", a.report.reason},
          {"newton_iterations", a.report.newton_iterations},
          {"frictionless_newton_iterations",
           a.frictionless_newton ? nlohmann::json(*a.frictionless_newton) : nlohmann::json()},
          {"certificate", a.certified.certificate.verdict()},
          {"certified", a.certified.certificate.certified()},
          {"cpu_s", a.cpu}};
}

// Which attempt the edit goes on from: the first that succeeded, else the
// first that converged, else the first (the requested start's).
const Attempt& best_attempt(const std::vector<std::unique_ptr<Attempt>>& attempts) {
  for (const auto& a : attempts)
    if (a->succeeded()) return *a;
  for (const auto& a : attempts)
    if (a->report.converged) return *a;
  return *attempts.front();
}

class EditSession {
public:
  EditSession(const Options& options, std::string directory, EditGarment garment,
              std::vector<EditStep> steps, EditDrapeSource drape, std::shared_ptr<EditRun> run)
      : options_(options), directory_(std::move(directory)), garment_(std::move(garment)),
        steps_(std::move(steps)), drape_(std::move(drape)), run_(std::move(run)) {}

  void edit(ClothProblem& base, const std::vector<ClothMaterial>& materials, Vec x);

private:
  ProblemFactory factory(const ClothProblem& base, const std::vector<ClothMaterial>& materials);
  double ensure_slope(Design& design);
  void add_slope(Design& from, const Eigen::VectorXd& dp, ClothProblem& to, Vec into);
  void predict_gmls(const Eigen::VectorXd& query, ClothProblem& to, Vec into, GmlsWeights* used);
  void predict_geometric(Design& last, const Design& next, Vec into);
  std::unique_ptr<Design> next_design(Design& last, const Eigen::VectorXd& p,
                                      const EditDesign& design);
  StaticOptions static_options() const;
  std::optional<int> staged_friction() const;
  void reset_state(Design& last, ClothProblem& problem);
  std::unique_ptr<Attempt> resolve_from(Design& last, ClothProblem& problem,
                                        const std::string& start, Vec candidate);
  nlohmann::json solve_step(std::size_t k, const Eigen::VectorXd& p, const EditDesign& design);
  Eigen::VectorXd drag_change(std::size_t k, nlohmann::json* record);
  void report_drags(nlohmann::json* step, nlohmann::json drag);
  void write_state(const std::string& directory, const Design& design, Vec x);

  const Options& options_;
  std::string directory_;
  EditGarment garment_;
  std::vector<EditStep> steps_;
  EditDrapeSource drape_;
  std::shared_ptr<EditRun> run_;
  ProblemFactory factory_;
  std::vector<std::unique_ptr<Design>> designs_;
  const EditDesign* design_ = nullptr;
  double scratch_cpu_ = 0.0;
};

ProblemFactory EditSession::factory(const ClothProblem& base,
                                    const std::vector<ClothMaterial>& materials) {
  // Seams take their stiffness from the stiffest fabric, as the drape's.
  const ClothMaterial& stiffest = stiffest_material(materials);
  const SeamStiffness seam_stiffness =
      garment_.seams.empty() ? SeamStiffness{}
                             : case_seam_stiffness(read_seam_case(options_), stiffest);
  return [this, materials, seam_stiffness, pinned = base.pinned(),
          tension = base.sewing_tension](MPI_Comm comm, const TriangleMesh& mesh, double floor) {
    std::vector<ClothMaterial> floored = materials;
    for (ClothMaterial& m : floored)
      m.bending_stiffness = std::max(m.bending_stiffness, floor);
    auto problem = std::make_unique<ClothProblem>(comm, mesh, floored, pinned);
    problem->sewing_tension = tension;
    if (!garment_.seams.empty()) problem->set_seams(garment_.seams, seam_stiffness);
    return problem;
  };
}

// The sensitivity of a design, factorised: its CPU time, s (0 when it was).
double EditSession::ensure_slope(Design& design) {
  if (design.slope) return 0.0;
  const double started = process_cpu_seconds();
  const std::string tangent = options_.text("sensitivity-tangent");
  if (tangent != "exact" && tangent != "projected")
    throw InputError("option --sensitivity-tangent: unknown tangent '" + tangent +
                     "' (exact, projected)");
  SensitivityOptions settings;
  settings.exact_tangent = tangent == "exact";
  design.slope = std::make_unique<DesignSensitivity>(*design.problem, design.x, factory_, settings);
  SartorPetscCall(design.slope->factorise());
  return process_cpu_seconds() - started;
}

// into += S_from dX(dp), in the layout of `to`.
void EditSession::add_slope(Design& from, const Eigen::VectorXd& dp, ClothProblem& to, Vec into) {
  if (dp.norm() == 0.0) return;
  Vec dx = nullptr, moved = nullptr;
  SartorPetscCall(VecDuplicate(from.x, &dx));
  SartorPetscCall(VecDuplicate(into, &moved));
  SartorPetscCall(from.slope->apply(design_->rest_change(dp, *from.mesh), dx));
  SartorPetscCall(transfer_vector(*from.problem, dx, to, moved));
  SartorPetscCall(VecAXPY(into, 1.0, moved));
  SartorPetscCall(VecDestroy(&dx));
  SartorPetscCall(VecDestroy(&moved));
}

void EditSession::predict_gmls(const Eigen::VectorXd& query, ClothProblem& to, Vec into,
                               GmlsWeights* used) {
  std::vector<Eigen::VectorXd> samples;
  for (const auto& d : designs_)
    samples.push_back(d->p);
  GmlsOptions gmls;
  gmls.degree = int(options_.positive_real("gmls-degree"));
  if (gmls.degree != 1 && gmls.degree != 2)
    throw InputError("option --gmls-degree: must be 1 or 2, got " + options_.text("gmls-degree"));
  *used = gmls_weights(samples, query, gmls);
  Vec state = nullptr;
  SartorPetscCall(VecDuplicate(into, &state));
  SartorPetscCall(VecZeroEntries(into));
  for (std::size_t m = 0; m < designs_.size(); ++m) {
    Design& d = *designs_[m];
    SartorPetscCall(transfer_vector(*d.problem, d.x, to, state));
    SartorPetscCall(VecAXPY(into, used->value_weight[m], state));
    add_slope(d, used->slope_direction[m], to, into);
  }
  SartorPetscCall(VecDestroy(&state));
}

// The thesis' geometric route (ch. 4, eqs. 4.1-4.2): each vertex, at its
// edited rest point, takes the barycentric combination of the last drape's
// positions in the triangle of the last design's panel that holds that
// point (extrapolated from the nearest one outside the panel:
// garment::Prolongation, the drape levels' transfer); each side of a seam is
// carried in its own panel, and the two are then closed at their mean.
void EditSession::predict_geometric(Design& last, const Design& next, Vec into) {
  std::vector<Eigen::Vector3d> positions =
      broadcast_positions(gathered(*last.problem, last.x), last.mesh->vertex_count());
  TriangleMesh before = *last.mesh, after = *next.mesh;
  before.material_ids = after.material_ids = garment_.panel_of_triangle;
  positions = garment::Prolongation(before, after).vertex_field(positions);
  garment::close_seams(after, garment_.seams, &positions);
  SartorPetscCall(next.problem->set_solution(positions, into));
}

// The drape's last stage again: sewn, loaded, with its contact rounds.
StaticOptions EditSession::static_options() const {
  const StaticCase statics = read_static_case(options_);
  StaticOptions solve;
  solve.minimise = statics.minimise;
  solve.max_offset_depth = statics.max_offset_depth;
  if (solve.max_offset_depth == 0.0) solve.max_contact_rounds = 0;
  solve.start_load_factor = 1.0;
  solve.progress_interval = 10.0;
  return solve;
}

// The drape's sewing stages, where the re-solve repeats the last two of
// them (--edit-friction staged): solve_static starts after the first n - 2
// (StaticOptions::first_sewing_stage), so the stage before the last sews without
// friction (ClothProblem::sewing) and the last anchors the cloth afresh
// where that one left it, as the drape did. None for a drape not sewn in
// stages, with --edit-anchors kept, or --edit-friction held.
std::optional<int> EditSession::staged_friction() const {
  const std::string kind = options_.text("edit-friction"); // run_edit checked it
  const int stages = read_static_case(options_).sewing_stages;
  if (kind == "held" || stages < 2 || options_.text("edit-anchors") != "fresh") return std::nullopt;
  return stages;
}

// `problem` in the last design's state (loads, sewing, contact), with its
// friction anchors afresh unless --edit-anchors kept: statics anchor what
// touches a body at their start, and the last drape's anchors would hold the
// contact where the edit moved it from.
void EditSession::reset_state(Design& last, ClothProblem& problem) {
  SartorPetscCall(copy_problem_state(*last.problem, problem));
  if (options_.text("edit-anchors") == "fresh") problem.restore_anchors({});
}

// The drape's last stage re-solved from `candidate` (pushed out of the
// body), on `problem` reset to the last design's state, and certified.
std::unique_ptr<Attempt> EditSession::resolve_from(Design& last, ClothProblem& problem,
                                                   const std::string& start, Vec candidate) {
  reset_state(last, problem);
  auto attempt = std::make_unique<Attempt>();
  attempt->start = start;
  const double started = process_cpu_seconds();
  SartorPetscCall(VecDuplicate(candidate, &attempt->x));
  SartorPetscCall(VecCopy(candidate, attempt->x));
  attempt->pushed = push_out_of_bodies(problem, attempt->x);
  attempt->start_residual = residual_norm(problem, attempt->x);
  const StaticOptions solve = static_options();
  IncrementalSystem system(problem, attempt->x);
  if (const long cap = options_.integer_in("edit-max-newton", 0, 1000000000); cap > 0) {
    SnesTolerances capped;
    SartorPetscCall(SnesTolerances::of(system.snes(), &capped));
    capped.max_iterations = PetscInt(cap);
    SartorPetscCall(capped.apply(system.snes()));
  }
  StaticOptions staged = solve; // the certificate's re-solves take `solve`
  const std::optional<int> stages = staged_friction();
  if (stages) {
    staged.sewing_stages = *stages;
    staged.start_load_factor = 0.0; // the stages' loads grow from none, as the drape's
    staged.first_sewing_stage = *stages - 2;
  }
  SartorPetscCall(solve_static(system, attempt->x, staged, &attempt->report));
  if (stages && !attempt->report.steps.empty())
    attempt->frictionless_newton = attempt->report.steps.front().newton_iterations;
  attempt->certified =
      certify_case(read_certificate_case(options_), problem, attempt->x, &solve, &attempt->report);
  attempt->cpu = process_cpu_seconds() - started;
  SartorPetscCall(problem.anchors_everywhere(&attempt->anchors));
  attempt->contact = problem.contact;
  return attempt;
}

void EditSession::write_state(const std::string& directory, const Design& design, Vec x) {
  std::vector<element::MembraneStrain> strains;
  SartorPetscCall(design.problem->gather_strains(x, &strains));
  const auto positions = gathered(*design.problem, x);
  if (is_root()) write_cloth_results(directory, *design.mesh, positions, strains, garment_.labels);
}

// A rest triangle squashed below this fraction of its area by an edit (or
// turned inside out) makes the edited pattern fold over itself.
constexpr double least_area_kept = 0.05;

double signed_material_area(const std::array<Eigen::Vector2d, 3>& uv) {
  const Eigen::Vector2d a = uv[1] - uv[0], b = uv[2] - uv[0];
  return 0.5 * (a.x() * b.y() - a.y() * b.x());
}

// Throws InputError where the edited rest coordinates fold a panel over
// itself (a dart slid past its neighbours, a corner dragged across the
// panel), naming the panels and how many triangles.
void refuse_folded_rest(const TriangleMesh& before, const TriangleMesh& after,
                        const std::vector<int>& panel_of_triangle,
                        const garment::Pattern& pattern) {
  std::map<std::string, int> folded;
  for (std::size_t t = 0; t < before.triangle_count(); ++t) {
    const double area = signed_material_area(before.material_uv[t]);
    if (signed_material_area(after.material_uv[t]) / area < least_area_kept)
      ++folded[pattern.panels[std::size_t(panel_of_triangle[t])].id];
  }
  if (folded.empty()) return;
  std::string where;
  for (const auto& [panel, count] : folded)
    where += (where.empty() ? "" : ", ") + std::to_string(count) + " in panel '" + panel + "'";
  throw InputError("sartor edit: the edited pattern folds over itself: triangles turned inside "
                   "out or squashed below " +
                   format_number(100.0 * least_area_kept) + " % of their area (" + where +
                   "); make the edit smaller");
}

// Delaunay smoothing (Sensitive Couture §6) of an edited rest mesh whose
// worst triangle's quality (triangle_quality: 1 equilateral, 0 flat) fell
// below `least_quality`: edges flipped, the vertices kept, so positions,
// sensitivities and seams carry over. The report: the worst quality before
// and after, the flips, and whether the mesh stays distorted (remeshing
// with state transfer is not done).
nlohmann::json smooth_distorted_mesh(TriangleMesh* mesh, double least_quality) {
  const double worst = worst_quality(*mesh);
  nlohmann::json report = {{"worst_quality", worst}, {"flips", 0}, {"smoothed", false}};
  if (worst >= least_quality) return report;
  const FlipReport flipped = delaunay_smoothing(*mesh);
  report["smoothed"] = true;
  report["flips"] = flipped.flips;
  report["worst_quality_before_smoothing"] = flipped.worst_before;
  report["worst_quality"] = flipped.worst_after;
  report["still_distorted"] = flipped.worst_after < least_quality;
  return report;
}

// The line of a step whose rest mesh was smoothed, and the warning where it
// stays distorted.
void report_smoothing(MPI_Comm comm, const nlohmann::json& step) {
  const nlohmann::json& mesh = step["rest_mesh"];
  if (!mesh["smoothed"].get<bool>()) return;
  SartorPetscCall(PetscPrintf(
      comm,
      "sartor edit: %s: the edit squashed triangles (worst quality %.3f, 1 equilateral); "
      "Delaunay smoothing flipped %d edges: worst quality %.3f\n",
      step["folder"].get<std::string>().c_str(),
      mesh["worst_quality_before_smoothing"].get<double>(), mesh["flips"].get<int>(),
      mesh["worst_quality"].get<double>()));
  if (mesh["still_distorted"].get<bool>())
    SartorPetscCall(PetscPrintf(
        comm,
        "sartor edit: warning: %s: the rest mesh stays distorted after smoothing (remeshing "
        "is not implemented): split the edit into smaller steps or mesh finer\n",
        step["folder"].get<std::string>().c_str()));
}

// Each seam's two sides' rest lengths in `mesh` (along their vertices'
// material coordinates): an edit that lengthens one side of a seam sews
// unequal lengths, the longer eased (gathered) into the shorter.
nlohmann::json seam_rest_lengths(const TriangleMesh& mesh, const std::vector<Seam>& seams) {
  const std::vector<Eigen::Vector2d> uv = vertex_material_uv(mesh);
  const auto length = [&](const std::vector<int>& line) {
    double sum = 0.0;
    for (std::size_t i = 1; i < line.size(); ++i)
      sum += (uv[std::size_t(line[i])] - uv[std::size_t(line[i - 1])]).norm();
    return sum;
  };
  nlohmann::json lengths = nlohmann::json::array();
  for (const Seam& seam : seams)
    lengths.push_back({{"seam", seam.name}, {"a_m", length(seam.a)}, {"b_m", length(seam.b)}});
  return lengths;
}

// A step's change of the design: its moves', plus each named parameter's
// moves per unit times its change.
Eigen::VectorXd step_change(const EditStep& step, const EditDesign& design) {
  Eigen::VectorXd change = design.parameters(step.moves);
  for (const ParameterChange& slider : step.changes)
    change += slider.by * design.parameters(slider.parameter.moves);
  return change;
}

// The design p on the mesh moved to its rest coordinates, its problem in
// the last design's state and its solution vector made (not yet filled).
std::unique_ptr<Design> EditSession::next_design(Design& last, const Eigen::VectorXd& p,
                                                 const EditDesign& design) {
  auto next = std::make_unique<Design>();
  next->p = p;
  const TriangleMesh& drape_mesh = *designs_.front()->mesh;
  next->owned_mesh = std::make_unique<TriangleMesh>(
      moved_rest(drape_mesh, design.rest_change(p, drape_mesh), 1.0));
  refuse_folded_rest(drape_mesh, *next->owned_mesh, garment_.panel_of_triangle, garment_.pattern);
  next->rest_mesh = smooth_distorted_mesh(next->owned_mesh.get(),
                                          options_.nonnegative_real("edit-smoothing-quality"));
  next->mesh = next->owned_mesh.get();
  next->owned = factory_(last.problem->comm(), *next->mesh, 0.0);
  next->problem = next->owned.get();
  reset_state(last, *next->problem);
  SartorPetscCall(next->problem->create_solution(&next->x));
  return next;
}

nlohmann::json EditSession::solve_step(std::size_t k, const Eigen::VectorXd& p,
                                       const EditDesign& design) {
  Design& last = *designs_.back();
  const double slope_cpu = ensure_slope(last);
  const double predict_started = process_cpu_seconds();
  std::unique_ptr<Design> next = next_design(last, p, design);
  ClothProblem& problem = *next->problem;
  Vec unchanged = nullptr, linear = nullptr, gmls = nullptr, geometric = nullptr;
  for (Vec* v : {&unchanged, &linear, &gmls, &geometric})
    SartorPetscCall(VecDuplicate(next->x, v));
  SartorPetscCall(transfer_vector(*last.problem, last.x, problem, unchanged));
  SartorPetscCall(VecCopy(unchanged, linear));
  add_slope(last, p - last.p, problem, linear);
  GmlsWeights used;
  predict_gmls(p, problem, gmls, &used);
  const double predict_cpu = process_cpu_seconds() - predict_started;
  const double geometric_started = process_cpu_seconds();
  predict_geometric(last, *next, geometric);
  const double geometric_cpu = process_cpu_seconds() - geometric_started;

  // With one design GMLS is the linear prediction: one of the two is tried.
  // The geometric route is for comparison: a start only when asked for.
  const std::string requested = options_.text("edit-start");
  std::map<std::string, Vec> candidates{{"linear", linear}, {"unchanged", unchanged}};
  if (requested == "geometric") candidates["geometric"] = geometric;
  if (designs_.size() > 1 || requested == "gmls") candidates["gmls"] = gmls;
  if (designs_.size() == 1 && requested == "gmls") candidates.erase("linear");
  nlohmann::json start_energy = nlohmann::json::object();
  const std::vector<std::string> order =
      order_starts(candidates, options_, problem, next->x, &start_energy);
  // A re-solve that fails (not converged, or not certified) is tried again
  // from the other starts, unless --no-edit-retry.
  std::vector<std::unique_ptr<Attempt>> attempts;
  for (const std::string& start : order) {
    attempts.push_back(resolve_from(last, problem, start, candidates.at(start)));
    if (attempts.back()->succeeded() || options_.flag("no-edit-retry")) break;
  }
  const Attempt& chosen = best_attempt(attempts);
  SartorPetscCall(VecCopy(chosen.x, next->x));
  problem.restore_anchors(chosen.anchors);
  problem.contact = chosen.contact;
  double solve_cpu = 0.0;
  nlohmann::json tried = nlohmann::json::array();
  for (const auto& attempt : attempts) {
    solve_cpu += attempt->cpu;
    tried.push_back(attempt_json(*attempt));
  }

  char name[32];
  std::snprintf(name, sizeof name, "edit_%02zu", k + 1);
  const std::string folder = directory_ + "/" + name;
  if (is_root()) {
    make_output_directory(folder);
    write_edit_svg(folder + "/pattern.svg", garment_.pattern, design.outlines(last.p),
                   design.outlines(p), steps_[k].name);
    write_json(folder + "/outlines.json",
               edit_outlines_json(garment_.pattern, design.outlines(last.p), design.outlines(p),
                                  steps_[k].name));
  }
  if (!options_.flag("no-edit-outputs")) {
    write_state(folder + "/linear", *next, linear);
    write_state(folder + "/gmls", *next, gmls);
    write_state(folder + "/geometric", *next, geometric);
    write_state(folder + "/resolved", *next, next->x);
  }
  const double edit_cpu = slope_cpu + predict_cpu + solve_cpu;
  nlohmann::json step = {{"name", steps_[k].name},
                         {"folder", name},
                         {"largest_corner_move_m", design.largest_move(p - last.p)},
                         {"rest_mesh", next->rest_mesh},
                         {"seam_rest_lengths", seam_rest_lengths(*next->mesh, garment_.seams)},
                         {"error_against_resolved",
                          {{"unchanged", distance_json(distance(problem, unchanged, next->x))},
                           {"linear", distance_json(distance(problem, linear, next->x))},
                           {"gmls", distance_json(distance(problem, gmls, next->x))},
                           {"geometric", distance_json(distance(problem, geometric, next->x))}}},
                         {"gmls", {{"designs", designs_.size()}, {"degree", used.degree}}},
                         {"lowest_point_z_m",
                          {{"before", lowest_point(problem, unchanged)},
                           {"linear", lowest_point(problem, linear)},
                           {"gmls", lowest_point(problem, gmls)},
                           {"geometric", lowest_point(problem, geometric)},
                           {"resolved", lowest_point(problem, next->x)}}},
                         {"start", chosen.start},
                         {"start_energy_J", start_energy},
                         {"start_pushed_out",
                          {{"vertices", chosen.pushed.pushed},
                           {"deepest_m", chosen.pushed.deepest},
                           {"body_queries", chosen.pushed.queries}}},
                         {"start_residual_N", chosen.start_residual},
                         {"attempts", tried},
                         {"resolve", resolve_json(chosen.report, chosen.certified)},
                         {"sensitivity_stabilised", last.slope->stabilised()},
                         {"cpu_s",
                          {{"sensitivity_factorisation", slope_cpu},
                           {"prediction", predict_cpu},
                           {"geometric_prediction", geometric_cpu},
                           {"resolve", solve_cpu},
                           {"edit_total", edit_cpu},
                           {"drape_from_scratch", scratch_cpu_}}},
                         {"speedup",
                          {{"resolve", solve_cpu > 0.0 ? scratch_cpu_ / solve_cpu : 0.0},
                           {"edit_total", edit_cpu > 0.0 ? scratch_cpu_ / edit_cpu : 0.0}}}};
  for (Vec* v : {&unchanged, &linear, &gmls, &geometric})
    SartorPetscCall(VecDestroy(v));
  designs_.push_back(std::move(next));
  return step;
}

// Step k's drags (Sensitive Couture §4.1): the change of the step's design
// parameters (EditStep) whose linear response fits the drags in least
// squares, the smallest such where several do, from the dragged vertices'
// sensitivities in the last design; returns the change of the design, and
// `record` gets the parameters' changes and per drag its vertex, its
// sensitivities and its predicted move. Throws InputError when the
// parameters do not move the dragged vertices, or would move a corner more
// than 0.5 m.
Eigen::VectorXd EditSession::drag_change(std::size_t k, nlohmann::json* record) {
  const EditStep& edit = steps_[k];
  const std::string step = "edit step " + std::to_string(k + 1) + " ('" + edit.name + "')";
  Design& last = *designs_.back();
  const double started = process_cpu_seconds();
  ensure_slope(last);
  const std::size_t m = edit.parameters.size(), n = edit.drags.size();
  std::vector<Eigen::VectorXd> directions;
  std::vector<std::vector<Eigen::Vector3d>> slopes; // per parameter, per vertex (rank 0)
  Vec dx = nullptr;
  SartorPetscCall(VecDuplicate(last.x, &dx));
  for (const EditParameter& parameter : edit.parameters) {
    directions.push_back(design_->parameters(parameter.moves));
    SartorPetscCall(last.slope->apply(design_->rest_change(directions.back(), *last.mesh), dx));
    slopes.push_back(gathered(*last.problem, dx));
  }
  SartorPetscCall(VecDestroy(&dx));
  const std::vector<Eigen::Vector3d> positions = gathered(*last.problem, last.x);
  // Rank 0 finds each drag's free vertex nearest its point; every rank
  // learns the vertex, its position and its rows of S: 4 + 3m numbers a drag.
  const std::size_t width = 4 + 3 * m;
  std::vector<double> found(n * width, -1.0);
  if (is_root()) {
    std::vector<bool> pinned(positions.size(), false);
    for (int v : last.problem->pinned())
      pinned[std::size_t(v)] = true;
    for (std::size_t i = 0; i < n; ++i) {
      double nearest = INFINITY;
      for (std::size_t v = 0; v < positions.size(); ++v) {
        const double d = (positions[v] - edit.drags[i].point).norm();
        if (pinned[v] || d >= nearest) continue;
        nearest = d;
        found[i * width] = double(v);
        for (int c = 0; c < 3; ++c) {
          found[i * width + 1 + std::size_t(c)] = positions[v][c];
          for (std::size_t j = 0; j < m; ++j)
            found[i * width + 4 + 3 * j + std::size_t(c)] = slopes[j][v][c];
        }
      }
    }
  }
  SartorPetscCall(MPI_Bcast(found.data(), int(found.size()), MPI_DOUBLE, 0, last.problem->comm()));
  Eigen::MatrixXd S(3 * n, m);
  Eigen::VectorXd wanted(3 * n);
  for (std::size_t i = 0; i < n; ++i) {
    if (found[i * width] < 0.0) throw InputError(step + ": drag: the cloth has no free vertex");
    wanted.segment<3>(Eigen::Index(3 * i)) = edit.drags[i].by;
    for (std::size_t j = 0; j < m; ++j)
      for (std::size_t c = 0; c < 3; ++c)
        S(Eigen::Index(3 * i + c), Eigen::Index(j)) = found[i * width + 4 + 3 * j + c];
  }
  if (!(S.squaredNorm() > 0.0))
    throw InputError(step + ": drag: the step's moves do not move the vertices nearest the " +
                     "drags' points (their sensitivities are zero)");
  const Eigen::VectorXd dg = S.completeOrthogonalDecomposition().solve(wanted);
  Eigen::VectorXd change = Eigen::VectorXd::Zero(design_->size());
  for (std::size_t j = 0; j < m; ++j)
    change += dg[Eigen::Index(j)] * directions[j];
  const double largest = design_->largest_move(change);
  if (!(largest <= 0.5))
    throw InputError(step + ": drag: the drags ask for corner moves of " + format_number(largest) +
                     " m (at most 0.5 m): the step's moves hardly carry the dragged vertices; " +
                     "choose moves that do");
  const Eigen::VectorXd predicted = S * dg;
  const auto vector = [](const double* v) { return nlohmann::json{v[0], v[1], v[2]}; };
  nlohmann::json parameters = nlohmann::json::array(), drags = nlohmann::json::array();
  for (std::size_t j = 0; j < m; ++j)
    parameters.push_back({{"name", edit.parameters[j].name}, {"change", dg[Eigen::Index(j)]}});
  // A point far from the drape picks a vertex the user may not have meant.
  std::vector<std::string> warnings;
  for (std::size_t i = 0; i < n; ++i) {
    const double* row = &found[i * width];
    const double distance = (Eigen::Vector3d(row[1], row[2], row[3]) - edit.drags[i].point).norm();
    if (distance > far_drag_point) {
      warnings.push_back(step + ": drag " + std::to_string(i + 1) + "'s point is " +
                         format_number(distance) + " m from the nearest cloth vertex (" +
                         std::to_string(long(row[0])) + "), which it drags");
    }
    nlohmann::json sensitivities = nlohmann::json::array();
    for (std::size_t j = 0; j < m; ++j)
      sensitivities.push_back(vector(row + 4 + 3 * j));
    drags.push_back({{"vertex", long(row[0])},
                     {"point_m", vector(edit.drags[i].point.data())},
                     {"point_distance_m", distance},
                     {"vertex_position_m", vector(row + 1)},
                     {"by_m", vector(edit.drags[i].by.data())},
                     {"sensitivity_m_per_unit", sensitivities},
                     {"predicted_move_m", vector(predicted.data() + 3 * i)}});
  }
  print_warnings(warnings);
  *record = {
      {"parameters", parameters}, {"drags", drags}, {"cpu_s", process_cpu_seconds() - started}};
  return change;
}

// Adds to `step` (solve_step's record of a step) the drags' record with the
// re-solved moves of their vertices, its CPU time counted in the edit's.
void EditSession::report_drags(nlohmann::json* step, nlohmann::json drag) {
  const Design& next = *designs_.back();
  const auto positions = gathered(*next.problem, next.x);
  for (nlohmann::json& one : drag["drags"]) {
    double moved[3] = {0.0, 0.0, 0.0};
    if (is_root()) {
      const auto v = std::size_t(one["vertex"].get<long>());
      for (std::size_t c = 0; c < 3; ++c)
        moved[c] = positions[v][long(c)] - one["vertex_position_m"][c].get<double>();
    }
    SartorPetscCall(MPI_Bcast(moved, 3, MPI_DOUBLE, 0, next.problem->comm()));
    one["resolved_move_m"] = {moved[0], moved[1], moved[2]};
    const auto& by = one["by_m"];
    const auto& predicted = one["predicted_move_m"];
    SartorPetscCall(PetscPrintf(
        next.problem->comm(),
        "sartor edit: %s drag: vertex %ld asked to move by (%.4g, %.4g, %.4g) m; predicted move "
        "(%.4g, %.4g, %.4g) m, re-solved (%.4g, %.4g, %.4g) m\n",
        (*step)["folder"].get<std::string>().c_str(), one["vertex"].get<long>(),
        by[0].get<double>(), by[1].get<double>(), by[2].get<double>(), predicted[0].get<double>(),
        predicted[1].get<double>(), predicted[2].get<double>(), moved[0], moved[1], moved[2]));
  }
  std::string changes;
  for (const auto& parameter : drag["parameters"])
    changes += (changes.empty() ? "" : ", ") + parameter["name"].get<std::string>() + " " +
               format_number(parameter["change"].get<double>());
  SartorPetscCall(PetscPrintf(next.problem->comm(),
                              "sartor edit: %s drag: the parameters changed by: %s\n",
                              (*step)["folder"].get<std::string>().c_str(), changes.c_str()));
  nlohmann::json& cpu = (*step)["cpu_s"];
  cpu["sensitivity_factorisation"] =
      cpu["sensitivity_factorisation"].get<double>() + drag["cpu_s"].get<double>();
  cpu["edit_total"] = cpu["edit_total"].get<double>() + drag["cpu_s"].get<double>();
  (*step)["speedup"]["edit_total"] =
      scratch_cpu_ / std::max(cpu["edit_total"].get<double>(), 1e-300);
  (*step)["drag"] = std::move(drag);
}

void EditSession::edit(ClothProblem& base, const std::vector<ClothMaterial>& materials, Vec x) {
  scratch_cpu_ =
      drape_.directory.empty() ? process_cpu_seconds() - drape_.started_cpu : drape_.recorded_cpu;
  if (garment_.panel_of_triangle.size() != base.mesh().triangle_count())
    throw std::logic_error("sartor edit: the drape's mesh is not the constructed garment's");
  factory_ = factory(base, materials);
  const nlohmann::json bone_intervals = attach_bone_intervals(options_, bone_interval_length, base);
  const EditDesign design(garment_.pattern, base.mesh(), garment_.panel_of_triangle,
                          interior_coordinates_option(options_));
  design_ = &design;
  auto first = std::make_unique<Design>();
  first->p = Eigen::VectorXd::Zero(design.size());
  first->mesh = &base.mesh();
  first->problem = &base;
  SartorPetscCall(VecDuplicate(x, &first->x));
  SartorPetscCall(VecCopy(x, first->x));
  designs_.push_back(std::move(first));
  nlohmann::json steps = nlohmann::json::array();
  Eigen::VectorXd p = designs_.front()->p;
  bool all_certified = true;
  for (std::size_t k = 0; k < steps_.size(); ++k) {
    const bool drags = !steps_[k].drags.empty();
    nlohmann::json drag;
    p += drags ? drag_change(k, &drag) : step_change(steps_[k], design);
    nlohmann::json step = solve_step(k, p, design);
    if (drags) report_drags(&step, std::move(drag));
    for (const ParameterChange& change : steps_[k].changes)
      step["changes"].push_back({{"parameter", change.parameter.name}, {"by", change.by}});
    all_certified = all_certified && step["resolve"]["certified"].get<bool>();
    if (!step["resolve"]["converged"].get<bool>())
      run_->not_converged.push_back(step["folder"].get<std::string>());
    const auto& error = step["error_against_resolved"];
    const auto& cpu = step["cpu_s"];
    std::string others; // the other attempts: "from linear: not converged, ..."
    for (const auto& attempt : step["attempts"])
      if (attempt["start"] != step["start"])
        others += std::string(others.empty() ? "" : ", ") + "from " +
                  attempt["start"].get<std::string>() + ": " +
                  (attempt["converged"].get<bool>() ? attempt["certificate"].get<std::string>()
                                                    : "not converged");
    const std::string from =
        step["start"].get<std::string>() + (others.empty() ? "" : " (" + others + ")");
    SartorPetscCall(PetscPrintf(
        base.comm(),
        "sartor edit: %s ('%s'): lowest point %+.1f mm; predictions off by (max) linear %.2f "
        "mm, GMLS %.2f mm, geometric %.2f mm, unchanged %.2f mm; re-solve from %s: %s, %d "
        "Newton iterations, "
        "certificate: %s; CPU s: re-solve %.2f, edit %.2f, drape from scratch %.2f\n",
        step["folder"].get<std::string>().c_str(), steps_[k].name.c_str(),
        1e3 * (step["lowest_point_z_m"]["resolved"].get<double>() -
               step["lowest_point_z_m"]["before"].get<double>()),
        1e3 * error["linear"]["max_m"].get<double>(), 1e3 * error["gmls"]["max_m"].get<double>(),
        1e3 * error["geometric"]["max_m"].get<double>(),
        1e3 * error["unchanged"]["max_m"].get<double>(), from.c_str(),
        step["resolve"]["converged"].get<bool>() ? "converged" : "NOT converged",
        int(step["resolve"]["newton_iterations"].get<long>()),
        step["resolve"]["certificate"].get<std::string>().c_str(), cpu["resolve"].get<double>(),
        cpu["edit_total"].get<double>(), cpu["drape_from_scratch"].get<double>()));
    report_smoothing(base.comm(), step);
    steps.push_back(step);
    // The edits build on each other: none follows a drape out of equilibrium.
    if (!run_->not_converged.empty()) break;
  }
  designs_.clear();
  run_->ran = true;
  run_->all_certified = all_certified;
  run_->summary = {{"steps", steps},
                   {"drape_from_scratch_cpu_s", scratch_cpu_},
                   {"drape_resumed_from", drape_.directory},
                   {"start", options_.text("edit-start")},
                   {"gmls_degree", int(options_.positive_real("gmls-degree"))},
                   {"interior", options_.text("edit-interior")},
                   {"bone_intervals", bone_intervals}};
}

} // namespace

void attach_edit(const Options& options, const std::string& directory, EditGarment garment,
                 std::vector<EditStep> steps, const EditDrapeSource& drape, CaseCloth* cloth,
                 const std::shared_ptr<EditRun>& run) {
  auto session = std::make_shared<EditSession>(options, directory, std::move(garment),
                                               std::move(steps), drape, run);
  cloth->after_statics = [session](ClothProblem& problem,
                                   const std::vector<ClothMaterial>& materials,
                                   const std::vector<SeamSpring>&, Vec x,
                                   const std::shared_ptr<const RunCheckpoint>&) {
    session->edit(problem, materials, x);
  };
}

} // namespace sartor
