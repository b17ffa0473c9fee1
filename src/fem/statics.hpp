#pragma once
// Static equilibrium of a cloth: Newton's method (PETSc SNES) with the loads
// ramped up in steps. A load step that Newton cannot solve from the previous
// state is approached by pseudo-transient continuation: heavily damped
// backward-Euler steps, each minimising
//     E(x) - f.x + |x - x_k|^2_M / (2 dt^2)       (M: lumped masses)
// with dt growing while steps succeed, until plain Newton converges
// (Sensitive Couture §7's robust path from far-from-equilibrium starts). If
// that fails too, the load increment is halved, up to `max_cutbacks` times,
// and the solve stops with SNES's reason.
//
// Solver choices come from the options database (-snes_*, -ksp_*, -pc_*).
// Defaults: Newton with a backtracking line search on the energy, a direct
// solve (MUMPS LU) of each Newton system.

#include "fem/cloth_problem.hpp"

#include <petscsnes.h>

#include <string>
#include <vector>

namespace sartor {

struct StaticOptions {
  // The solve ramps the load factor from here to problem.load_factor.
  double start_load_factor = 0.0;
  int load_steps = 1;
  int max_cutbacks = 8;
  double initial_pseudo_step = 1e-2; // dt of the first continuation step, s
  int max_pseudo_steps = 200;        // per load step
};

struct LoadStepReport {
  double load_factor = 0.0;
  bool converged = false;
  std::string reason;
  PetscInt newton_iterations = 0;
  PetscInt linear_iterations = 0;
  PetscInt pseudo_steps = 0; // continuation steps taken before the final Newton solve
  double residual_norm = 0.0;
};

struct StaticReport {
  bool converged = false;
  std::string reason; // of the last attempt
  std::vector<LoadStepReport> steps;
  PetscInt newton_iterations = 0;
  PetscInt linear_iterations = 0;
  PetscInt pseudo_steps = 0;
  double initial_residual_norm = 0.0;
  double final_residual_norm = 0.0;
  double solve_seconds = 0.0;
};

// Solves in place: `x` holds the start and, on return, the last converged state.
PetscErrorCode solve_static(ClothProblem& problem, Vec x, const StaticOptions& options,
                            StaticReport* report);
// The same with a system kept from solve to solve (its SNES and Jacobian),
// as a time stepper that solves equilibrium at every step does.
class IncrementalSystem;
PetscErrorCode solve_static(IncrementalSystem& system, Vec x, const StaticOptions& options,
                            StaticReport* report);

} // namespace sartor
