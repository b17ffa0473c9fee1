#include "fem/statics.hpp"

#include "fem/incremental_system.hpp"

#include <algorithm>
#include <chrono>

namespace sartor {

namespace {

void add(const IncrementalSystem::Solve& solve, LoadStepReport* step) {
  step->newton_iterations += solve.newton_iterations;
  step->linear_iterations += solve.linear_iterations;
  step->residual_norm = solve.residual_norm;
  step->reason = solve.reason;
}

// The norm of the system's residual at x (inertia included when weighted).
PetscErrorCode residual_norm(IncrementalSystem& system, Vec x, PetscReal* norm) {
  Vec f = nullptr;
  PetscFunctionBeginUser;
  PetscCall(VecDuplicate(x, &f));
  PetscCall(system.residual(x, f));
  PetscCall(VecNorm(f, NORM_2, norm));
  PetscCall(VecDestroy(&f));
  PetscFunctionReturn(0);
}

// PETSc stops on a small Newton correction (SNORM) or on an iteration count
// and calls that converged, whatever the residual: with a singular tangent
// (nothing pinned, a free panel) or a load far beyond the cloth's strength
// the correction means nothing and the residual stays where it started. A
// solve is converged only if its residual met the tolerances; on those other
// stops, one six orders below the solve's start counts as met too, far below
// the start and above the round-off at which a converged Newton step vanishes.
PetscErrorCode check_residual_met(IncrementalSystem& system, PetscReal start,
                                  IncrementalSystem::Solve* solve) {
  PetscReal atol = 0.0, rtol = 0.0, stol = 0.0;
  PetscInt max_iterations = 0, max_evaluations = 0;
  PetscFunctionBeginUser;
  const bool residual_test = solve->reason == SNESConvergedReasons[SNES_CONVERGED_FNORM_ABS] ||
                             solve->reason == SNESConvergedReasons[SNES_CONVERGED_FNORM_RELATIVE];
  if (!solve->converged || residual_test) PetscFunctionReturn(0);
  PetscCall(
      SNESGetTolerances(system.snes(), &atol, &rtol, &stol, &max_iterations, &max_evaluations));
  if (solve->residual_norm <= std::max({atol, rtol * start, 1e-6 * start})) PetscFunctionReturn(0);
  solve->converged = false;
  solve->reason += " with the residual above its tolerance";
  PetscFunctionReturn(0);
}

// One SNES solve from x; its statistics are added to `step`.
PetscErrorCode newton(IncrementalSystem& system, Vec x, LoadStepReport* step, bool* converged) {
  IncrementalSystem::Solve solve;
  PetscReal start = 0.0;
  PetscFunctionBeginUser;
  PetscCall(system.problem().hold(x)); // as the solve starts: pins in their places
  PetscCall(residual_norm(system, x, &start));
  PetscCall(system.solve(x, &solve));
  PetscCall(check_residual_met(system, start, &solve));
  add(solve, step);
  *converged = solve.converged;
  PetscFunctionReturn(0);
}

// Pseudo-transient continuation towards equilibrium at the current load:
// inertia about the last pseudo-step's state, 1/dt^2 M.
PetscErrorCode continuation(IncrementalSystem& system, Vec x, const StaticOptions& options,
                            LoadStepReport* step, bool* converged) {
  Vec anchor = system.predicted();
  PetscFunctionBeginUser;
  *converged = false;
  double dt = options.initial_pseudo_step;
  PetscCall(VecCopy(x, anchor));
  for (int k = 0; k < options.max_pseudo_steps && dt > 1e-12; ++k) {
    system.inertia_weight = 1.0 / (dt * dt);
    bool stepped = false;
    PetscCall(newton(system, x, step, &stepped));
    if (!stepped) {
      PetscCall(VecCopy(anchor, x));
      dt *= 0.25;
      continue;
    }
    ++step->pseudo_steps;
    PetscReal motion = 0.0, size = 0.0;
    PetscCall(VecAXPY(anchor, -1.0, x));
    PetscCall(VecNorm(anchor, NORM_INFINITY, &motion));
    PetscCall(VecNorm(x, NORM_INFINITY, &size));
    PetscCall(VecCopy(x, anchor));
    dt *= 2.0;
    // Near rest, or every tenth step, try the undamped problem.
    if (motion < 1e-3 * size || k % 10 == 9) {
      system.inertia_weight = 0.0;
      PetscCall(newton(system, x, step, converged));
      if (*converged) break;
      PetscCall(VecCopy(anchor, x));
    }
  }
  system.inertia_weight = 0.0;
  PetscFunctionReturn(0);
}

} // namespace

PetscErrorCode solve_static(ClothProblem& problem, Vec x, const StaticOptions& options,
                            StaticReport* report) {
  PetscFunctionBeginUser;
  IncrementalSystem system(problem, x);
  PetscCall(solve_static(system, x, options, report));
  PetscFunctionReturn(0);
}

PetscErrorCode solve_static(IncrementalSystem& system, Vec x, const StaticOptions& options,
                            StaticReport* report) {
  Vec f = nullptr, last = nullptr;
  ClothProblem& problem = system.problem();
  PetscFunctionBeginUser;
  const auto started = std::chrono::steady_clock::now();
  system.inertia_weight = 0.0;
  system.damping_weight = 0.0;
  for (Vec* v : {&f, &last})
    PetscCall(VecDuplicate(x, v));

  // The load goes from options.start_load_factor to problem.load_factor;
  // `reached` and the increments are fractions of that way.
  const double start = options.start_load_factor;
  const double target = problem.load_factor;
  const auto load_at = [&](double fraction) { return start + fraction * (target - start); };
  double reached = 0.0;
  double increment = 1.0 / std::max(1, options.load_steps);
  int cutbacks = 0;
  PetscCall(problem.update_contact(x)); // friction anchors for what touches a body at the start
  PetscCall(problem.residual(x, f));
  PetscCall(VecNorm(f, NORM_2, &report->initial_residual_norm));
  while (reached < 1.0) {
    const double next = std::min(1.0, reached + increment);
    problem.load_factor = next < 1.0 ? load_at(next) : target;
    PetscCall(VecCopy(x, last));
    LoadStepReport step;
    step.load_factor = problem.load_factor;
    PetscCall(newton(system, x, &step, &step.converged));
    if (!step.converged) {
      PetscCall(VecCopy(last, x));
      PetscCall(continuation(system, x, options, &step, &step.converged));
    }
    report->steps.push_back(step);
    report->newton_iterations += step.newton_iterations;
    report->linear_iterations += step.linear_iterations;
    report->pseudo_steps += step.pseudo_steps;
    report->reason = step.reason;
    if (step.converged) {
      reached = next;
      PetscCall(problem.accept_step(x));
      continue;
    }
    PetscCall(VecCopy(last, x));
    if (++cutbacks > options.max_cutbacks) {
      problem.load_factor = load_at(reached);
      break;
    }
    increment *= 0.5;
    PetscCall(PetscInfo(system.snes(), "load step to %g failed (%s); retrying with increment %g\n",
                        problem.load_factor, step.reason.c_str(), increment * (target - start)));
  }
  report->converged = reached >= 1.0;
  PetscCall(problem.residual(x, f));
  PetscCall(VecNorm(f, NORM_2, &report->final_residual_norm));
  report->solve_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  for (Vec* v : {&f, &last})
    PetscCall(VecDestroy(v));
  PetscFunctionReturn(0);
}

} // namespace sartor
