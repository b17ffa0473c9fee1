#pragma once
// Static equilibrium of a cloth: Newton's method (PETSc SNES) with the loads
// ramped up in steps; a step that fails is retried with half the increment,
// and after `max_cutbacks` halvings the solve stops with SNES's reason.
//
// Solver choices come from the options database (-snes_*, -ksp_*, -pc_*).
// Defaults: Newton with a backtracking line search on the energy, and a
// direct solve (MUMPS LU) of each Newton system.

#include "fem/cloth_problem.hpp"

#include <petscsnes.h>

#include <string>
#include <vector>

namespace sartor {

struct StaticOptions {
  int load_steps = 1;
  int max_cutbacks = 8;
};

struct LoadStepReport {
  double load_factor = 0.0;
  bool converged = false;
  std::string reason;
  PetscInt newton_iterations = 0;
  PetscInt linear_iterations = 0;
  double residual_norm = 0.0;
};

struct StaticReport {
  bool converged = false;
  std::string reason; // of the last attempt
  std::vector<LoadStepReport> steps;
  PetscInt newton_iterations = 0;
  PetscInt linear_iterations = 0;
  double initial_residual_norm = 0.0;
  double final_residual_norm = 0.0;
  double solve_seconds = 0.0;
};

// Solves in place: `x` holds the start and, on return, the last converged state.
PetscErrorCode solve_static(ClothProblem& problem, Vec x, const StaticOptions& options,
                            StaticReport* report);

} // namespace sartor
