#include "solvers/incremental_system.hpp"

#include "fem/petsc_call.hpp"
#include "fem/petsc_options.hpp"

#include <string>

namespace sartor {

namespace {

PetscErrorCode form_residual(SNES, Vec x, Vec f, void* context) {
  return static_cast<IncrementalSystem*>(context)->residual(x, f);
}

PetscErrorCode form_jacobian(SNES, Vec x, Mat J, Mat, void* context) {
  return static_cast<IncrementalSystem*>(context)->jacobian(x, J);
}

PetscErrorCode form_objective(SNES, Vec x, PetscReal* value, void* context) {
  return static_cast<IncrementalSystem*>(context)->objective(x, value);
}

PetscErrorCode converged(SNES snes, PetscInt iteration, PetscReal position_norm,
                         PetscReal step_norm, PetscReal residual_norm, SNESConvergedReason* reason,
                         void* context) {
  return static_cast<IncrementalSystem*>(context)->converged(snes, iteration, position_norm,
                                                             step_norm, residual_norm, reason);
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

// A Jacobian without a potential is not symmetric: a Cholesky factorisation
// (the default for a symmetric problem on one rank) becomes LU.
PetscErrorCode factorise_unsymmetric(KSP ksp) {
  PC pc = nullptr;
  PetscBool cholesky = PETSC_FALSE;
  PetscFunctionBeginUser;
  PetscCall(KSPGetPC(ksp, &pc));
  PetscCall(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(pc), PCCHOLESKY, &cholesky));
  if (cholesky) PetscCall(PCSetType(pc, PCLU));
  PetscFunctionReturn(0);
}

} // namespace

PetscErrorCode SnesTolerances::of(SNES snes, SnesTolerances* t) {
  return SNESGetTolerances(snes, &t->atol, &t->rtol, &t->stol, &t->max_iterations,
                           &t->max_evaluations);
}

PetscErrorCode SnesTolerances::apply(SNES snes) const {
  return SNESSetTolerances(snes, atol, rtol, stol, max_iterations, max_evaluations);
}

IncrementalSystem::IncrementalSystem(ClothProblem& problem, Vec like) : problem_(problem) {
  SartorPetscCall(set_default_direct_solver(problem.comm(), "", problem.symmetric_jacobian()));
  SartorPetscCall(problem.create_jacobian(&jacobian_));
  jacobian_version_ = problem.coupling_version();
  SartorPetscCall(attach_near_null_space(like, jacobian_));
  for (Vec* v : {&residual_, &work_, &switch_point_, &direction_, &trial_x_, &trial_f_,
                 &extended_x_, &extended_f_})
    SartorPetscCall(VecDuplicate(like, v));
  SartorPetscCall(problem.lumped_mass(work_));
  inertia_ = std::make_unique<fem::InertiaForm>(work_);
  // Keeps the residual norms of each solve (the first is the initial one).
  norms_.assign(1000, 0.0);
  snes_has_objective_ = problem.has_potential();
  SartorPetscCall(create_snes(snes_has_objective_, &snes_));
}

PetscErrorCode IncrementalSystem::create_snes(bool with_objective, SNES* snes) {
  PetscFunctionBeginUser;
  PetscCall(SNESCreate(problem_.comm(), snes));
  PetscCall(SNESSetFunction(*snes, residual_, form_residual, this));
  PetscCall(SNESSetJacobian(*snes, jacobian_, jacobian_, form_jacobian, this));
  // Without a potential (pressure on a surface with a free edge, monolithic creep) the line search
  // uses the residual norm; otherwise Phi.
  if (with_objective) PetscCall(SNESSetObjective(*snes, form_objective, this));
  // Defaults the options database can override: a residual below round-off
  // of the membrane forces counts as converged.
  PetscCall(SNESSetTolerances(*snes, 1e-12 * problem_.force_scale(), 1e-10, 1e-14, 100, -1));
  PetscCall(SNESSetFromOptions(*snes));
  KSP ksp = nullptr;
  PetscCall(SNESGetKSP(*snes, &ksp));
  PetscCall(gather_telescope_onto_one_rank(ksp));
  if (!with_objective || !problem_.symmetric_jacobian()) PetscCall(factorise_unsymmetric(ksp));
  PetscCall(SNESSetConvergenceTest(*snes, sartor::converged, this, nullptr));
  PetscCall(SNESSetConvergenceHistory(*snes, norms_.data(), nullptr, PetscInt(norms_.size()),
                                      PETSC_TRUE));
  PetscFunctionReturn(0);
}

SNES IncrementalSystem::snes() {
  // A system whose potential comes and goes (monolithic creep holds its
  // unloaded lengths at some solves) gets a second SNES without the
  // objective: PETSc cannot unset one.
  if (problem_.has_potential() || !snes_has_objective_) return snes_;
  if (!snes_without_potential_) SartorPetscCall(create_snes(false, &snes_without_potential_));
  return snes_without_potential_;
}

IncrementalSystem::~IncrementalSystem() {
  SNESDestroy(&snes_);
  SNESDestroy(&snes_without_potential_);
  MatDestroy(&jacobian_);
  for (Vec* v : {&residual_, &work_, &switch_point_, &direction_, &trial_x_, &trial_f_,
                 &extended_x_, &extended_f_})
    VecDestroy(v);
}

PetscErrorCode IncrementalSystem::refresh_couplings(Vec x) {
  bool changed = false;
  Mat J = nullptr;
  PetscFunctionBeginUser;
  PetscCall(problem_.refresh_couplings(x, &changed));
  if (problem_.coupling_version() == jacobian_version_) PetscFunctionReturn(0);
  PetscCall(problem_.create_jacobian(&J));
  jacobian_version_ = problem_.coupling_version();
  PetscCall(attach_near_null_space(x, J));
  // A preconditioner set up for the old structure starts afresh: on several
  // ranks PCTELESCOPE would reuse its gathered matrix, whose nonzeros differ.
  for (SNES snes : {snes_, snes_without_potential_}) {
    if (!snes) continue;
    KSP ksp = nullptr;
    PC pc = nullptr;
    PetscCall(SNESSetJacobian(snes, J, J, form_jacobian, this));
    PetscCall(SNESGetKSP(snes, &ksp));
    PetscCall(KSPGetPC(ksp, &pc));
    PetscCall(PCReset(pc));
  }
  PetscCall(MatDestroy(&jacobian_));
  jacobian_ = J;
  PetscFunctionReturn(0);
}

PetscErrorCode IncrementalSystem::solve(Vec x, Solve* result) {
  PetscFunctionBeginUser;
  // SNES's steps have no bound that keeps the cloth from passing through itself.
  PetscCheck(minimises() || !problem_.has_self_contact(), problem_.comm(), PETSC_ERR_SUP,
             "cloth self-contact needs the minimiser (a potential, and --static-solver or "
             "--dynamic-solver minimise)");
  PetscCall(refresh_couplings(x));
  if (minimises()) {
    PetscCall(minimise(x, result));
    PetscFunctionReturn(0);
  }
  PetscCall(problem_.hold(x));
  const SNES snes_now = snes();
  PetscErrorCode (*line_search_objective)(SNES, Vec, PetscReal*, void*) = nullptr;
  PetscCall(SNESGetObjective(snes_now, &line_search_objective, nullptr));
  PetscBool newton_line_search = PETSC_FALSE;
  PetscCall(PetscObjectTypeCompare(PetscObject(snes_now), SNESNEWTONLS, &newton_line_search));
  handing_over_ = false;
  if (!line_search_objective || !newton_line_search) {
    PetscCall(run_snes(snes_now, x, result));
    PetscFunctionReturn(0);
  }
  // Close to the solution a Newton step lowers Phi by less than its
  // round-off, and a line search on Phi then decides on round-off (another
  // CPU's BLAS takes other steps, and a time step may fail on one machine
  // only). So the line search on Phi runs while the residual is above
  // `basin_fraction` of its start, where Phi's decrease is still measurable
  // (|F| |dx| far above Phi's round-off), and full Newton steps finish the
  // solve from there: they converge quadratically in Newton's basin and need
  // no merit function.
  // Every solve with a potential, statics with SNES included (the creep
  // cases differ by up to 0.6 m under Prescott's rounding otherwise).
  handing_over_ = true;
  switched_ = false;
  switch_at_fraction_ = basin_fraction;
  PetscCall(run_snes(snes_now, x, result));
  switch_at_fraction_ = 0.0;
  // A solve that starts near its solution (|F_0| itself small) may stall in
  // Phi's round-off before that: where Newton's correction is below 1e-6 of
  // the positions the iterate is in Newton's basin too.
  SNESLineSearch line_search = nullptr;
  PetscReal position_norm = 0.0, residual_norm = 0.0, correction_norm = 0.0;
  PetscCall(SNESGetLineSearch(snes_now, &line_search));
  PetscCall(SNESLineSearchGetNorms(line_search, &position_norm, &residual_norm, &correction_norm));
  const bool stalled = result->reason == SNESConvergedReasons[SNES_DIVERGED_LINE_SEARCH] &&
                       correction_norm <= 1e-6 * position_norm;
  if ((result->reason == SNESConvergedReasons[SNES_CONVERGED_ITS] && switched_) || stalled) {
    const Solve first = *result;
    PetscCall(finish_with_newton(snes_now, x, result));
    if (!result->converged && !minimise_failed_time_steps) {
      // Not in Newton's basin after all: the line search on Phi to the end.
      PetscCall(PetscInfo(snes_now,
                          "full Newton steps from |F| = %g failed (%s); line search "
                          "on the potential to the tolerance\n",
                          first.residual_norm, result->reason.c_str()));
      PetscCall(VecCopy(switch_point_, x));
      PetscCall(run_snes(snes_now, x, result));
    }
  }
  if (!result->converged && minimise_failed_time_steps)
    PetscCall(minimise_failed_time_step(snes_now, x, result));
  PetscFunctionReturn(0);
}

// A time step SNES fails on a potential (its line search on Phi gave up, its
// full Newton steps left the basin, or max_it ran out) is solved by the
// minimiser from the step's last accepted state: whether SNES's path fails is
// decided by round-off near those limits (the hanging sheet with the patch
// model rejected its step at 1.515 s under Prescott's kernels, not under
// SkylakeX's, and every later step moved), while the minimiser converges
// from the same start on either machine to the same solution, so that no
// step is cut back on one machine only. The last accepted state, not SNES's
// start (the prediction x_n + dt v_n): it is outside the bodies.
PetscErrorCode IncrementalSystem::minimise_failed_time_step(SNES snes, Vec x, Solve* result) {
  PetscFunctionBeginUser;
  const Solve failed = *result;
  PetscCall(PetscInfo(snes,
                      "time step to t = %g s: SNES failed (%s) at |F| = %g; the minimiser from "
                      "the last accepted state\n",
                      problem_.time, failed.reason.c_str(), double(failed.residual_norm)));
  PetscCall(VecCopy(inertia_->previous(), x));
  PetscCall(minimise(x, result));
  result->newton_iterations += failed.newton_iterations;
  result->linear_iterations += failed.linear_iterations;
  PetscFunctionReturn(0);
}

PetscErrorCode IncrementalSystem::finish_with_newton(SNES snes, Vec x, Solve* result) {
  PetscFunctionBeginUser;
  const Solve first = *result;
  PetscCall(VecCopy(x, switch_point_)); // where the line search on Phi stopped
  SNESLineSearch line_search = nullptr;
  PetscCall(SNESGetLineSearch(snes, &line_search));
  SNESLineSearchType type = nullptr;
  PetscCall(SNESLineSearchGetType(line_search, &type));
  const std::string line_search_type = type;
  SnesTolerances saved;
  PetscCall(SnesTolerances::of(snes, &saved));
  // The tolerance of the whole solve: rtol relative to the first residual.
  PetscCall(SNESLineSearchSetType(line_search, SNESLINESEARCHBASIC));
  SnesTolerances finish = saved;
  finish.atol = std::max(saved.atol, saved.rtol * first_norm_);
  finish.rtol = 0.0;
  finish.max_iterations = newton_finish_iterations;
  PetscCall(finish.apply(snes));
  PetscCall(run_snes(snes, x, result));
  PetscCall(saved.apply(snes));
  PetscCall(SNESLineSearchSetType(line_search, line_search_type.c_str()));
  PetscCall(SNESLineSearchSetFromOptions(line_search)); // the type's own options again
  result->newton_iterations += first.newton_iterations;
  result->linear_iterations += first.linear_iterations;
  PetscFunctionReturn(0);
}

PetscErrorCode IncrementalSystem::run_snes(SNES snes, Vec x, Solve* result) {
  SNESConvergedReason reason;
  PetscFunctionBeginUser;
  PetscCall(SNESSolve(snes, nullptr, x));
  PetscCall(SNESGetConvergedReason(snes, &reason));
  PetscCall(SNESGetIterationNumber(snes, &result->newton_iterations));
  PetscCall(SNESGetLinearSolveIterations(snes, &result->linear_iterations));
  PetscCall(SNESGetFunctionNorm(snes, &result->residual_norm));
  result->reason = SNESConvergedReasons[reason];
  // SNES ends on CONVERGED_SNORM_RELATIVE when a failed line search leaves
  // a step below -snes_stol of the positions: the residual is above the
  // tolerance (else the residual test would have stopped it first), and
  // whether the shrunk step falls below stol is round-off. Not a solution.
  result->converged = reason > 0 && !(reason == SNES_CONVERGED_SNORM_RELATIVE && handing_over_);
  PetscFunctionReturn(0);
}

PetscErrorCode IncrementalSystem::converged(SNES snes, PetscInt iteration, PetscReal position_norm,
                                            PetscReal step_norm, PetscReal residual_norm,
                                            SNESConvergedReason* reason) {
  PetscFunctionBeginUser;
  if (iteration == 0 && switch_at_fraction_ > 0.0) {
    first_norm_ = residual_norm;
    switched_ = false;
  }
  PetscCall(SNESConvergedDefault(snes, iteration, position_norm, step_norm, residual_norm, reason,
                                 nullptr));
  // A step below -snes_stol of the positions (a line search shrunk to
  // nothing) is no solution while the residual is above the tolerance:
  // whether the step falls below stol or the line search gives up first is
  // round-off; the line search's own failure or max_it ends the solve.
  if (*reason == SNES_CONVERGED_SNORM_RELATIVE && handing_over_) {
    *reason = SNES_CONVERGED_ITERATING;
  }
  if (*reason == SNES_CONVERGED_ITERATING && switch_at_fraction_ > 0.0 && iteration > 0 &&
      residual_norm <= switch_at_fraction_ * first_norm_) {
    switched_ = true;
    *reason = SNES_CONVERGED_ITS; // to the full Newton steps (solve)
  }
  PetscFunctionReturn(0);
}

PetscErrorCode IncrementalSystem::residual(Vec x, Vec f) {
  PetscFunctionBeginUser;
  PetscCall(problem_.residual(x, f));
  PetscCall(inertia_->add_gradient(x, f));
  PetscCall(problem_.replace_held_rows(x, f)); // the inertia's share of them too
  PetscFunctionReturn(0);
}

PetscErrorCode IncrementalSystem::jacobian(Vec x, Mat J) {
  PetscFunctionBeginUser;
  PetscCall(problem_.jacobian(x, J));
  if (inertia_->active()) {
    PetscCall(inertia_->add_hessian(x, false, J));
    PetscCall(problem_.replace_held_rows(J));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode IncrementalSystem::objective(Vec x, PetscReal* value) {
  double potential = 0.0, scale = 0.0;
  PetscFunctionBeginUser;
  PetscCall(incremental_potential(x, &potential, &scale));
  *value = potential;
  PetscFunctionReturn(0);
}

} // namespace sartor
