#include "app/static_checkpoint.hpp"

#include "app/commands.hpp"
#include "common/error.hpp"

#include <nlohmann/json.hpp>

namespace sartor {

namespace {

constexpr const char* static_kind = "static";

// /state of a static solve's checkpoint: the report so far. JSON writes
// doubles with 17 significant digits, so they read back exactly. Within a
// level of a drape on several levels, the level's record as "drape_level".
std::string state_text(const StaticReport& r, const std::string& drape_level) {
  nlohmann::json steps = nlohmann::json::array();
  for (const LoadStepReport& s : r.steps) {
    steps.push_back({s.load_factor, s.converged, s.reason, s.newton_iterations, s.linear_iterations,
                     s.pseudo_steps, s.residual_norm, s.tolerance});
  }
  nlohmann::json rounds = nlohmann::json::array();
  for (const ContactRound& c : r.rounds) {
    rounds.push_back(
        {c.newton_iterations, c.residual_norm, c.sliding_vertices, c.contact_stiffness_scale});
  }
  const auto& m = r.minimiser;
  nlohmann::json state{
      {"kind", static_kind},
      {"report",
       {{"converged", r.converged},
        {"reason", r.reason},
        {"steps", steps},
        {"newton_iterations", r.newton_iterations},
        {"linear_iterations", r.linear_iterations},
        {"pseudo_steps", r.pseudo_steps},
        {"initial_residual_norm", r.initial_residual_norm},
        {"minimised", r.minimised},
        {"minimiser",
         {m.step_bound_cuts, m.regularised_steps, m.residual_rule_trials, m.failed_factorisations,
          m.exact_steps, m.extended_steps}},
        {"sewing_stages", r.sewing_stages},
        {"contact_rounds", r.contact_rounds},
        {"contact_stiffness_scale", r.contact_stiffness_scale},
        {"sliding_vertices", r.sliding_vertices},
        {"contact_round_failed", r.contact_round_failed},
        {"friction_consistent", r.friction_consistent},
        {"anchored_residual_norm", r.anchored_residual_norm},
        {"consistency_tolerance", r.consistency_tolerance},
        {"rounds", rounds},
        {"unconverged_stages", r.unconverged_stages},
        {"ramp", {r.ramp.under_way, r.ramp.reached, r.ramp.increment, r.ramp.cutbacks}}}}};
  if (!drape_level.empty()) state["drape_level"] = nlohmann::json::parse(drape_level);
  return state.dump();
}

StaticReport report_from(const nlohmann::json& state) {
  if (state.at("kind") != static_kind) throw std::invalid_argument("not of a static solve");
  const nlohmann::json& j = state.at("report");
  StaticReport r;
  r.converged = j.at("converged").get<bool>();
  r.reason = j.at("reason").get<std::string>();
  for (const nlohmann::json& s : j.at("steps")) {
    // The solve's tolerance decides whether the contact rounds after a
    // resume find the friction consistent (absent before 2026-12-07: 0,
    // and every round then ran).
    r.steps.push_back({s.at(0).get<double>(), s.at(1).get<bool>(), s.at(2).get<std::string>(),
                       s.at(3).get<PetscInt>(), s.at(4).get<PetscInt>(), s.at(5).get<PetscInt>(),
                       s.at(6).get<double>(), s.size() > 7 ? s.at(7).get<double>() : 0.0});
  }
  r.newton_iterations = j.at("newton_iterations").get<PetscInt>();
  r.linear_iterations = j.at("linear_iterations").get<PetscInt>();
  r.pseudo_steps = j.at("pseudo_steps").get<PetscInt>();
  r.initial_residual_norm = j.at("initial_residual_norm").get<double>();
  r.minimised = j.at("minimised").get<bool>();
  const nlohmann::json& m = j.at("minimiser");
  r.minimiser = {m.at(0).get<PetscInt>(), m.at(1).get<PetscInt>(), m.at(2).get<PetscInt>(),
                 m.at(3).get<PetscInt>(), m.at(4).get<PetscInt>(),
                 // absent from checkpoints written before 2026-12-07
                 m.size() > 5 ? m.at(5).get<PetscInt>() : 0};
  r.sewing_stages = j.at("sewing_stages").get<int>();
  r.contact_rounds = j.at("contact_rounds").get<int>();
  r.contact_stiffness_scale = j.at("contact_stiffness_scale").get<double>();
  r.sliding_vertices = j.at("sliding_vertices").get<long>();
  r.contact_round_failed = j.at("contact_round_failed").get<bool>();
  r.friction_consistent = j.at("friction_consistent").get<bool>();
  r.anchored_residual_norm = j.at("anchored_residual_norm").get<double>();
  r.consistency_tolerance = j.at("consistency_tolerance").get<double>();
  for (const nlohmann::json& c : j.at("rounds")) {
    r.rounds.push_back({c.at(0).get<PetscInt>(), c.at(1).get<double>(), c.at(2).get<long>(),
                        c.at(3).get<double>()});
  }
  // Checkpoints written before these were reported have none.
  if (j.contains("unconverged_stages"))
    r.unconverged_stages = j.at("unconverged_stages").get<std::vector<int>>();
  // Checkpoints written before load steps were checkpointed have no ramp.
  if (j.contains("ramp")) {
    const nlohmann::json& ramp = j.at("ramp");
    r.ramp = {ramp.at(0).get<bool>(), ramp.at(1).get<double>(), ramp.at(2).get<double>(),
              ramp.at(3).get<int>()};
  }
  if (r.sewing_stages < 1 || r.contact_rounds < 0 || !(r.contact_stiffness_scale > 0.0)) {
    throw std::invalid_argument("its stage, round or penalty counts are not valid");
  }
  if (r.ramp.under_way && !(r.ramp.reached >= 0.0 && r.ramp.reached < 1.0 &&
                            r.ramp.increment > 0.0 && r.ramp.increment <= 1.0)) {
    throw std::invalid_argument("its load ramp is not valid");
  }
  return r;
}

} // namespace

PetscErrorCode StaticResume::restore(ClothProblem& problem, Vec x) const {
  PetscFunctionBeginUser;
  PetscCall(problem.set_solution(checkpoint.positions, x));
  problem.restore_anchors(checkpoint.anchors);
  problem.contact.stiffness_scale = report.contact_stiffness_scale;
  PetscFunctionReturn(0);
}

StaticResume read_static_checkpoint(const std::string& path, const ClothProblem& problem) {
  StaticResume resume;
  resume.checkpoint = first_phase(read_checkpoint(path));
  const RunCheckpoint& checkpoint = resume.checkpoint;
  if (checkpoint.state.empty() || !checkpoint.velocities.empty()) {
    throw InputError(path + ": the checkpoint is not of a static solve (a dynamic or creep "
                            "run's?); resume it as one");
  }
  const std::size_t vertices = problem.mesh().vertex_count();
  if (checkpoint.positions.size() != vertices) {
    throw InputError(path + ": the checkpoint has " + std::to_string(checkpoint.positions.size()) +
                     " vertices, the case " + std::to_string(vertices) +
                     ": it belongs to another case or mesh");
  }
  try {
    const nlohmann::json state = nlohmann::json::parse(checkpoint.state);
    resume.report = report_from(state);
    if (state.contains("drape_level")) resume.drape_level = state.at("drape_level").dump();
  } catch (const std::exception& error) {
    throw InputError(path + ": the checkpoint's /state is not a static solve's state (" +
                     error.what() + ")");
  }
  return resume;
}

std::function<PetscErrorCode(Vec, const StaticReport&)>
static_checkpoint_writer(ClothProblem& problem, const CaseCheckpointing& checkpointing,
                         long* written, std::shared_ptr<const RunCheckpoint>* last) {
  return [&problem, checkpointing, written, last](Vec x,
                                                  const StaticReport& report) -> PetscErrorCode {
    RunCheckpoint checkpoint;
    PetscFunctionBeginUser;
    // A static solve has no clock: its load steps (those of the stages and
    // rounds included) say where it stands.
    checkpoint.next_step = 1.0;
    checkpoint.step = long(report.steps.size());
    checkpoint.load_factor = problem.load_factor;
    PetscCall(problem.gather_positions(x, &checkpoint.positions));
    PetscCall(problem.gather_anchors(&checkpoint.anchors));
    if (is_root()) {
      // Within a drape level: the level's start, which its mesh holds.
      if (!checkpointing.drape_level.empty()) checkpoint.start_positions = problem.mesh().positions;
      checkpoint.state = state_text(report, checkpointing.drape_level);
      write_checkpoint(checkpointing.file, checkpoint);
      *last = std::make_shared<const RunCheckpoint>(std::move(checkpoint));
    }
    ++*written;
    PetscFunctionReturn(0);
  };
}

PetscErrorCode write_final_static_state(ClothProblem& problem, Vec x,
                                        const CaseCheckpointing& checkpointing,
                                        const StaticReport& report) {
  PetscFunctionBeginUser;
  CaseCheckpointing final_state = checkpointing;
  final_state.file = checkpointing.final_state;
  // Not the solve's last checkpoint (a wear's /before): that stays the solver's.
  long written = 0;
  std::shared_ptr<const RunCheckpoint> last;
  PetscCall(static_checkpoint_writer(problem, final_state, &written, &last)(x, report));
  PetscFunctionReturn(0);
}

} // namespace sartor
