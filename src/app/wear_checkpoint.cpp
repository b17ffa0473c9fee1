#include "app/wear_checkpoint.hpp"

#include "app/commands.hpp"
#include "common/error.hpp"
#include "solvers/certificate.hpp"

#include <nlohmann/json.hpp>

#include <limits>

namespace sartor {

namespace {

constexpr const char* wear_kind = "wear";

nlohmann::json step_json(const WearStep& s) {
  const CreepStepReport& c = s.step;
  return {c.step,      c.time,    c.dt,         c.load_factor, c.newton_iterations, c.rejected,
          c.increment, c.output,  s.hem_height, s.max_elastic, s.max_viscoelastic,  s.max_permanent,
          s.certified, s.verdict, s.dome_height};
}

WearStep step_from(const nlohmann::json& j) {
  WearStep s;
  CreepStepReport& c = s.step;
  c.step = j.at(0).get<long>();
  c.time = j.at(1).get<double>();
  c.dt = j.at(2).get<double>();
  c.load_factor = j.at(3).get<double>();
  c.newton_iterations = j.at(4).get<PetscInt>();
  c.rejected = j.at(5).get<int>();
  c.increment = j.at(6).get<double>();
  c.output = j.at(7).get<bool>();
  s.hem_height = j.at(8).get<double>();
  s.max_elastic = j.at(9).get<double>();
  s.max_viscoelastic = j.at(10).get<double>();
  s.max_permanent = j.at(11).get<double>();
  s.certified = j.at(12).get<bool>();
  s.verdict = j.at(13).get<std::string>();
  if (j.size() > 14) s.dome_height = j.at(14).get<double>(); // written since 2026-12-07
  return s;
}

nlohmann::json take_off_json(const TakeOffReport& t) {
  return {{"wear_time", t.wear_time},
          {"converged", t.converged},
          {"reason", t.reason},
          {"hem_height", t.hem_height},
          {"hem_drop", t.hem_drop},
          {"bagging_height", t.bagging_height},
          {"bagging_vertex", t.bagging_vertex},
          {"dome_height", t.dome_height},
          {"excess_area", t.excess_area},
          {"max_permanent", t.max_permanent},
          {"max_viscoelastic", t.max_viscoelastic},
          {"newton_iterations", t.newton_iterations},
          {"recovery_steps", t.recovery_steps},
          {"rejected_steps", t.rejected_steps},
          {"saddle_escapes", t.saddle_escapes},
          {"certificate", certificate_json(t.certificate)},
          {"positions", position_rows(t.positions)},
          {"creep", creep_rows(t.creep)}};
}

TakeOffReport take_off_from(const nlohmann::json& j) {
  TakeOffReport t;
  t.wear_time = j.at("wear_time").get<double>();
  t.converged = j.at("converged").get<bool>();
  t.reason = j.at("reason").get<std::string>();
  t.hem_height = j.at("hem_height").get<double>();
  t.hem_drop = j.at("hem_drop").get<double>();
  t.bagging_height = j.at("bagging_height").get<double>();
  t.bagging_vertex = j.at("bagging_vertex").get<long>();
  // Checkpoints written before the dome height: not known (NaN, null in JSON).
  t.dome_height = j.value("dome_height", std::numeric_limits<double>::quiet_NaN());
  t.excess_area = j.value("excess_area", std::numeric_limits<double>::quiet_NaN());
  t.max_permanent = j.at("max_permanent").get<double>();
  t.max_viscoelastic = j.at("max_viscoelastic").get<double>();
  t.newton_iterations = j.at("newton_iterations").get<PetscInt>();
  t.recovery_steps = j.at("recovery_steps").get<long>();
  t.rejected_steps = j.at("rejected_steps").get<long>();
  t.saddle_escapes = j.value("saddle_escapes", 0L); // absent before 2026-12-08
  t.certificate = certificate_from_json(j.at("certificate"));
  t.positions = positions_from_rows(j.at("positions").get<std::vector<double>>());
  t.creep = creep_from_rows(j.at("creep").get<std::vector<double>>());
  return t;
}

// /state of a wear's checkpoint. JSON writes doubles with 17 significant
// digits, so they read back exactly.
std::string state_text(const WearReport& report, double contact_stiffness_scale) {
  nlohmann::json steps = nlohmann::json::array(), take_offs = nlohmann::json::array();
  for (const WearStep& s : report.steps)
    steps.push_back(step_json(s));
  for (const TakeOffReport& t : report.take_offs)
    take_offs.push_back(take_off_json(t));
  return nlohmann::json{{"kind", wear_kind},
                        {"contact_stiffness_scale", contact_stiffness_scale},
                        {"certified_steps", report.certified_steps},
                        {"newton_iterations", report.wear.newton_iterations},
                        {"rejected_steps", report.wear.rejected_steps},
                        {"steps", steps},
                        {"take_offs", take_offs}}
      .dump();
}

WearResume resume_from(const nlohmann::json& state, RunCheckpoint checkpoint) {
  WearResume resume;
  resume.contact_stiffness_scale = state.at("contact_stiffness_scale").get<double>();
  WearReport& r = resume.report;
  r.certified_steps = state.at("certified_steps").get<long>();
  r.wear.newton_iterations = state.at("newton_iterations").get<PetscInt>();
  r.wear.rejected_steps = state.at("rejected_steps").get<long>();
  for (const nlohmann::json& s : state.at("steps"))
    r.steps.push_back(step_from(s));
  for (const nlohmann::json& t : state.at("take_offs"))
    r.take_offs.push_back(take_off_from(t));
  if (!(resume.contact_stiffness_scale > 0.0) || r.steps.empty() ||
      r.steps.back().step.time != checkpoint.time) {
    throw std::invalid_argument("its steps do not end at the checkpoint's time");
  }
  resume.checkpoint = std::move(checkpoint);
  return resume;
}

} // namespace

bool within_wear(const std::string& path) {
  return read_checkpoint(path).before != nullptr;
}

std::optional<WearResume> read_wear_checkpoint(const std::string& path) {
  RunCheckpoint checkpoint = read_checkpoint(path);
  if (!checkpoint.before) return std::nullopt;
  WearResume resume;
  try {
    const nlohmann::json state = nlohmann::json::parse(checkpoint.state);
    if (state.at("kind") != wear_kind) throw std::invalid_argument("not of a wear");
    resume = resume_from(state, std::move(checkpoint));
  } catch (const std::exception& error) {
    throw InputError(path + ": the checkpoint's /state is not a wear's state (" + error.what() +
                     ")");
  }
  return resume;
}

void check_wear_mesh(const WearResume& resume, const std::string& path, const TriangleMesh& mesh) {
  const RunCheckpoint& worn = resume.checkpoint;
  bool take_offs_fit = true;
  for (const TakeOffReport& t : resume.report.take_offs)
    take_offs_fit = take_offs_fit && t.positions.size() == mesh.vertex_count() &&
                    t.creep.size() == mesh.triangle_count();
  if (worn.positions.size() != mesh.vertex_count() || worn.creep.size() != mesh.triangle_count() ||
      !take_offs_fit) {
    throw InputError(path + ": the wear's states do not have the garment's " +
                     std::to_string(mesh.vertex_count()) + " vertices and " +
                     std::to_string(mesh.triangle_count()) +
                     " triangles: the checkpoint belongs to another garment or mesh");
  }
}

std::function<PetscErrorCode(ClothProblem&, Vec, const CreepCoupling&, const CreepStepReport&,
                             double, const WearReport&)>
wear_checkpoint_writer(const std::string& file, std::shared_ptr<const RunCheckpoint> drape,
                       long* written) {
  if (is_root() && !drape) {
    throw InputError("wear checkpoints: the drape wrote no checkpoint to carry (" + file + ")");
  }
  return [file, drape, written](ClothProblem& worn, Vec x, const CreepCoupling& creep,
                                const CreepStepReport& step, double next_step,
                                const WearReport& report) -> PetscErrorCode {
    RunCheckpoint checkpoint;
    PetscFunctionBeginUser;
    checkpoint.time = step.time;
    checkpoint.next_step = next_step;
    checkpoint.step = step.step;
    checkpoint.load_factor = worn.load_factor;
    PetscCall(worn.gather_positions(x, &checkpoint.positions));
    PetscCall(creep.gather(&checkpoint.creep));
    PetscCall(worn.gather_anchors(&checkpoint.anchors));
    if (is_root()) {
      checkpoint.state = state_text(report, worn.contact.stiffness_scale);
      checkpoint.before = drape;
      write_checkpoint(file, checkpoint);
    }
    ++*written;
    PetscFunctionReturn(0);
  };
}

} // namespace sartor
