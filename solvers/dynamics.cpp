#include "solvers/dynamics.hpp"

#include "common/error.hpp"
#include "solvers/incremental_system.hpp"
#include "solvers/progress_clock.hpp"
#include "solvers/statics.hpp"
#include "solvers/step_controller.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

namespace sartor {

namespace {

PetscErrorCode kinetic_energy(Vec v, Vec mass, Vec work, double* value) {
  PetscFunctionBeginUser;
  PetscCall(VecPointwiseMult(work, v, v));
  PetscCall(VecDot(work, mass, value));
  *value *= 0.5;
  PetscFunctionReturn(0);
}

void check(const DynamicOptions& options, double start) {
  const auto positive = [](double value, const char* name) {
    if (!(value > 0.0) || !std::isfinite(value)) {
      throw InputError(std::string("dynamics: ") + name + " must be a positive number, got " +
                       std::to_string(value));
    }
  };
  positive(options.time_step, "the time step");
  if (!(options.time_end > start)) {
    throw InputError("dynamics: the end time " + std::to_string(options.time_end) +
                     " s is not after the start time " + std::to_string(start) + " s");
  }
  if (!(options.damping >= 0.0) || !(options.output_interval >= 0.0) ||
      !(options.rest_tolerance >= 0.0) || options.max_cutbacks < 0) {
    throw InputError("dynamics: damping, output interval, rest tolerance and cut-backs must "
                     "not be negative");
  }
}

// The problem and its vectors as the time steps see them: positions x,
// velocities v, and work vectors f (a residual) and work.
struct DynamicState {
  ClothProblem& problem;
  IncrementalSystem& system;
  Vec x, v, f, work;
};

// A step's energies and static residual at the state reached.
PetscErrorCode measure(const DynamicState& s, DynamicStepReport* step) {
  ClothEnergy energy;
  PetscFunctionBeginUser;
  PetscCall(kinetic_energy(s.v, s.system.inertia().mass(), s.work, &step->kinetic_energy));
  PetscCall(s.problem.energy(s.x, &energy));
  step->potential_energy = energy.total();
  PetscCall(s.problem.residual(s.x, s.f));
  PetscCall(VecNorm(s.f, NORM_2, &step->static_residual_norm));
  PetscFunctionReturn(0);
}

// One backward Euler step from the clock's time, of the length *dt asks for
// unless the clock cuts it to land on an output, an event or the end; halved on
// failure up to max_cutbacks times; *accepted tells whether one converged
// (else report->reason says why). After a success *dt doubles back towards
// the time step.
PetscErrorCode take_step(DynamicState& s, const DynamicOptions& options, StepController& clock,
                         double* dt, DynamicStepReport* step, DynamicReport* report,
                         bool* accepted) {
  PetscFunctionBeginUser;
  IncrementalSystem& system = s.system;
  const double t = clock.time();
  *accepted = false;
  for (int attempt = 0; !*accepted; ++attempt) {
    const StepPlan plan = clock.plan(*dt);
    const double h = plan.length;
    PetscCall(VecCopy(s.x, system.inertia().previous()));
    PetscCall(VecWAXPY(system.inertia().predicted(), h, s.v, s.x));
    system.inertia().inertia_weight = 1.0 / (h * h);
    system.inertia().damping_weight = options.damping / h;
    s.problem.time = plan.to;
    // SNES starts from the prediction; the minimiser from the last state,
    // which is outside the bodies, so that its step bound keeps it there.
    if (!options.minimise) PetscCall(VecCopy(system.inertia().predicted(), s.x));
    IncrementalSystem::Solve solve;
    PetscCall(system.solve(s.x, &solve));
    step->newton_iterations += solve.newton_iterations;
    step->linear_iterations += solve.linear_iterations;
    step->reason = solve.reason;
    if (solve.converged) {
      *accepted = true;
      clock.accept(plan);
      step->time = plan.to;
      step->dt = h;
      step->output = clock.output_due();
      if (step->output) clock.pass_output();
      // v = (x - x_n) / h
      PetscCall(VecWAXPY(s.v, -1.0, system.inertia().previous(), s.x));
      PetscCall(VecScale(s.v, 1.0 / h));
      *dt = std::min(2.0 * *dt, options.time_step);
      break;
    }
    PetscCall(VecCopy(system.inertia().previous(), s.x));
    s.problem.time = t;
    if (attempt >= options.max_cutbacks) {
      report->completed = false;
      char message[256];
      std::snprintf(message, sizeof message,
                    "the time step from t = %.6g s (dt = %.3g s) failed after %d cut-backs: "
                    "SNES %s",
                    t, h, attempt, solve.reason.c_str());
      report->reason = message;
      break;
    }
    ++step->rejected;
    *dt = 0.5 * h;
    PetscCall(PetscInfo(system.snes(), "time step to %g failed (%s); retrying with dt = %g\n",
                        plan.to, solve.reason.c_str(), *dt));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode print_dynamic_progress(const ClothProblem& problem, ProgressClock& progress,
                                      const DynamicStepReport& step, const DynamicReport& report,
                                      double t, double start, double span, bool finished) {
  PetscFunctionBeginUser;
  PetscCall(PetscPrintf(problem.comm(),
                        "  t = %.4g s (%3.0f%%): %" PetscInt_FMT " steps, %" PetscInt_FMT
                        " Newton iterations, %" PetscInt_FMT
                        " rejected; kinetic %.3e J, potential %.6e J; %s\n",
                        t, 100.0 * (t - start) / span, step.step, report.newton_iterations,
                        report.rejected_steps, step.kinetic_energy, step.potential_energy,
                        progress.timing(finished ? 1.0 : (t - start) / span).c_str()));
  PetscFunctionReturn(0);
}

// The static solve after the relaxation (--settle): from the last accepted
// state, which it keeps when the solve fails.
PetscErrorCode settle(DynamicState& s, DynamicReport* report) {
  PetscFunctionBeginUser;
  IncrementalSystem& system = s.system;
  system.inertia().inertia_weight = 0.0;
  system.inertia().damping_weight = 0.0;
  PetscCall(VecCopy(s.x, system.inertia().previous())); // the last accepted state, kept on failure
  // The time steps of a relaxation may be solved loosely (-snes_rtol); the
  // equilibrium is solved to at least 1e-10 of the settle's first residual.
  SnesTolerances saved;
  PetscCall(SnesTolerances::of(system.snes(), &saved));
  SnesTolerances settling = saved;
  settling.rtol = std::min(saved.rtol, PetscReal(1e-10));
  PetscCall(settling.apply(system.snes()));
  // Statics' own solve, so that the settle of a potential ends as a static
  // drape does: contact rounds until the friction anchors' update leaves
  // the state in equilibrium (solvers/statics.hpp), the adaptive penalty off.
  StaticOptions options;
  options.start_load_factor = s.problem.load_factor;
  options.minimise = system.minimise_statics;
  options.max_offset_depth = 0.0;
  options.max_cutbacks = 0; // the load is already whole: a retry would repeat the solve
  StaticReport solve;
  PetscCall(solve_static(system, s.x, options, &solve));
  PetscCall(saved.apply(system.snes()));
  report->newton_iterations += solve.newton_iterations;
  report->linear_iterations += solve.linear_iterations;
  report->settle_newton_iterations = solve.newton_iterations;
  report->settle_contact_rounds = solve.contact_rounds;
  report->settle_contact_round_failed = solve.contact_round_failed;
  report->settled = solve.converged;
  // The settled state is the last converged solve's (a contact round that
  // fails keeps the state before it): its reason and residual, with the
  // friction anchors it was solved with. Whether friction is consistent
  // after their update is the certificate's to say.
  const LoadStepReport* settled = nullptr;
  for (const LoadStepReport& step : solve.steps)
    if (step.converged) settled = &step;
  report->settle_reason = settled ? settled->reason : solve.reason;
  if (settled) {
    report->settle_residual_norm = settled->residual_norm;
  } else {
    PetscCall(s.problem.residual(s.x, s.f));
    PetscCall(VecNorm(s.f, NORM_2, &report->settle_residual_norm));
  }
  if (solve.converged) {
    PetscCall(VecSet(s.v, 0.0)); // solve_static has accepted the state
  } else {
    PetscCall(VecCopy(system.inertia().previous(), s.x));
    report->completed = false;
    report->reason = "the static solve after the relaxation failed: SNES " + solve.reason;
  }
  PetscFunctionReturn(0);
}

} // namespace

PetscErrorCode solve_dynamic(ClothProblem& problem, Vec x, Vec v, const DynamicOptions& options,
                             DynamicReport* report, const DynamicObserver& observe,
                             const DynamicCheckpoints& checkpoints) {
  Vec f = nullptr, work = nullptr;
  PetscFunctionBeginUser;
  const auto started = std::chrono::steady_clock::now();
  const DynamicControl* resume = checkpoints.resume;
  const double start = resume ? resume->start : problem.time;
  check(options, start);
  const double span = options.time_end - start;
  // Times closer than this are the same time (round-off of sums of steps).
  const double tiny = 1e-9 * std::min(options.time_step, span);
  problem.pins_follow_time = true;
  IncrementalSystem system(problem, x);
  system.minimise_time_steps = options.minimise;
  system.minimise_failed_time_steps = true;
  PetscCall(VecDuplicate(x, &f));
  PetscCall(VecDuplicate(x, &work));
  DynamicState state{problem, system, x, v, f, work};
  // Vertices that touch a body in the starting placement stick there (a
  // resumed run has the checkpoint's anchors).
  if (!resume) PetscCall(problem.update_contact(x));

  DynamicControl control;
  if (resume) {
    control = *resume;
  } else {
    DynamicStepReport initial;
    initial.time = start;
    initial.output = true;
    PetscCall(measure(state, &initial));
    report->steps.push_back(initial);
    if (observe) PetscCall(observe(initial, x, v));
    control = {
        start, start, options.time_step, 0, initial.kinetic_energy, initial.static_residual_norm};
  }
  const double initial_residual = control.initial_residual;
  // Steps land on the outputs (multiples of the output interval), the
  // problem's event times and the end; a step is not cut to reach a
  // checkpoint: checkpoints do not change the answer.
  StepController clock(start, options.time_end, tiny, problem.event_times());
  clock.output_every(options.output_interval);
  clock.checkpoint_every(checkpoints.interval, PeriodicEvent::Landing::first_step_past_it);
  clock.resume(control.time);
  double dt = control.next_step;
  double previous_kinetic = control.previous_kinetic;
  ProgressClock progress;
  PetscInt step_index = control.step;
  report->completed = true;
  while (!report->at_rest && !clock.finished()) {
    DynamicStepReport step;
    step.step = ++step_index;
    bool accepted = false;
    PetscCall(take_step(state, options, clock, &dt, &step, report, &accepted));
    report->newton_iterations += step.newton_iterations;
    report->linear_iterations += step.linear_iterations;
    report->rejected_steps += step.rejected;
    if (!accepted) break;

    const double t = clock.time();
    PetscCall(problem.accept_step(x));
    PetscCall(measure(state, &step));
    if (options.kinetic_damping && step.kinetic_energy < previous_kinetic) {
      // Past a peak of the kinetic energy: start again from rest.
      PetscCall(VecSet(v, 0.0));
      step.velocities_reset = true;
      ++report->velocity_resets;
      previous_kinetic = 0.0;
    } else {
      previous_kinetic = step.kinetic_energy;
    }
    const bool at_rest = options.rest_tolerance > 0.0 &&
                         step.static_residual_norm <= options.rest_tolerance * initial_residual;
    if (at_rest) {
      step.output = true;
      report->at_rest = true;
    }
    report->steps.push_back(step);
    if (observe) PetscCall(observe(step, x, v));
    const bool finished = at_rest || clock.finished();
    if (options.print_progress && progress.due(finished))
      PetscCall(print_dynamic_progress(problem, progress, step, *report, t, start, span, finished));
    if (checkpoints.write && clock.checkpoint_due()) {
      clock.pass_checkpoint();
      PetscCall(
          checkpoints.write({start, t, dt, step_index, previous_kinetic, initial_residual}, x, v));
    }
    if (at_rest) break;
  }
  report->final_time = clock.time();
  if (options.settle && report->completed) PetscCall(settle(state, report));
  report->solve_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  PetscCall(VecDestroy(&f));
  PetscCall(VecDestroy(&work));
  PetscFunctionReturn(0);
}

} // namespace sartor
