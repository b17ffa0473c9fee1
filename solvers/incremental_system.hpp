#pragma once
// The nonlinear system of one load, pseudo-time or time step, shared by the
// static and dynamic solvers: the stationary point of the incremental potential
//     Phi(x) = E(x) - f.x + (a/2) |x - x_pred|^2_M + (b/2) |x - x_prev|^2_M
// (M: lumped masses), whose residual and Jacobian are
//     F(x) = grad E - f + M (a (x - x_pred) + b (x - x_prev)),
//     J(x) = K(x) + (a + b) M.
// Statics: a = b = 0, or a = 1/dt^2 about the last state in pseudo-transient
// continuation. Backward Euler: a = 1/dt^2 about x_n + dt v_n and b = alpha/dt
// about x_n (mass-proportional damping alpha M v).
//
// The SNES takes every choice from the options database (no prefix), with
// defaults: Newton with a line search on Phi (on the residual norm while
// there is no potential: pressure on a surface with a free edge, monolithic creep), MUMPS LU, and a
// residual tolerance at round-off of the membrane forces. Where the line search on Phi stalls at
// Phi's round-off after the residual has fallen 1e3-fold, Newton finishes on the residual norm.
// A time step SNES fails on a potential is solved again by the minimiser below, so that whether
// a step is cut back does not hinge on round-off near SNES's limits.
//
// Statics of a potential (a = b = 0, no pressure on a free edge, no pin held by
// equations) go to `minimise` instead (solvers/minimiser.cpp) unless
// `minimise_statics` is off, and so do time steps with `minimise_time_steps`:
// Newton on Phi with a Levenberg-style regularisation mu M, a step bound from
// the bodies' signed distances and a backtracking line search on Phi
// (docs/drape.md#the-static-minimiser).

#include "fem/cloth_problem.hpp"
#include "fem/forms/inertia_form.hpp"

#include <petscsnes.h>

#include <chrono>
#include <memory>

#include <string>
#include <vector>

namespace sartor {

// A SNES's tolerances (SNESGetTolerances), to change some of them for a
// solve and put them back.
struct SnesTolerances {
  PetscReal atol = 0.0, rtol = 0.0, stol = 0.0;
  PetscInt max_iterations = 0, max_evaluations = 0;
  static PetscErrorCode of(SNES snes, SnesTolerances* tolerances);
  PetscErrorCode apply(SNES snes) const;
};

class IncrementalSystem {
public:
  // Collective. `like` is a solution vector of `problem`.
  IncrementalSystem(ClothProblem& problem, Vec like);
  ~IncrementalSystem();
  IncrementalSystem(const IncrementalSystem&) = delete;
  IncrementalSystem& operator=(const IncrementalSystem&) = delete;

  ClothProblem& problem() { return problem_; }
  // The SNES the next solve uses: with the line search on Phi while the
  // problem has a potential.
  SNES snes();
  // The inertia and damping terms (a, b, x_pred, x_prev and M above): set
  // their weights to 0 for statics.
  fem::InertiaForm& inertia() { return *inertia_; }
  const fem::InertiaForm& inertia() const { return *inertia_; }

  // Solve::reason of a minimiser stalled by the bodies' step bound.
  static constexpr const char* step_bound_stalled = "DIVERGED_STEP_BOUND_STALLED";
  struct Solve {
    bool converged = false;
    std::string reason;
    PetscInt newton_iterations = 0;
    PetscInt linear_iterations = 0;
    double residual_norm = 0.0;
    double tolerance = 0.0; // the minimiser's: max(atol, rtol |F_0|)
  };
  // Solves from x in place (x holds SNES's last iterate on failure).
  PetscErrorCode solve(Vec x, Solve* result);

  // The static minimiser (solvers/minimiser.cpp) instead of SNES for statics of
  // a potential. Its stopping test is SNES's: |F| <= max(atol, rtol |F_0|),
  // at most max_it iterations (-snes_atol, -snes_rtol, -snes_max_it), or
  // `loose_rtol` instead of rtol when that is larger (the continuation
  // stages of sewing, solvers/statics.hpp).
  bool minimise_statics = true;
  // The same minimiser for the time steps of dynamics (backward Euler's
  // incremental potential, inertia and damping included), in place of SNES:
  // the contact step bound keeps every vertex outside the bodies within a
  // step, and the unprojected Hessian near the step's solution gives
  // Newton's quadratic convergence where compressed membranes wrinkle.
  bool minimise_time_steps = false;
  // Time steps (dynamics): a step SNES fails on a potential is solved by the
  // minimiser from the inertia's previous state, the last accepted one
  // (IncrementalSystem::solve).
  bool minimise_failed_time_steps = false;
  double loose_rtol = 0.0;
  PetscInt loose_max_iterations = 0; // with loose_rtol: at most this many (0: max_it)
  // End a solve the bodies' step bound stalls (reason step_bound_stalled):
  // the sewing stages before the last, which solve_static then solves again
  // on stiffer contact (solvers/statics.cpp).
  bool end_stalled_solves = false;
  struct MinimiserStatistics {
    PetscInt step_bound_cuts = 0;      // Newton steps shortened by the contact step bound
    PetscInt regularised_steps = 0;    // steps with mu > 0
    PetscInt residual_rule_trials = 0; // line-search trials decided on slopes (Phi in round-off)
    PetscInt failed_factorisations = 0;
    PetscInt exact_steps = 0;    // with the unprojected Hessian
    PetscInt extended_steps = 0; // whole steps the line search lengthened
  };
  MinimiserStatistics minimiser_statistics;
  // Progress lines of the minimiser on stdout (what is solved, iteration,
  // |F| against its tolerance, wall time since progress_origin), at most one
  // every progress_interval seconds of wall time; 0: none.
  double progress_interval = 0.0;
  std::string progress_label;
  std::chrono::steady_clock::time_point progress_origin = std::chrono::steady_clock::now();
  std::chrono::steady_clock::time_point progress_last = progress_origin; // the last line
  // Whether solve() uses the minimiser for the system as it is now.
  bool minimises() const;

  PetscErrorCode residual(Vec x, Vec f);
  PetscErrorCode jacobian(Vec x, Mat J);
  PetscErrorCode objective(Vec x, PetscReal* value);
  // SNES's convergence test (SNESConvergedDefault), which also ends the line
  // search on Phi once the residual is below the fraction of solve() (the
  // reason then is SNES_CONVERGED_ITS).
  PetscErrorCode converged(SNES snes, PetscInt iteration, PetscReal position_norm,
                           PetscReal step_norm, PetscReal residual_norm,
                           SNESConvergedReason* reason);
  // Where solve() leaves the line search on Phi for full Newton steps: the
  // residual below this fraction of its start, and at most this many of
  // them before it goes back to the line search.
  static constexpr double basin_fraction = 1e-3;
  static constexpr PetscInt newton_finish_iterations = 20;

private:
  PetscErrorCode create_snes(bool with_objective, SNES* snes);
  // The Jacobian created anew when the problem's couplings (self-contact
  // pairs) have changed at x (ClothProblem::refresh_couplings), or since it
  // was created (a certificate's refresh).
  PetscErrorCode refresh_couplings(Vec x);
  // solvers/minimiser.cpp
  PetscErrorCode minimise(Vec x, Solve* result);
  struct Trial;
  PetscErrorCode newton_direction(Vec x, Vec gradient, double mu, Vec direction, bool* solved,
                                  PetscInt* linear_iterations);
  PetscErrorCode line_search(Vec x, Vec gradient, Vec direction, double first_length,
                             bool may_extend, Trial* trial);
  struct LongerTrial;
  PetscErrorCode longer_trial(Vec direction, double length, double end_slope, const Trial& accepted,
                              LongerTrial* longer);
  PetscErrorCode take_longer_trial(const LongerTrial& longer, Trial* trial);
  PetscErrorCode extend_step(Vec direction, double slope, Trial* trial);
  PetscErrorCode regularisation_scale(double* scale);
  PetscErrorCode incremental_potential(Vec x, double* value, double* scale);
  struct Regularisation;
  PetscErrorCode search_direction(Vec x, PetscInt iteration, Regularisation* regularisation,
                                  PetscInt* linear_iterations, bool* solved, bool* exact);
  PetscErrorCode print_minimiser_state(PetscInt iteration, const Trial& current,
                                       PetscReal tolerance, bool monitor, double mu, double bound);
  Vec direction_ = nullptr;
  Vec trial_x_ = nullptr;
  Vec trial_f_ = nullptr;
  Vec extended_x_ = nullptr; // a longer trial than the accepted one (extend_step)
  Vec extended_f_ = nullptr;
  PetscErrorCode run_snes(SNES snes, Vec x, Solve* result);
  PetscErrorCode finish_with_newton(SNES snes, Vec x, Solve* result);
  PetscErrorCode minimise_failed_time_step(SNES snes, Vec x, Solve* result);
  double switch_at_fraction_ = 0.0; // of the first residual; 0: no switch
  double first_norm_ = 0.0;         // the first residual of the solve
  bool switched_ = false;           // the last solve stopped at switch_at_fraction_
  bool handing_over_ = false;       // a solve with a potential: line search, then Newton

  ClothProblem& problem_;
  SNES snes_ = nullptr;
  bool snes_has_objective_ = false;
  SNES snes_without_potential_ = nullptr; // made when first needed
  Mat jacobian_ = nullptr;
  long jacobian_version_ = 0; // ClothProblem::coupling_version when jacobian_ was created
  Vec residual_ = nullptr;
  std::unique_ptr<fem::InertiaForm> inertia_;
  Vec work_ = nullptr;
  Vec switch_point_ = nullptr;   // where the line search on Phi handed over to Newton
  std::vector<PetscReal> norms_; // residual norms of the last SNES solve
};

} // namespace sartor
