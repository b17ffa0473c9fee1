#include "fem/statics.hpp"

#include <chrono>

namespace sartor {

namespace {

PetscErrorCode form_residual(SNES, Vec x, Vec f, void* context) {
  return static_cast<ClothProblem*>(context)->residual(x, f);
}

PetscErrorCode form_jacobian(SNES, Vec x, Mat J, Mat, void* context) {
  return static_cast<ClothProblem*>(context)->jacobian(x, J);
}

PetscErrorCode form_energy(SNES, Vec x, PetscReal* value, void* context) {
  ClothEnergy energy;
  PetscFunctionBeginUser;
  PetscCall(static_cast<ClothProblem*>(context)->energy(x, &energy));
  *value = energy.total();
  PetscFunctionReturn(0);
}

PetscErrorCode set_default(const char* name, const char* value) {
  PetscBool chosen = PETSC_FALSE;
  PetscFunctionBeginUser;
  PetscCall(PetscOptionsHasName(nullptr, nullptr, name, &chosen));
  if (!chosen) PetscCall(PetscOptionsSetValue(nullptr, name, value));
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

} // namespace

PetscErrorCode solve_static(ClothProblem& problem, Vec x, const StaticOptions& options,
                            StaticReport* report) {
  SNES snes = nullptr;
  Mat J = nullptr;
  Vec f = nullptr, last = nullptr;
  PetscFunctionBeginUser;
  const auto started = std::chrono::steady_clock::now();
  PetscCall(set_default("-ksp_type", "preonly"));
  PetscCall(set_default("-pc_type", "lu"));
  PetscCall(set_default("-pc_factor_mat_solver_type", "mumps"));
  PetscCall(set_default("-snes_rtol", "1e-10"));
  PetscCall(set_default("-snes_stol", "1e-14"));
  PetscCall(set_default("-snes_max_it", "100"));

  PetscCall(problem.create_jacobian(&J));
  PetscCall(attach_near_null_space(x, J));
  PetscCall(VecDuplicate(x, &f));
  PetscCall(VecDuplicate(x, &last));
  PetscCall(SNESCreate(problem.comm(), &snes));
  PetscCall(SNESSetFunction(snes, f, form_residual, &problem));
  PetscCall(SNESSetJacobian(snes, J, J, form_jacobian, &problem));
  // A follower load has no energy; otherwise the line search uses the energy.
  if (!problem.has_follower_load()) PetscCall(SNESSetObjective(snes, form_energy, &problem));
  PetscCall(SNESSetFromOptions(snes));

  const double target = problem.load_factor;
  double reached = 0.0;
  double increment = target / std::max(1, options.load_steps);
  int cutbacks = 0;
  PetscCall(problem.residual(x, f));
  PetscCall(VecNorm(f, NORM_2, &report->initial_residual_norm));
  report->converged = false;
  while (reached < target) {
    const double next = std::min(target, reached + increment);
    problem.load_factor = next;
    PetscCall(VecCopy(x, last));
    PetscCall(SNESSolve(snes, nullptr, x));
    SNESConvergedReason reason;
    LoadStepReport step;
    step.load_factor = next;
    PetscCall(SNESGetConvergedReason(snes, &reason));
    PetscCall(SNESGetIterationNumber(snes, &step.newton_iterations));
    PetscCall(SNESGetLinearSolveIterations(snes, &step.linear_iterations));
    PetscCall(SNESGetFunctionNorm(snes, &step.residual_norm));
    step.converged = reason > 0;
    step.reason = SNESConvergedReasons[reason];
    report->steps.push_back(step);
    report->newton_iterations += step.newton_iterations;
    report->linear_iterations += step.linear_iterations;
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
  PetscCall(VecDestroy(&f));
  PetscCall(VecDestroy(&last));
  PetscFunctionReturn(0);
}

} // namespace sartor
