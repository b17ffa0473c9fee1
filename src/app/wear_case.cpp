#include "app/wear_case.hpp"

#include "app/commands.hpp"
#include "app/creep_case.hpp"
#include "app/wear_checkpoint.hpp"
#include "common/csv.hpp"
#include "common/error.hpp"
#include "common/output.hpp"
#include "contact/body_spec.hpp"
#include "fem/petsc_call.hpp"
#include "material/fabric.hpp"
#include "solvers/posed_mannequin.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <fstream>
#include <map>
#include <optional>
#include <set>
#include <sstream>

namespace sartor {

const std::vector<OptionSpec>& wear_option_specs() {
  static const std::vector<OptionSpec> specs{
      {"wear-time", "S", "",
       "after the static drape, wear the garment for S seconds (creep at adaptive steps, "
       "--creep-scheme, --creep-tolerance, --max-time-step), then take it off "
       "(docs/wear.md); --analysis creep: 28800 (8 h)"},
      {"wear-first-step", "S", "1", "(wear) the first time step, s"},
      {"take-off-times", "T,...", "",
       "(wear) wear times at which the garment is also taken off and recovers, s [the wear time]"},
      {"recovery-time", "S", "3600", "(wear) time the taken-off garment hangs recovering, s"},
      {"hold-band", "M", "0.03",
       "(wear) the garment is hung by its boundary vertices within M of its highest draped "
       "vertex (the waistband), m"},
      {"hem-band", "M", "0.02",
       "(wear) the hem: boundary vertices within M of the lowest draped vertex, m"},
      {"bagging-box", "X0,X1,Y0,Y1,Z0,Z1", "",
       "(wear) the bagging height is measured on the vertices draped in this box, m [all]"},
      {"wear-contact-rounds", "N", "30",
       "(wear) contact rounds of each step's solve, at most (friction anchors updated and the "
       "penalty adapted within the step until friction is consistent, else the step is retried "
       "shorter; 0: anchors lagged by a "
       "step, drape's penalty kept, and the states not in equilibrium)"},
      {"no-step-certificate", "", "",
       "(wear) do not certify every wear step (the final states are certified)"},
      {"wear-poses", "T:POSE;...", "",
       "(wear) the mannequin moves through these poses over the wear, joint angles interpolated "
       "between keyframes (e.g. \"0:;600:hip_l:90,hip_r:90,knee_l:90,knee_r:90;7800:;8400:\"); "
       "its pose at 0 s must be the draped one (--body's pose=)"},
      {"wear-pose-step", "DEG", "5",
       "(wear) while the body moves, steps end where no joint has turned by more than DEG degrees"},
  };
  return specs;
}

bool wear_requested(const Options& options) {
  return options.is_set("wear-time");
}

namespace {

// Per fabric of the cloth: its creep parameters per direction, or
// --creep-parameters for every fabric and direction.
std::vector<CreepMaterial> wear_creep_materials(const CreepCase& creep,
                                                const std::vector<std::string>& fabrics) {
  if (creep.given) return std::vector<CreepMaterial>(fabrics.size(), *creep.given);
  std::vector<CreepMaterial> materials;
  for (const std::string& name : fabrics) {
    const Fabric fabric = resolve_fabrics(name).front().fabric;
    fabric.check_creep();
    materials.push_back({fabric.in(Direction::warp).creep, fabric.in(Direction::weft).creep});
  }
  return materials;
}

// The vertices the take-off holds, the hem and the bagging region, from the
// draped positions (every rank).
void select_vertices(const Options& options, const TriangleMesh& mesh,
                     const std::vector<Eigen::Vector3d>& draped, WearGarment* garment) {
  double top = -INFINITY, bottom = INFINITY;
  for (const Eigen::Vector3d& p : draped) {
    top = std::max(top, p.z());
    bottom = std::min(bottom, p.z());
  }
  const double hold = options.positive_real("hold-band");
  const double hem = options.positive_real("hem-band");
  // Boundary vertices: the hem, cuffs, waist and the panels' seam lines
  // (the panels are sewn by springs, not merged).
  std::vector<bool> boundary(mesh.vertex_count(), false);
  for (int v : boundary_vertices(mesh))
    boundary[std::size_t(v)] = true;
  std::vector<double> box;
  if (options.is_set("bagging-box")) box = option_numbers(options, "bagging-box", 6);
  for (std::size_t v = 0; v < draped.size(); ++v) {
    const Eigen::Vector3d& p = draped[v];
    if (boundary[v] && p.z() >= top - hold) garment->held.push_back(int(v));
    if (boundary[v] && p.z() <= bottom + hem) garment->hem.push_back(int(v));
    if (!box.empty() && p.x() >= box[0] && p.x() <= box[1] && p.y() >= box[2] && p.y() <= box[3] &&
        p.z() >= box[4] && p.z() <= box[5])
      garment->bagging.push_back(int(v));
  }
  if (!box.empty() && garment->bagging.empty()) {
    throw InputError("option --bagging-box: no vertex of the draped garment is in the box");
  }
}

WearOptions wear_options(const Options& options, const CreepCase& creep) {
  WearOptions wear;
  wear.wear.time_end = options.positive_real("wear-time");
  wear.wear.time_step = options.positive_real("wear-first-step");
  wear.wear.min_step = creep.min_step;
  wear.wear.max_step = creep.max_step;
  wear.wear.creep_tolerance = creep.tolerance;
  wear.wear.scheme = creep.scheme;
  wear.wear.print_progress = true;
  wear.wear.equilibrium.progress_interval = 10.0; // a step's solve that runs long says so
  wear.wear.equilibrium.minimise = minimiser_chosen(options, "static-solver");
  // Contact rounds within each wear step (30 by default) make the friction
  // consistent with the anchors the state ends with, at half the residual
  // the certificate allows (solvers/wear.cpp); a step they leave inconsistent is
  // retried shorter. 0 lags the anchors by one step and keeps the drape's
  // penalty (docs/wear.md).
  wear.wear.equilibrium.max_contact_rounds = int(options.integer_in("wear-contact-rounds", 0, 100));
  wear.recovery_time = options.positive_real("recovery-time");
  if (options.is_set("take-off-times")) {
    wear.take_off_times = option_numbers(options, "take-off-times", 0);
  } else {
    wear.take_off_times = {wear.wear.time_end};
  }
  double last = 0.0;
  for (double t : wear.take_off_times) {
    if (!(t > last) || t > wear.wear.time_end) {
      throw InputError("option --take-off-times: the times must increase within (0, --wear-time " +
                       format_number(wear.wear.time_end) + "] s, got " + format_number(t));
    }
    last = t;
  }
  wear.certify_steps = !options.flag("no-step-certificate");
  return wear;
}

std::vector<ClothTimeSeries::CellField> creep_fields(const std::vector<ElementCreep>& states) {
  std::vector<ClothTimeSeries::CellField> fields{{"viscoelastic_warp", {}},
                                                 {"permanent_warp", {}},
                                                 {"viscoelastic_weft", {}},
                                                 {"permanent_weft", {}},
                                                 {"permanent", {}}};
  for (const ElementCreep& c : states) {
    fields[0].values.push_back(c.warp.viscoelastic);
    fields[1].values.push_back(c.warp.permanent);
    fields[2].values.push_back(c.weft.viscoelastic);
    fields[3].values.push_back(c.weft.permanent);
    fields[4].values.push_back(std::max(c.warp.permanent, c.weft.permanent));
  }
  return fields;
}

// The wear states (every accepted step) into DIRECTORY/wear/series.*; a
// resumed wear keeps the states up to `resumed_time` (s; negative: none).
// wear.csv's header and one row per wear state.
const char* const wear_table_header =
    "time_s,dt_s,newton_iterations,rejected,creep_increment,hem_height_m,"
    "max_elastic_strain,max_viscoelastic_strain,max_permanent_strain,certified,certificate,"
    "dome_height_m\n";

std::string wear_table_row(const WearStep& s) {
  std::ostringstream row;
  row.precision(10);
  row << s.step.time << ',' << s.step.dt << ',' << s.step.newton_iterations << ','
      << s.step.rejected << ',' << s.step.increment << ',' << s.hem_height << ',' << s.max_elastic
      << ',' << s.max_viscoelastic << ',' << s.max_permanent << ',' << (s.certified ? 1 : 0) << ','
      << s.verdict << ',' << s.dome_height << '\n';
  return row.str();
}

// Rank 0: wear.csv grows by a row with every accepted wear state, so that a
// wear stopped before its end leaves the states it reached; the first call
// writes the header and the states a resumed wear had reached before.
class GrowingWearTable {
public:
  explicit GrowingWearTable(std::string path) : path_(std::move(path)) {}

  void add(const std::vector<WearStep>& steps) {
    std::ofstream table(path_, written_ == 0 ? std::ios::trunc : std::ios::app);
    if (written_ == 0) table << wear_table_header;
    for (; written_ < steps.size(); ++written_)
      table << wear_table_row(steps[written_]);
    if (!table) throw std::runtime_error("cannot write " + path_);
  }

private:
  std::string path_;
  std::size_t written_ = 0;
};

// The wear's observer: its series (wear/) and wear.csv, row by row.
WearObserver wear_series(const std::string& directory, const ClothOutputLabels& labels,
                         const std::shared_ptr<WearRun>& run, double resumed_time) {
  auto series = std::make_shared<std::unique_ptr<ClothTimeSeries>>();
  auto table = std::make_shared<GrowingWearTable>(directory + "/wear.csv");
  return [directory, series, table, labels, run,
          resumed_time](ClothProblem& problem, Vec x, const CreepCoupling& creep, double time) {
    std::vector<Eigen::Vector3d> positions;
    std::vector<element::MembraneStrain> strains;
    std::vector<ElementCreep> states;
    SartorPetscCall(problem.gather_positions(x, &positions));
    SartorPetscCall(problem.gather_strains(x, &strains));
    SartorPetscCall(creep.gather(&states));
    if (!is_root()) return;
    if (!*series) {
      make_output_directory(directory + "/wear");
      *series = resumed_time < 0.0
                    ? std::make_unique<ClothTimeSeries>(directory + "/wear", problem.mesh(), labels)
                    : std::make_unique<ClothTimeSeries>(directory + "/wear", problem.mesh(), labels,
                                                        resumed_time);
    }
    (*series)->write(time, positions, strains, creep_fields(states));
    table->add(run->report.steps);
  };
}

// The wear's resume (when --restart is a checkpoint taken within the wear)
// and its checkpoints (with --checkpoint-interval: after every wear step).
class WearCheckpoints {
public:
  // `resume`: read_wear_checkpoint's of --restart, read before the drape.
  WearCheckpoints(const CaseCheckpointing& checkpointing, std::optional<WearResume> resume,
                  const ClothProblem& problem, const std::shared_ptr<const RunCheckpoint>& drape,
                  WearRun* run)
      : resume_(std::move(resume)) {
    if (resume_) {
      check_wear_mesh(*resume_, checkpointing.restart_file, problem.mesh());
      restart_.resume = &resume_->checkpoint;
      restart_.resumed = &resume_->report;
      restart_.contact_stiffness_scale = resume_->contact_stiffness_scale;
      run->resumed_time = resume_->checkpoint.time;
      SartorPetscCall(PetscPrintf(problem.comm(),
                                  "sartor drape: resuming the wear from %s at t = %g s\n",
                                  checkpointing.restart_file.c_str(), run->resumed_time));
    }
    if (checkpointing.interval > 0.0) {
      restart_.write = wear_checkpoint_writer(checkpointing.file, drape, &run->checkpoints_written);
    }
  }
  WearCheckpoints(const WearCheckpoints&) = delete;
  WearCheckpoints& operator=(const WearCheckpoints&) = delete;
  double resumed_time() const { return resume_ ? resume_->checkpoint.time : -1.0; }
  const WearRestart& restart() const { return restart_; }

private:
  std::optional<WearResume> resume_;
  WearRestart restart_; // points into resume_
};

// --wear-poses: the mannequin of --body following the pose history, its
// pose at 0 s the draped one; nullptr without the option.
std::shared_ptr<const PosedMannequin> wear_poses(const Options& options) {
  if (!options.is_set("wear-poses")) return nullptr;
  const std::optional<MannequinModel> model =
      contact::spec_mannequin(options.text("body"), "option --body");
  if (!model) {
    throw InputError("option --wear-poses: the body must be the mannequin (--body \"mannequin "
                     "[measurements=FILE.json] [pose=...] ...\"), got '" +
                     options.text("body") + "'");
  }
  contact::PoseHistory history;
  try {
    history = contact::parse_pose_history(options.text("wear-poses"));
  } catch (const InputError& error) {
    throw InputError(std::string("option --wear-poses: ") + error.what());
  }
  const Pose start = history.at(0.0);
  for (const JointRange& joint : pose_joints()) {
    if (start.angle(joint.name) != model->pose().angle(joint.name)) {
      throw InputError("option --wear-poses: at 0 s " + joint.name + " is at " +
                       format_number(start.angle(joint.name)) +
                       " deg, but the garment is draped "
                       "with it at " +
                       format_number(model->pose().angle(joint.name)) +
                       " deg (--body's pose=): the wear starts from the draped pose");
    }
  }
  try {
    return std::make_shared<const PosedMannequin>(*model, history,
                                                  options.positive_real("wear-pose-step"));
  } catch (const InputError& error) {
    throw InputError(std::string("option --wear-poses: ") + error.what());
  }
}

// The worn problem's --body, made to follow `poses` on the problem's clock
// (its friction, pivot and rigid motion kept).
void follow_poses(const Options& options, const std::shared_ptr<const PosedMannequin>& poses,
                  ClothProblem& problem) {
  const std::string name =
      contact::parse_body(options.text("body"), "option --body", "body").name();
  for (contact::Body& body : problem.bodies) {
    if (body.name() != name) continue;
    contact::Body moving(name, std::make_shared<ShapeOnClock>(poses, &problem.time), body.pivot());
    moving.motion = body.motion;
    moving.friction = body.friction;
    body = std::move(moving);
    return;
  }
  throw InputError("option --wear-poses: the worn problem has no body named '" + name + "'");
}

} // namespace

void attach_wear(const Options& options, const std::string& directory,
                 const ClothOutputLabels& labels, CaseCloth* cloth,
                 const std::shared_ptr<WearRun>& run) {
  const std::shared_ptr<const PosedMannequin> poses = wear_poses(options);
  const CreepCase creep_case = read_creep_case(options);
  WearOptions settings = wear_options(options, creep_case);
  if (poses) {
    settings.landings = poses->knots();
    settings.wear.follow_bodies = true;
  }
  if (creep_case.scheme == CreepScheme::monolithic && options.flag("self-contact")) {
    throw InputError("option --self-contact: the monolithic creep scheme has no potential, and "
                     "self-contact needs the minimiser: give --creep-scheme staggered");
  }
  run->scheme = creep_scheme_name(creep_case.scheme);
  run->fabrics = cloth->fabrics;
  const std::vector<CreepMaterial> creep = wear_creep_materials(creep_case, cloth->fabrics);
  const std::vector<double> gravity = option_numbers(options, "gravity", 3);
  const CaseCheckpointing checkpointing = case_checkpointing(options, directory);
  auto resume = std::make_shared<std::optional<WearResume>>();
  if (!checkpointing.restart_file.empty())
    *resume = read_wear_checkpoint(checkpointing.restart_file);
  cloth->after_statics = [&options, settings, poses, creep, gravity, directory, labels, run,
                          checkpointing, resume](
                             ClothProblem& problem, const std::vector<ClothMaterial>& materials,
                             const std::vector<SeamSpring>& springs, Vec x,
                             const std::shared_ptr<const RunCheckpoint>& drape) {
    const double cpu_start = process_cpu_seconds();
    WearGarment garment;
    garment.materials = materials;
    garment.creep = creep;
    garment.springs = springs;
    garment.gravity = {gravity[0], gravity[1], gravity[2]};
    garment.self_contact = problem.self_contact_settings();
    std::vector<Eigen::Vector3d> draped;
    SartorPetscCall(problem.gather_positions(x, &draped));
    std::vector<double> flat;
    for (const Eigen::Vector3d& p : draped)
      flat.insert(flat.end(), {p.x(), p.y(), p.z()});
    flat.resize(3 * problem.mesh().vertex_count());
    MPI_Bcast(flat.data(), int(flat.size()), MPI_DOUBLE, 0, problem.comm());
    draped.resize(problem.mesh().vertex_count());
    for (std::size_t v = 0; v < draped.size(); ++v)
      draped[v] = {flat[3 * v], flat[3 * v + 1], flat[3 * v + 2]};
    select_vertices(options, problem.mesh(), draped, &garment);
    run->held = garment.held;
    run->hem = garment.hem;
    SartorPetscCall(PetscPrintf(problem.comm(),
                                "sartor drape: wearing for %g s (%s coupling), %zu vertices held "
                                "at take-off, %zu hem vertices\n",
                                settings.wear.time_end, run->scheme.c_str(), garment.held.size(),
                                garment.hem.size()));
    if (poses) follow_poses(options, poses, problem);
    const WearCheckpoints checkpoints(checkpointing, std::move(*resume), problem, drape, run.get());
    SartorPetscCall(solve_wear(problem, x, garment, settings, &run->report,
                               wear_series(directory, labels, run, checkpoints.resumed_time()),
                               checkpoints.restart()));
    if (is_root()) {
      make_output_directory(directory + "/takeoff");
      ClothTimeSeries series(directory + "/takeoff", problem.mesh(), labels);
      for (const TakeOffReport& taken : run->report.take_offs)
        series.write(taken.wear_time, taken.positions,
                     std::vector<element::MembraneStrain>(problem.mesh().triangle_count()),
                     creep_fields(taken.creep));
    }
    run->ran = true;
    run->cpu_seconds = process_cpu_seconds() - cpu_start;
  };
}

namespace {

nlohmann::json per_panel_permanent(const TakeOffReport& taken, const ClothOutputLabels& labels) {
  std::map<int, std::pair<double, double>> largest_and_sum;
  std::map<int, long> count;
  for (std::size_t t = 0; t < taken.creep.size(); ++t) {
    const int panel = labels.panel_of_triangle.empty() ? 0 : labels.panel_of_triangle[t];
    const double p = std::max(taken.creep[t].warp.permanent, taken.creep[t].weft.permanent);
    auto& entry = largest_and_sum[panel];
    entry.first = std::max(entry.first, p);
    entry.second += p;
    ++count[panel];
  }
  nlohmann::json panels = nlohmann::json::object();
  for (const auto& [panel, entry] : largest_and_sum) {
    const std::string name = std::size_t(panel) < labels.panels.size()
                                 ? labels.panels[std::size_t(panel)]
                                 : std::to_string(panel);
    panels[name] = {{"max_permanent_strain", entry.first},
                    {"mean_permanent_strain", entry.second / double(count[panel])}};
  }
  return panels;
}

} // namespace

void add_wear_summary(const WearRun& run, const ClothOutputLabels& labels,
                      nlohmann::json& summary) {
  const WearReport& report = run.report;
  long accepted = 0, newton = 0, certified = 0;
  for (const WearStep& step : report.steps) {
    if (step.step.step == 0) continue;
    ++accepted;
    newton += long(step.step.newton_iterations);
    certified += step.certified ? 1 : 0;
  }
  nlohmann::json take_offs = nlohmann::json::array();
  for (const TakeOffReport& taken : report.take_offs) {
    take_offs.push_back({{"wear_time_s", taken.wear_time},
                         {"converged", taken.converged},
                         {"reason", taken.reason},
                         {"hem_height_m", taken.hem_height},
                         {"hem_drop_m", taken.hem_drop},
                         {"bagging_height_m", taken.bagging_height},
                         {"bagging_vertex", taken.bagging_vertex},
                         {"dome_height_m", taken.dome_height},
                         {"excess_area_m2", taken.excess_area},
                         {"max_permanent_strain", taken.max_permanent},
                         {"max_viscoelastic_strain", taken.max_viscoelastic},
                         {"newton_iterations", taken.newton_iterations},
                         {"recovery_steps", taken.recovery_steps},
                         {"saddle_escapes", taken.saddle_escapes},
                         {"certificate", taken.certificate.verdict()},
                         {"certified", taken.certificate.certified()},
                         {"panels", per_panel_permanent(taken, labels)}});
  }
  summary["wear"] = {
      {"scheme", run.scheme},
      {"fabrics", run.fabrics},
      {"completed", report.wear.completed},
      {"reason", report.wear.completed ? "reached the end time" : report.wear.reason},
      {"final_time_s", report.wear.final_time},
      {"steps", accepted},
      {"rejected_steps", report.wear.rejected_steps},
      {"newton_iterations", newton},
      {"newton_iterations_per_step", accepted ? double(newton) / double(accepted) : 0.0},
      {"certified_steps", certified},
      {"final_certificate", report.final_certificate.verdict()},
      {"held_vertices", run.held.size()},
      {"hem_vertices", run.hem.size()},
      {"fresh_hung_hem_height_m", report.fresh_hem_height},
      {"fresh_hung_converged", report.fresh_converged},
      {"take_offs", take_offs},
      {"checkpoints_written", run.checkpoints_written},
      {"resumed_at_s",
       run.resumed_time >= 0.0 ? nlohmann::json(run.resumed_time) : nlohmann::json()},
      {"cpu_s", run.cpu_seconds}};
}

void print_wear(const WearRun& run) {
  const WearReport& report = run.report;
  long newton = 0;
  for (const WearStep& step : report.steps)
    newton += step.step.step > 0 ? long(step.step.newton_iterations) : 0L;
  const long steps = long(report.steps.size()) - 1;
  SartorPetscCall(PetscPrintf(
      PETSC_COMM_WORLD,
      "sartor drape: wear to t = %g s (%s) in %ld steps (%ld rejected), %.1f Newton iterations "
      "per step, %ld of %zu states certified; %.1f s CPU; final state: %s\n",
      report.wear.final_time, report.wear.completed ? "completed" : report.wear.reason.c_str(),
      steps, report.wear.rejected_steps, steps > 0 ? double(newton) / double(steps) : 0.0,
      report.certified_steps, report.steps.size(), run.cpu_seconds,
      report.final_certificate.verdict().c_str()));
  // Certified per step unless --no-step-certificate (then no verdicts).
  const auto failed = [](const WearStep& s) { return !s.certified && !s.verdict.empty(); };
  const auto first = std::find_if(report.steps.begin(), report.steps.end(), failed);
  if (first != report.steps.end()) {
    std::ostringstream warning;
    warning << std::count_if(report.steps.begin(), report.steps.end(), failed) << " of "
            << report.steps.size()
            << " wear states are not certified, the first at t = " << first->step.time
            << " s: " << first->verdict << " (wear.csv's column certificate; docs/wear.md)";
    print_warnings({warning.str()});
  }
  if (!report.take_offs.empty() && !report.fresh_converged) {
    print_warnings({"the fresh garment's hanging equilibrium, which hem drop and bagging height "
                    "are measured against, did not converge: they compare with a garment that is "
                    "not at rest and mean nothing (docs/wear.md#take-off)"});
  }
  for (const TakeOffReport& t : report.take_offs) {
    SartorPetscCall(PetscPrintf(
        PETSC_COMM_WORLD,
        "  taken off at %g s, hung %s: hem drop %.3e m, bagging height %.3e m, permanent dome "
        "height %.3e m, permanent strain up to %.3e (viscoelastic left %.1e); certificate: %s\n",
        t.wear_time, t.converged ? "and recovered" : ("(" + t.reason + ")").c_str(), t.hem_drop,
        t.bagging_height, t.dome_height, t.max_permanent, t.max_viscoelastic,
        t.certificate.verdict().c_str()));
  }
}

void write_wear_tables(const std::string& directory, const WearRun& run) {
  if (!is_root()) return;
  std::ostringstream wear;
  wear << wear_table_header;
  for (const WearStep& s : run.report.steps)
    wear << wear_table_row(s);
  write_file_atomically(directory + "/wear.csv", wear.str());
  std::ostringstream takeoff;
  takeoff.precision(10);
  takeoff << "wear_time_s,hem_height_m,hem_drop_m,bagging_height_m,max_permanent_strain,"
             "max_viscoelastic_strain,certified,dome_height_m,excess_area_m2\n";
  for (const TakeOffReport& t : run.report.take_offs) {
    takeoff << t.wear_time << ',' << t.hem_height << ',' << t.hem_drop << ',' << t.bagging_height
            << ',' << t.max_permanent << ',' << t.max_viscoelastic << ','
            << (t.certificate.certified() ? 1 : 0) << ',' << t.dome_height << ',' << t.excess_area
            << '\n';
  }
  write_file_atomically(directory + "/takeoff.csv", takeoff.str());
}

} // namespace sartor
