#include "solvers/creep_analysis.hpp"

#include "common/error.hpp"
#include "solvers/incremental_system.hpp"
#include "solvers/progress_clock.hpp"
#include "solvers/step_controller.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>

namespace sartor {

namespace {

void check(const CreepOptions& options, double start) {
  const auto positive = [](double value, const char* name) {
    if (!(value > 0.0) || !std::isfinite(value)) {
      throw InputError(std::string("creep: ") + name + " must be a positive number, got " +
                       std::to_string(value));
    }
  };
  positive(options.time_step, "the time step");
  positive(options.min_step, "the smallest time step");
  positive(options.creep_tolerance, "the creep tolerance");
  if (!(options.time_end > start)) {
    throw InputError("creep: the end time " + std::to_string(options.time_end) +
                     " s is not after the start time " + std::to_string(start) + " s");
  }
  if (!(options.max_step >= 0.0) || !(options.output_interval >= 0.0) ||
      !(options.damping >= 0.0)) {
    throw InputError(
        "creep: the largest time step, the output interval and the damping must not be negative");
  }
}

// The times steps must end on besides the end: the knots of the load
// history and the problem's event times.
std::vector<double> step_landings(const ClothProblem& problem, const CreepOptions& options) {
  std::vector<double> landings = options.load.times();
  const std::vector<double> events = problem.event_times();
  landings.insert(landings.end(), events.begin(), events.end());
  return landings;
}

// A monolithic coupling is undone however the run ends.
struct UncoupleAtExit {
  CreepCoupling& creep;
  ~UncoupleAtExit() { creep.uncouple(); }
};

// Two vectors destroyed however the run ends.
struct DestroyAtExit {
  Vec* first;
  Vec* second;
  ~DestroyAtExit() {
    VecDestroy(first);
    VecDestroy(second);
  }
};

// Restores the state of the run a checkpoint records.
PetscErrorCode resume_creep(ClothProblem& problem, CreepCoupling& creep, Vec x,
                            const RunCheckpoint& resume) {
  PetscFunctionBeginUser;
  problem.time = resume.time;
  problem.load_factor = resume.load_factor;
  PetscCall(problem.set_solution(resume.positions, x));
  creep.restore(resume.creep);
  problem.restore_anchors(resume.anchors);
  PetscFunctionReturn(0);
}

// A dynamic run's starting velocities: zero, or the checkpoint's.
PetscErrorCode initial_velocity(const ClothProblem& problem, Vec x, const RunCheckpoint* resume,
                                Vec* velocity) {
  PetscFunctionBeginUser;
  PetscCall(VecDuplicate(x, velocity));
  PetscCall(VecSet(*velocity, 0.0));
  if (resume && !resume->velocities.empty()) {
    PetscCall(problem.set_solution(resume->velocities, *velocity));
  }
  PetscFunctionReturn(0);
}

// The equilibrium at the start, reported as the run's first step; *ok is
// false (and the report says why) when it does not converge.
PetscErrorCode initial_creep_state(ClothProblem& problem, CreepCoupling& creep,
                                   IncrementalSystem& system, Vec x, const CreepOptions& options,
                                   double start, CreepReport* report, const CreepObserver& observe,
                                   bool* ok) {
  PetscFunctionBeginUser;
  problem.load_factor = options.load.after(start);
  StaticReport initial;
  PetscCall(solve_static(system, x, options.equilibrium, &initial));
  report->newton_iterations += initial.newton_iterations;
  *ok = initial.converged;
  if (!initial.converged) {
    report->reason = "the initial equilibrium did not converge (" + initial.reason + ")";
    report->final_time = start;
    PetscFunctionReturn(0);
  }
  PetscCall(creep.record_tensions(x));
  CreepStepReport first;
  first.time = start;
  first.load_factor = problem.load_factor;
  first.newton_iterations = initial.newton_iterations;
  first.output = true;
  report->steps.push_back(first);
  if (observe) PetscCall(observe(first, x));
  PetscFunctionReturn(0);
}

// One time step of length h from the last accepted state `last` (and, in
// dynamics, its velocity) to x; counts its Newton iterations.
struct CreepStep {
  ClothProblem& problem;
  IncrementalSystem& system;
  const CreepOptions& options;
  Vec x, last, velocity;
  double h;
  PetscInt newton_iterations = 0;
};

// Why a static solve that converged did not settle its contact: its
// contact rounds ended (ran out, or the last failed) before the friction was
// consistent with the anchors (StaticOptions::contact_tolerance), or with a
// vertex deeper in the offset layer than the adaptive penalty allows. Empty
// where it settled, or where no rounds were asked for (anchors lagged by a
// step, a choice the caller made).
std::string contact_unsettled(const ClothProblem& problem, const StaticOptions& solve,
                              const StaticReport& result) {
  if (problem.bodies.empty() || !result.minimised || solve.max_contact_rounds == 0) return "";
  if (!result.friction_consistent) {
    return std::to_string(result.contact_rounds) + " contact rounds" +
           (result.contact_round_failed ? " (the last failed)" : "") + " left a residual of " +
           std::to_string(result.anchored_residual_norm) +
           " N with the friction anchors updated (consistent at " +
           std::to_string(result.consistency_tolerance) + " N)";
  }
  if (contact_too_deep(problem, solve, result)) {
    return "a vertex ended " + std::to_string(result.deepest_offset_depth) +
           " m deep in the offset layer, more than " + std::to_string(solve.max_offset_depth) +
           " of it";
  }
  return "";
}

// Equilibrium at the step's end from the load factor the problem holds to
// `factor`; dynamic: the backward Euler step from the last accepted state.
PetscErrorCode step_equilibrium(CreepStep& step, double factor, CreepReport* report,
                                bool* converged) {
  PetscFunctionBeginUser;
  ClothProblem& problem = step.problem;
  if (step.options.dynamic) {
    problem.load_factor = factor;
    step.system.inertia().inertia_weight = 1.0 / (step.h * step.h);
    step.system.inertia().damping_weight = step.options.damping / step.h;
    PetscCall(VecCopy(step.last, step.system.inertia().previous()));
    PetscCall(VecWAXPY(step.system.inertia().predicted(), step.h, step.velocity, step.last));
    IncrementalSystem::Solve result;
    PetscCall(step.system.solve(step.x, &result));
    step.newton_iterations += result.newton_iterations;
    *converged = result.converged;
    if (!*converged) report->reason = result.reason;
    PetscFunctionReturn(0);
  }
  StaticOptions solve = step.options.equilibrium;
  solve.start_load_factor = problem.load_factor;
  solve.load_steps = 1;
  problem.load_factor = factor;
  StaticReport result;
  PetscCall(solve_static(step.system, step.x, solve, &result));
  step.newton_iterations += result.newton_iterations;
  *converged = result.converged;
  if (!*converged) report->reason = result.reason;
  const std::string unsettled = contact_unsettled(problem, solve, result);
  if (*converged && !unsettled.empty()) {
    *converged = false;
    report->reason = unsettled;
  }
  PetscFunctionReturn(0);
}

// The start of a step to t1 whose bodies move (CreepOptions::follow_bodies):
// the cloth near them carried along, then what is still inside pushed out
// (the flesh round a bending knee is not rigid).
PetscErrorCode start_with_the_bodies(ClothProblem& problem, Vec x, double t1, double reach) {
  PetscFunctionBeginUser;
  if (problem.bodies.empty()) PetscFunctionReturn(0); // a take-off's recovery
  PetscCall(problem.carry_with_bodies(x, t1, reach));
  ClothProblem::PushOut pushed;
  PetscCall(problem.push_out_of_bodies(x, &pushed));
  PetscCall(PetscInfo(nullptr,
                      "creep step to %g s: %ld vertices pushed out of the bodies, the deepest "
                      "from %g m\n",
                      t1, pushed.pushed, pushed.deepest));
  PetscFunctionReturn(0);
}

struct StepAttempt {
  bool converged = false;
  bool too_large = false; // the creep increment exceeds twice the tolerance
  double increment = 0.0; // the creep increment of the step
};

// The step to t1: equilibrium, the creep update, and (where needed)
// equilibrium again with the new unloaded lengths.
PetscErrorCode attempt_creep_step(CreepStep& step, CreepCoupling& creep, double t1, bool monolithic,
                                  CreepReport* report, StepAttempt* attempt) {
  PetscFunctionBeginUser;
  ClothProblem& problem = step.problem;
  const CreepOptions& options = step.options;
  const double h = step.h;
  if (options.follow_bodies && !options.dynamic) {
    PetscCall(start_with_the_bodies(problem, step.x, t1, options.follow_reach));
  }
  problem.time = t1;
  bool converged = false;
  if (monolithic) creep.couple(h);
  // Pins let go at t1 still hold at its left limit, like a load jump's.
  const auto& releases = problem.release_times();
  const bool release_at_t1 = std::find(releases.begin(), releases.end(), t1) != releases.end();
  problem.hold_at_release = true;
  PetscCall(step_equilibrium(step, options.load.before(t1), report, &converged));
  problem.hold_at_release = false;
  double increment = 0.0;
  if (converged && monolithic) PetscCall(creep.advance_coupled(step.x, &increment));
  if (converged && !monolithic) PetscCall(creep.advance(step.x, h, &increment));
  const bool too_large =
      converged && increment > 2.0 * options.creep_tolerance && h > options.min_step;
  // Staggered: equilibrium with the new unloaded lengths. Monolithic: x is
  // already in equilibrium with them, unless the load jumps or pins let go
  // at t1.
  const bool solve_again =
      !monolithic || release_at_t1 || options.load.after(t1) != options.load.before(t1);
  if (converged && !too_large && solve_again) {
    PetscCall(step_equilibrium(step, options.load.after(t1), report, &converged));
  }
  attempt->converged = converged;
  attempt->too_large = too_large;
  attempt->increment = increment;
  PetscFunctionReturn(0);
}

// What a step's contact rounds change besides the positions: the friction
// anchors and the adaptive penalty.
struct ContactState {
  std::vector<AnchorRow> anchors;
  double stiffness_scale = 1.0;
};

PetscErrorCode save_contact(ClothProblem& problem, ContactState* state) {
  PetscFunctionBeginUser;
  if (problem.bodies.empty()) PetscFunctionReturn(0);
  PetscCall(problem.anchors_everywhere(&state->anchors));
  state->stiffness_scale = problem.contact.stiffness_scale;
  PetscFunctionReturn(0);
}

// Back to the last accepted state at t after a rejected step: a retry
// starts from the anchors and penalty that state was solved with.
PetscErrorCode roll_back_creep_step(const CreepStep& step, CreepCoupling& creep, double t,
                                    double factor_before, const ContactState& contact) {
  PetscFunctionBeginUser;
  PetscCall(VecCopy(step.last, step.x));
  creep.roll_back();
  step.problem.time = t;
  step.problem.load_factor = factor_before;
  if (!step.problem.bodies.empty()) {
    step.problem.restore_anchors(contact.anchors);
    step.problem.contact.stiffness_scale = contact.stiffness_scale;
  }
  PetscFunctionReturn(0);
}

// The step to retry with after a rejected step h: shortened to 0.9 of the
// creep tolerance when its increment was too large, else halved.
double retry_creep_step(const CreepOptions& options, double h, const StepAttempt& attempt) {
  return attempt.too_large ? h * std::max(0.2, 0.9 * options.creep_tolerance / attempt.increment)
                           : 0.5 * h;
}

// Commits the accepted step's creep and, in dynamics, its velocity.
PetscErrorCode accept_creep_step(const CreepStep& step, CreepCoupling& creep) {
  PetscFunctionBeginUser;
  creep.commit();
  PetscCall(creep.record_tensions(step.x));
  if (step.options.dynamic) {
    PetscCall(step.problem.accept_step(step.x)); // statics do it inside solve_static
    // v = (x - x_n) / h
    PetscCall(VecWAXPY(step.velocity, -1.0, step.last, step.x));
    PetscCall(VecScale(step.velocity, 1.0 / step.h));
  }
  PetscFunctionReturn(0);
}

// The next step after an accepted step h (dt before it; `shortened`: h was
// cut short of dt to land on a time): aimed at 0.9 of the creep tolerance.
double next_creep_step(const CreepOptions& options, double h, double dt, bool shortened,
                       double increment) {
  const double ideal = increment > 0.0 ? 0.9 * options.creep_tolerance * h / increment : 2.0 * h;
  dt = std::clamp(ideal, 0.5 * h, 2.0 * (shortened ? std::max(h, dt) : h));
  if (options.max_step > 0.0) dt = std::min(dt, options.max_step);
  return std::max(dt, options.min_step);
}

// The estimate of the wall time left counts steps, which grow about
// geometrically as the creep slows, not simulated time: from t alone it said
// hours where minutes were left.
PetscErrorCode print_creep_progress(const ClothProblem& problem, ProgressClock& progress,
                                    const CreepStepReport& accepted, const StepController& clock,
                                    double first_step) {
  PetscFunctionBeginUser;
  PetscCall(PetscPrintf(problem.comm(),
                        "  creep t = %-10.4g s (%3.0f %%): step %ld, dt %.3g s, load %.3g, "
                        "creep increment %.2e; %s\n",
                        clock.time(), 100.0 * clock.fraction_done(), accepted.step, accepted.dt,
                        problem.load_factor, accepted.increment,
                        progress.timing(clock.geometric_fraction_done(first_step)).c_str()));
  PetscFunctionReturn(0);
}

} // namespace

PetscErrorCode solve_creep(ClothProblem& problem, CreepCoupling& creep, Vec x,
                           const CreepOptions& options, CreepReport* report,
                           const CreepObserver& observe, const CreepRestart& restart) {
  Vec last = nullptr, velocity = nullptr;
  PetscFunctionBeginUser;
  const auto started = std::chrono::steady_clock::now();
  problem.pins_follow_time = true;
  if (options.follow_bodies) problem.contact.bounded_friction = true;
  const RunCheckpoint* resume = restart.resume;
  if (resume) PetscCall(resume_creep(problem, creep, x, *resume));
  const double start = problem.time;
  check(options, start);
  const double end = options.time_end;
  const double tiny = 1e-9 * (end - start);
  const bool monolithic = options.scheme == CreepScheme::monolithic;
  // Monolithic: uncoupled however the run ends.
  const UncoupleAtExit uncouple_at_exit{creep};
  if (monolithic) creep.couple(0.0);
  IncrementalSystem system(problem, x);
  PetscCall(VecDuplicate(x, &last));
  if (options.dynamic) PetscCall(initial_velocity(problem, x, resume, &velocity));
  // Every way out of this function destroys both.
  const DestroyAtExit destroy_at_exit{&last, &velocity};

  long step = resume ? resume->step : 0;
  double dt = resume ? resume->next_step : options.time_step;
  if (!resume) {
    bool ok = false;
    PetscCall(initial_creep_state(problem, creep, system, x, options, start, report, observe, &ok));
    if (!ok) PetscFunctionReturn(0);
  }

  StepController clock(start, end, tiny, step_landings(problem, options));
  clock.output_every(options.output_interval);
  clock.checkpoint_every(restart.checkpoint_interval, PeriodicEvent::Landing::steps_end_on_it);
  ProgressClock progress;
  int rejected = 0;
  while (!clock.finished()) {
    const StepPlan plan = clock.plan(dt);
    const double t = clock.time(), h = plan.length;
    const double factor_before = problem.load_factor;
    PetscCall(VecCopy(x, last));
    ContactState contact_before;
    PetscCall(save_contact(problem, &contact_before));

    CreepStep attempt_step{problem, system, options, x, last, velocity, h};
    StepAttempt attempt;
    PetscCall(attempt_creep_step(attempt_step, creep, plan.to, monolithic, report, &attempt));
    report->newton_iterations += attempt_step.newton_iterations;
    if (!attempt.converged || attempt.too_large) {
      PetscCall(
          PetscInfo(nullptr, "creep step from %g s to %g s rejected: %s\n", t, plan.to,
                    attempt.too_large ? "creep increment too large" : report->reason.c_str()));
      PetscCall(roll_back_creep_step(attempt_step, creep, t, factor_before, contact_before));
      dt = retry_creep_step(options, h, attempt);
      ++rejected;
      ++report->rejected_steps;
      if (dt < options.min_step) {
        report->reason = "the time step fell below " + std::to_string(options.min_step) +
                         " s at t = " + std::to_string(t) + " s (" + report->reason + ")";
        break;
      }
      continue;
    }
    PetscCall(accept_creep_step(attempt_step, creep));
    clock.accept(plan);
    ++step;
    dt = next_creep_step(options, h, dt, plan.shortened, attempt.increment);

    CreepStepReport accepted;
    accepted.step = step;
    accepted.time = plan.to;
    accepted.dt = h;
    accepted.load_factor = problem.load_factor;
    accepted.newton_iterations = attempt_step.newton_iterations;
    accepted.rejected = rejected;
    accepted.increment = attempt.increment;
    rejected = 0;
    if (clock.output_due()) {
      accepted.output = true;
      clock.pass_output();
    }
    report->steps.push_back(accepted);
    if (observe) PetscCall(observe(accepted, x));
    if (restart.every_step || clock.checkpoint_due()) {
      clock.pass_checkpoint();
      if (restart.write) PetscCall(restart.write(accepted, x, velocity, dt));
    }
    if (options.print_progress && progress.due(clock.finished()))
      PetscCall(print_creep_progress(problem, progress, accepted, clock, options.time_step));
  }
  report->completed = clock.finished();
  if (report->completed) report->reason.clear();
  report->final_time = clock.time();
  report->solve_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  PetscFunctionReturn(0);
}

} // namespace sartor
