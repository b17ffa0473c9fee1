#include "app/dynamic_case.hpp"

#include "app/commands.hpp"
#include "common/error.hpp"

#include <nlohmann/json.hpp>

namespace sartor {

namespace {

constexpr const char* dynamic_kind = "dynamic";

nlohmann::json step_json(const DynamicStepReport& s) {
  return {{"step", s.step},
          {"time", s.time},
          {"dt", s.dt},
          {"newton_iterations", s.newton_iterations},
          {"linear_iterations", s.linear_iterations},
          {"rejected", s.rejected},
          {"reason", s.reason},
          {"kinetic_energy", s.kinetic_energy},
          {"potential_energy", s.potential_energy},
          {"static_residual_norm", s.static_residual_norm},
          {"velocities_reset", s.velocities_reset},
          {"output", s.output}};
}

DynamicStepReport step_from(const nlohmann::json& j) {
  DynamicStepReport s;
  s.step = j.at("step").get<PetscInt>();
  s.time = j.at("time").get<double>();
  s.dt = j.at("dt").get<double>();
  s.newton_iterations = j.at("newton_iterations").get<PetscInt>();
  s.linear_iterations = j.at("linear_iterations").get<PetscInt>();
  s.rejected = j.at("rejected").get<int>();
  s.reason = j.at("reason").get<std::string>();
  s.kinetic_energy = j.at("kinetic_energy").get<double>();
  s.potential_energy = j.at("potential_energy").get<double>();
  s.static_residual_norm = j.at("static_residual_norm").get<double>();
  s.velocities_reset = j.at("velocities_reset").get<bool>();
  s.output = j.at("output").get<bool>();
  return s;
}

// /state of a dynamic run's checkpoint. JSON writes doubles with 17
// significant digits, so they read back exactly.
std::string state_text(const DynamicControl& c, const DynamicReport& report,
                       const std::vector<Eigen::Vector3d>& probe_history,
                       const std::string& drape_level) {
  nlohmann::json steps = nlohmann::json::array();
  for (const DynamicStepReport& s : report.steps)
    steps.push_back(step_json(s));
  nlohmann::json probe = nlohmann::json::array();
  for (const Eigen::Vector3d& d : probe_history)
    probe.push_back({d.x(), d.y(), d.z()});
  nlohmann::json state{{"kind", dynamic_kind},
                       {"control",
                        {{"start", c.start},
                         {"time", c.time},
                         {"next_step", c.next_step},
                         {"step", c.step},
                         {"previous_kinetic", c.previous_kinetic},
                         {"initial_residual", c.initial_residual}}},
                       {"report",
                        {{"at_rest", report.at_rest},
                         {"newton_iterations", report.newton_iterations},
                         {"linear_iterations", report.linear_iterations},
                         {"rejected_steps", report.rejected_steps},
                         {"velocity_resets", report.velocity_resets},
                         {"steps", steps}}},
                       {"probe_history", probe}};
  if (!drape_level.empty()) state["drape_level"] = nlohmann::json::parse(drape_level);
  return state.dump();
}

void read_state(const std::string& text, DynamicResume* resume) {
  const nlohmann::json state = nlohmann::json::parse(text);
  if (state.at("kind") != dynamic_kind) throw std::invalid_argument("not of a dynamic run");
  const nlohmann::json& c = state.at("control");
  DynamicControl& control = resume->control;
  control.start = c.at("start").get<double>();
  control.time = c.at("time").get<double>();
  control.next_step = c.at("next_step").get<double>();
  control.step = c.at("step").get<PetscInt>();
  control.previous_kinetic = c.at("previous_kinetic").get<double>();
  control.initial_residual = c.at("initial_residual").get<double>();
  const nlohmann::json& r = state.at("report");
  DynamicReport& report = resume->report;
  report.at_rest = r.at("at_rest").get<bool>();
  report.newton_iterations = r.at("newton_iterations").get<PetscInt>();
  report.linear_iterations = r.at("linear_iterations").get<PetscInt>();
  report.rejected_steps = r.at("rejected_steps").get<PetscInt>();
  report.velocity_resets = r.at("velocity_resets").get<PetscInt>();
  for (const nlohmann::json& s : r.at("steps"))
    report.steps.push_back(step_from(s));
  for (const nlohmann::json& d : state.at("probe_history"))
    resume->probe_history.emplace_back(d.at(0).get<double>(), d.at(1).get<double>(),
                                       d.at(2).get<double>());
  if (state.contains("drape_level")) resume->drape_level = state.at("drape_level").dump();
  if (report.steps.empty() || !(control.next_step > 0.0) || control.time < control.start) {
    throw std::invalid_argument("its step controller is not valid");
  }
}

} // namespace

std::size_t DynamicResume::series_states() const {
  std::size_t count = 0;
  for (const DynamicStepReport& s : report.steps)
    count += s.output ? 1 : 0;
  return count;
}

PetscErrorCode DynamicResume::restore(ClothProblem& problem, Vec x, Vec v) const {
  PetscFunctionBeginUser;
  problem.time = checkpoint.time;
  problem.load_factor = checkpoint.load_factor;
  PetscCall(problem.set_solution(checkpoint.positions, x));
  PetscCall(problem.set_solution(checkpoint.velocities, v));
  problem.restore_anchors(checkpoint.anchors);
  PetscFunctionReturn(0);
}

DynamicResume read_dynamic_checkpoint(const std::string& path, const ClothProblem& problem) {
  DynamicResume resume;
  resume.checkpoint = read_checkpoint(path);
  const RunCheckpoint& checkpoint = resume.checkpoint;
  if (checkpoint.state.empty() || checkpoint.velocities.empty()) {
    throw InputError(path + ": the checkpoint is not of an --analysis dynamic run (a creep "
                            "run's?); resume it as one");
  }
  const std::size_t vertices = problem.mesh().vertex_count();
  if (checkpoint.positions.size() != vertices || checkpoint.velocities.size() != vertices) {
    throw InputError(path + ": the checkpoint has " + std::to_string(checkpoint.positions.size()) +
                     " vertices, the case " + std::to_string(vertices) +
                     ": it belongs to another case or mesh");
  }
  try {
    read_state(checkpoint.state, &resume);
  } catch (const std::exception& error) {
    throw InputError(path + ": the checkpoint's /state is not a dynamic run's state (" +
                     error.what() + ")");
  }
  if (resume.control.time != checkpoint.time) {
    throw InputError(path + ": the checkpoint's /state is at another time than its /time");
  }
  return resume;
}

double checkpoint_time(const std::string& path) {
  return read_checkpoint(path).time;
}

std::function<PetscErrorCode(const DynamicControl&, Vec, Vec)>
dynamic_checkpoint_writer(ClothProblem& problem, const CaseCheckpointing& checkpointing,
                          const DynamicReport& report,
                          const std::vector<Eigen::Vector3d>& probe_history, long* written) {
  return [&problem, checkpointing, &report, &probe_history,
          written](const DynamicControl& control, Vec x, Vec v) -> PetscErrorCode {
    RunCheckpoint checkpoint;
    PetscFunctionBeginUser;
    checkpoint.time = control.time;
    checkpoint.next_step = control.next_step;
    checkpoint.step = long(control.step);
    checkpoint.load_factor = problem.load_factor;
    PetscCall(problem.gather_positions(x, &checkpoint.positions));
    PetscCall(problem.gather_positions(v, &checkpoint.velocities));
    // Gathered as their places: a pin's velocity is not a dof.
    for (int pin : problem.pinned())
      if (!checkpoint.velocities.empty()) checkpoint.velocities[std::size_t(pin)].setZero();
    PetscCall(problem.gather_anchors(&checkpoint.anchors));
    if (is_root()) {
      // Within a drape level: the level's start, which its mesh holds.
      if (!checkpointing.drape_level.empty()) checkpoint.start_positions = problem.mesh().positions;
      checkpoint.state = state_text(control, report, probe_history, checkpointing.drape_level);
      write_checkpoint(checkpointing.file, checkpoint);
    }
    ++*written;
    PetscFunctionReturn(0);
  };
}

} // namespace sartor
