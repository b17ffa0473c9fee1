#include "fem/statics.hpp"

#include <chrono>

namespace sartor {

namespace {

// The system SNES sees: the cloth's residual plus, during continuation, the
// damping term weight * M (x - anchor), weight = 1 / dt^2.
struct DampedSystem {
  ClothProblem* problem = nullptr;
  Vec mass = nullptr;
  Vec anchor = nullptr;
  Vec work = nullptr;
  double weight = 0.0;
};

PetscErrorCode form_residual(SNES, Vec x, Vec f, void* context) {
  auto* system = static_cast<DampedSystem*>(context);
  PetscFunctionBeginUser;
  PetscCall(system->problem->residual(x, f));
  if (system->weight > 0.0) {
    PetscCall(VecWAXPY(system->work, -1.0, system->anchor, x));
    PetscCall(VecPointwiseMult(system->work, system->work, system->mass));
    PetscCall(VecAXPY(f, system->weight, system->work));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode form_jacobian(SNES, Vec x, Mat J, Mat, void* context) {
  auto* system = static_cast<DampedSystem*>(context);
  PetscFunctionBeginUser;
  PetscCall(system->problem->jacobian(x, J));
  if (system->weight > 0.0) {
    PetscCall(VecCopy(system->mass, system->work));
    PetscCall(VecScale(system->work, system->weight));
    PetscCall(MatDiagonalSet(J, system->work, ADD_VALUES));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode form_energy(SNES, Vec x, PetscReal* value, void* context) {
  auto* system = static_cast<DampedSystem*>(context);
  ClothEnergy energy;
  PetscFunctionBeginUser;
  PetscCall(system->problem->energy(x, &energy));
  *value = energy.total();
  if (system->weight > 0.0) {
    PetscReal kinetic = 0.0;
    PetscCall(VecWAXPY(system->work, -1.0, system->anchor, x));
    PetscCall(VecPointwiseMult(system->work, system->work, system->work));
    PetscCall(VecDot(system->work, system->mass, &kinetic));
    *value += 0.5 * system->weight * kinetic;
  }
  PetscFunctionReturn(0);
}

// Rigid-body modes of the free dofs, for algebraic multigrid.
PetscErrorCode attach_near_null_space(Vec x, Mat J) {
  MatNullSpace modes = nullptr;
  PetscFunctionBeginUser;
  PetscCall(MatNullSpaceCreateRigidBody(x, &modes));
  PetscCall(MatSetNearNullSpace(J, modes));
  PetscCall(MatNullSpaceDestroy(&modes));
  PetscFunctionReturn(0);
}

PetscErrorCode set_default(const char* name, const char* value) {
  PetscBool chosen = PETSC_FALSE;
  PetscFunctionBeginUser;
  PetscCall(PetscOptionsHasName(nullptr, nullptr, name, &chosen));
  if (!chosen) PetscCall(PetscOptionsSetValue(nullptr, name, value));
  PetscFunctionReturn(0);
}

// One SNES solve from x; its statistics are added to `step`.
PetscErrorCode newton(SNES snes, Vec x, LoadStepReport* step, bool* converged) {
  SNESConvergedReason reason;
  PetscInt iterations = 0, linear = 0;
  PetscFunctionBeginUser;
  PetscCall(SNESSolve(snes, nullptr, x));
  PetscCall(SNESGetConvergedReason(snes, &reason));
  PetscCall(SNESGetIterationNumber(snes, &iterations));
  PetscCall(SNESGetLinearSolveIterations(snes, &linear));
  PetscCall(SNESGetFunctionNorm(snes, &step->residual_norm));
  step->newton_iterations += iterations;
  step->linear_iterations += linear;
  step->reason = SNESConvergedReasons[reason];
  *converged = reason > 0;
  PetscFunctionReturn(0);
}

// Pseudo-transient continuation towards equilibrium at the current load.
PetscErrorCode continuation(SNES snes, DampedSystem& system, Vec x, const StaticOptions& options,
                            LoadStepReport* step, bool* converged) {
  PetscFunctionBeginUser;
  *converged = false;
  double dt = options.initial_pseudo_step;
  PetscCall(VecCopy(x, system.anchor));
  for (int k = 0; k < options.max_pseudo_steps && dt > 1e-12; ++k) {
    system.weight = 1.0 / (dt * dt);
    bool stepped = false;
    PetscCall(newton(snes, x, step, &stepped));
    if (!stepped) {
      PetscCall(VecCopy(system.anchor, x));
      dt *= 0.25;
      continue;
    }
    ++step->pseudo_steps;
    PetscReal motion = 0.0, size = 0.0;
    PetscCall(VecWAXPY(system.work, -1.0, system.anchor, x));
    PetscCall(VecNorm(system.work, NORM_INFINITY, &motion));
    PetscCall(VecNorm(x, NORM_INFINITY, &size));
    PetscCall(VecCopy(x, system.anchor));
    dt *= 2.0;
    // Near rest, or every tenth step, try the undamped problem.
    if (motion < 1e-3 * size || k % 10 == 9) {
      system.weight = 0.0;
      PetscCall(newton(snes, x, step, converged));
      if (*converged) break;
      PetscCall(VecCopy(system.anchor, x));
    }
  }
  system.weight = 0.0;
  PetscFunctionReturn(0);
}

} // namespace

PetscErrorCode solve_static(ClothProblem& problem, Vec x, const StaticOptions& options,
                            StaticReport* report) {
  SNES snes = nullptr;
  Mat J = nullptr;
  Vec f = nullptr, last = nullptr;
  DampedSystem system;
  PetscFunctionBeginUser;
  const auto started = std::chrono::steady_clock::now();
  PetscCall(set_default("-ksp_type", "preonly"));
  PetscCall(set_default("-pc_type", "lu"));
  PetscCall(set_default("-pc_factor_mat_solver_type", "mumps"));

  system.problem = &problem;
  PetscCall(problem.create_jacobian(&J));
  PetscCall(attach_near_null_space(x, J));
  for (Vec* v : {&f, &last, &system.mass, &system.anchor, &system.work})
    PetscCall(VecDuplicate(x, v));
  PetscCall(problem.lumped_mass(system.mass));
  PetscCall(SNESCreate(problem.comm(), &snes));
  PetscCall(SNESSetFunction(snes, f, form_residual, &system));
  PetscCall(SNESSetJacobian(snes, J, J, form_jacobian, &system));
  // A follower load has no energy; otherwise the line search uses the energy.
  if (!problem.has_follower_load()) PetscCall(SNESSetObjective(snes, form_energy, &system));
  // Defaults the options database can override: a residual below round-off
  // of the membrane forces counts as converged.
  PetscCall(SNESSetTolerances(snes, 1e-12 * problem.force_scale(), 1e-10, 1e-14, 100, -1));
  PetscCall(SNESSetFromOptions(snes));

  const double target = problem.load_factor;
  double reached = 0.0;
  double increment = target / std::max(1, options.load_steps);
  int cutbacks = 0;
  PetscCall(problem.residual(x, f));
  PetscCall(VecNorm(f, NORM_2, &report->initial_residual_norm));
  while (reached < target) {
    const double next = std::min(target, reached + increment);
    problem.load_factor = next;
    PetscCall(VecCopy(x, last));
    LoadStepReport step;
    step.load_factor = next;
    PetscCall(newton(snes, x, &step, &step.converged));
    if (!step.converged) {
      PetscCall(VecCopy(last, x));
      PetscCall(continuation(snes, system, x, options, &step, &step.converged));
    }
    report->steps.push_back(step);
    report->newton_iterations += step.newton_iterations;
    report->linear_iterations += step.linear_iterations;
    report->pseudo_steps += step.pseudo_steps;
    report->reason = step.reason;
    if (step.converged) {
      reached = next;
      continue;
    }
    PetscCall(VecCopy(last, x));
    if (++cutbacks > options.max_cutbacks) {
      problem.load_factor = reached;
      break;
    }
    increment *= 0.5;
    PetscCall(PetscInfo(snes, "load step to %g failed (%s); retrying with increment %g\n", next,
                        step.reason.c_str(), increment));
  }
  report->converged = reached >= target;
  PetscCall(problem.residual(x, f));
  PetscCall(VecNorm(f, NORM_2, &report->final_residual_norm));
  report->solve_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  PetscCall(SNESDestroy(&snes));
  PetscCall(MatDestroy(&J));
  for (Vec* v : {&f, &last, &system.mass, &system.anchor, &system.work})
    PetscCall(VecDestroy(v));
  PetscFunctionReturn(0);
}

} // namespace sartor
