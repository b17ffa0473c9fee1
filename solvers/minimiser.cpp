// The static minimiser of IncrementalSystem (docs/drape.md#the-static-minimiser):
// Newton on the total potential Phi with the element Hessians as the problem
// assembles them (PSD-projected where the materials ask), regularised by
// mu M where the Hessian is singular or the step too long, the first trial
// step bounded by the bodies' signed distances (ClothProblem::
// contact_step_bound), and a backtracking line search on Phi with margins
// above Phi's round-off.

#include "solvers/incremental_system.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace sartor {

namespace {

// Armijo's sufficient decrease: Phi must fall by at least this fraction of
// the decrease its slope predicts.
constexpr double armijo_fraction = 1e-4;
// A decrease of Phi is trusted when it exceeds this fraction of the sum of
// the magnitudes of its parts; below, the trial is judged on |F| (Phi's
// round-off grows with those magnitudes, not with Phi).
constexpr double energy_resolution = 1e-10;
// The line search halves the step at most this many times (1e-6 of the first).
constexpr int max_halvings = 20;
// An accepted whole step along which Phi's slope at its end is still
// steeper than crawl_slope of its first (a quadratic's is 0 there) is
// doubled while it is steeper than extension_slope of it, at most
// max_extensions times (1024 times the step).
constexpr double crawl_slope = 0.9;
constexpr double extension_slope = 0.5;
constexpr int max_extensions = 10;
constexpr double max_slope_growth = 2.0;
// mu grows tenfold after a failed factorisation, a non-descent direction or a
// line search that had to cut the step below a quarter; it shrinks tenfold
// after a full step, to zero once below its floor.
constexpr double mu_growth = 10.0;
constexpr double full_step_fraction = 0.25;
// The bodies' step bound stalls a solve where the forces push a vertex
// harder than the contact penalty can hold it: each step may take half of
// its remaining distance, and the bound falls geometrically (to 1e-16 in
// about a hundred iterations) while |F| stays. Ten iterations in a row with
// the bound below this end the solve where the caller asks
// (end_stalled_solves), so that it can stiffen the penalty
// (solvers/statics.cpp) instead of spending -snes_max_it.
constexpr double stalled_bound = 1e-6;
constexpr int stalled_iterations = 10;

// Whether a predicted decrease of Phi (< 0) is above Phi's round-off at
// both ends of a trial, whose magnitudes are these.
bool resolved_decrease(double predicted, double scale, double other_scale) {
  return -predicted > energy_resolution * std::max(scale, other_scale);
}

// Armijo's rule on Phi's change (measured, or from the slopes).
bool sufficient_decrease(double change, double predicted) {
  return std::isfinite(change) && change <= armijo_fraction * predicted;
}

double magnitude(const ClothEnergy& e) {
  return std::abs(e.membrane) + std::abs(e.bending) + std::abs(e.external) + std::abs(e.contact) +
         std::abs(e.seam);
}

} // namespace

struct IncrementalSystem::Trial {
  double length = 0.0; // accepted step length; 0: none accepted
  double potential = 0.0;
  double potential_scale = 0.0;
  PetscReal residual_norm = 0.0;
};

bool IncrementalSystem::minimises() const {
  if (!problem_.has_potential()) return false;
  return inertia_->active() ? minimise_time_steps : minimise_statics;
}

// mu's floor: 1e-8 of the largest ratio of the Hessian's diagonal to the
// lumped mass, so that mu M is negligible against every stiffness the
// problem has, yet bounds the steps of its zero-stiffness modes (a panel
// free before its seams pull, a cloth sliding without friction).
PetscErrorCode IncrementalSystem::regularisation_scale(double* scale) {
  PetscFunctionBeginUser;
  PetscCall(MatGetDiagonal(jacobian_, work_));
  PetscCall(VecPointwiseDivide(work_, work_, inertia_->mass()));
  PetscReal largest = 0.0;
  PetscCall(VecMax(work_, nullptr, &largest));
  *scale = 1e-8 * std::max(PetscReal(1.0), largest);
  PetscFunctionReturn(0);
}

// Solves (J + mu M) d = -F at x; `solved` is false when the factorisation or
// the linear solve fails, or d is no descent direction of Phi.
PetscErrorCode IncrementalSystem::newton_direction(Vec x, Vec gradient, double mu, Vec direction,
                                                   bool* solved, PetscInt* linear_iterations) {
  KSP ksp = nullptr;
  KSPConvergedReason reason;
  PetscInt iterations = 0;
  PetscFunctionBeginUser;
  PetscCall(jacobian(x, jacobian_));
  bool stale = false;
  PetscCall(problem_.couplings_stale(&stale));
  if (stale) { // a pair came into contact outside the structure
    PetscCall(refresh_couplings(x));
    PetscCall(jacobian(x, jacobian_));
  }
  if (mu > 0.0) {
    PetscCall(VecCopy(inertia_->mass(), work_));
    PetscCall(VecScale(work_, mu));
    PetscCall(MatDiagonalSet(jacobian_, work_, ADD_VALUES));
  }
  PetscCall(SNESGetKSP(snes_, &ksp));
  PetscCall(KSPSetOperators(ksp, jacobian_, jacobian_));
  PetscCall(KSPSetErrorIfNotConverged(ksp, PETSC_FALSE));
  PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, nullptr));
  int failed = KSPSolve(ksp, gradient, direction) != 0;
  PetscCall(PetscPopErrorHandler());
  // An error raised on some ranks only (after the solve's collective parts)
  // must end the step on every rank, or the others wait in the next
  // collective call for ever.
  PetscCallMPI(MPIU_Allreduce(MPI_IN_PLACE, &failed, 1, MPI_INT, MPI_MAX,
                              PetscObjectComm(reinterpret_cast<PetscObject>(x))));
  *solved = false;
  if (failed) PetscFunctionReturn(0);
  PetscCall(KSPGetConvergedReason(ksp, &reason));
  PetscCall(KSPGetIterationNumber(ksp, &iterations));
  *linear_iterations += iterations;
  if (reason < 0) PetscFunctionReturn(0);
  PetscCall(VecScale(direction, -1.0));
  PetscReal slope = 0.0;
  PetscCall(VecDot(gradient, direction, &slope));
  *solved = std::isfinite(slope) && slope < 0.0;
  PetscFunctionReturn(0);
}

// Backtracks from `first_length` along `direction` until Phi falls by
// Armijo's fraction of its predicted decrease. While that decrease is within
// Phi's round-off, Phi's change is measured by the trapezoidal rule on its
// slope along the step, (F(x)·d + F(x + a d)·d) a/2: the slopes' round-off
// scales with the element forces times |d|, not with Phi, and the rule is
// exact on a quadratic, so Newton's full step is taken whole and a step past
// a kink of the force (a contact switching on, a friction anchor reaching
// its bound) is judged on Phi, not on |F| (which Newton's step need not lower
// there). PETSc's critical-point line search (-snes_linesearch_type cp)
// works on the same slope. A whole step taken may be lengthened
// (extend_step, where `may_extend`). Leaves F at the accepted point in
// trial_f_ and the point in trial_x_.
PetscErrorCode IncrementalSystem::line_search(Vec x, Vec gradient, Vec direction,
                                              double first_length, bool may_extend, Trial* trial) {
  PetscReal slope = 0.0;
  PetscFunctionBeginUser;
  PetscCall(VecDot(gradient, direction, &slope));
  const double potential = trial->potential, scale = trial->potential_scale;
  double length = first_length;
  for (int k = 0; k <= max_halvings; ++k, length *= 0.5) {
    PetscCall(VecWAXPY(trial_x_, length, direction, x));
    double value = 0.0, value_scale = 0.0;
    PetscCall(incremental_potential(trial_x_, &value, &value_scale));
    if (!std::isfinite(value)) continue;
    const double predicted = length * slope; // < 0
    bool accept = false;
    if (resolved_decrease(predicted, scale, value_scale)) {
      accept = sufficient_decrease(value - potential, predicted);
      if (accept) PetscCall(residual(trial_x_, trial_f_));
    } else {
      PetscCall(residual(trial_x_, trial_f_));
      PetscReal end_slope = 0.0;
      PetscCall(VecDot(trial_f_, direction, &end_slope));
      const double change = 0.5 * length * (slope + end_slope);
      accept = sufficient_decrease(change, predicted);
      ++minimiser_statistics.residual_rule_trials;
    }
    if (!accept) continue;
    trial->length = length;
    trial->potential = value;
    trial->potential_scale = value_scale;
    PetscCall(VecNorm(trial_f_, NORM_2, &trial->residual_norm));
    if (may_extend && length >= 1.0) PetscCall(extend_step(direction, slope, trial));
    PetscFunctionReturn(0);
  }
  trial->length = 0.0;
  PetscFunctionReturn(0);
}

// A point farther along the accepted step (IncrementalSystem::extend_step):
// its length, whether the bodies' bound cut it short, Phi's slope along the
// step there, and whether Phi fell from the accepted point by Armijo's
// fraction of what the accepted point's slope predicts (on the slopes where
// that is within round-off, as in line_search). The point is in
// extended_x_, F there in extended_f_.
struct IncrementalSystem::LongerTrial {
  double length = 0.0;
  bool bounded = false;
  double slope = 0.0;
  bool decreased = false;
  double potential = 0.0, potential_scale = 0.0;
};

PetscErrorCode IncrementalSystem::longer_trial(Vec direction, double length, double end_slope,
                                               const Trial& accepted, LongerTrial* longer) {
  PetscFunctionBeginUser;
  // The extra step from the accepted point, bounded by the bodies.
  const double extra = length - accepted.length;
  PetscCall(VecCopy(direction, extended_f_));
  PetscCall(VecScale(extended_f_, extra));
  double bound = 1.0;
  PetscCall(problem_.contact_step_bound(trial_x_, extended_f_, &bound));
  longer->bounded = bound < 1.0;
  longer->length = accepted.length + bound * extra;
  PetscCall(VecWAXPY(extended_x_, bound * extra, direction, trial_x_));
  PetscCall(incremental_potential(extended_x_, &longer->potential, &longer->potential_scale));
  longer->decreased = false;
  longer->slope = std::numeric_limits<double>::quiet_NaN(); // none where Phi is not finite
  if (!std::isfinite(longer->potential)) PetscFunctionReturn(0);
  PetscCall(residual(extended_x_, extended_f_));
  PetscReal slope = 0.0;
  PetscCall(VecDot(extended_f_, direction, &slope));
  longer->slope = slope;
  const double predicted = bound * extra * end_slope; // < 0
  const double change =
      resolved_decrease(predicted, accepted.potential_scale, longer->potential_scale)
          ? longer->potential - accepted.potential
          : 0.5 * bound * extra * (end_slope + longer->slope);
  longer->decreased = sufficient_decrease(change, predicted);
  PetscFunctionReturn(0);
}

PetscErrorCode IncrementalSystem::take_longer_trial(const LongerTrial& longer, Trial* trial) {
  PetscFunctionBeginUser;
  PetscCall(VecCopy(extended_x_, trial_x_));
  PetscCall(VecCopy(extended_f_, trial_f_));
  trial->length = longer.length;
  trial->potential = longer.potential;
  trial->potential_scale = longer.potential_scale;
  PetscCall(VecNorm(trial_f_, NORM_2, &trial->residual_norm));
  ++minimiser_statistics.extended_steps;
  PetscFunctionReturn(0);
}

// Lengthens an accepted whole step at whose end Phi still falls by more
// than crawl_slope of the slope it started with (doubling it, at most
// max_extensions times, while that is more than extension_slope): there
// the Hessian (projected where cloth is compressed, or unstable)
// overestimates Phi's curvature along the step many times, and whole
// Newton steps crawl (a taken-off garment folding,
// Phi falling 1e-9 J an iteration at a constant |F|). A doubling is taken
// where Phi fell and still falls there, not past the minimum along the
// step, nor where Phi falls ever faster (a snap through: buckling cloth,
// whose equilibrium the path decides, is left to Newton's steps). Then one
// trial where the slope, interpolated linearly between the last two lengths
// tried, is zero (a quadratic's minimum along the step), taken where Phi
// fell and its slope is smaller there.
PetscErrorCode IncrementalSystem::extend_step(Vec direction, double slope, Trial* trial) {
  PetscReal end_slope = 0.0;
  PetscFunctionBeginUser;
  PetscCall(VecDot(trial_f_, direction, &end_slope));
  double other_length = 0.0, other_slope = slope; // the secant's other end
  if (!(end_slope < crawl_slope * slope)) PetscFunctionReturn(0);
  LongerTrial longer;
  for (int k = 0; k < max_extensions && end_slope < extension_slope * slope; ++k) {
    PetscCall(longer_trial(direction, 2.0 * trial->length, end_slope, *trial, &longer));
    const bool falling = longer.slope <= 0.0 && longer.slope >= max_slope_growth * slope;
    if (!longer.decreased || !falling) { // the secant runs to the trial not taken
      other_length = longer.length, other_slope = longer.slope;
      break;
    }
    other_length = trial->length, other_slope = end_slope;
    PetscCall(take_longer_trial(longer, trial));
    end_slope = longer.slope;
    if (longer.bounded) PetscFunctionReturn(0);
  }
  if (!(end_slope < 0.0)) PetscFunctionReturn(0);
  // Where the slope's secant through the two ends is zero, past the accepted
  // point: the slope grew from one end to the other.
  const double rise = (other_slope - end_slope) / (other_length - trial->length);
  if (!(rise > 0.0) || !std::isfinite(rise)) PetscFunctionReturn(0);
  const double secant = std::min(trial->length - end_slope / rise, 2.0 * trial->length);
  PetscCall(longer_trial(direction, secant, end_slope, *trial, &longer));
  PetscCall(PetscInfo(snes_,
                      "step lengthened to %g times Newton's, then tried at %g: Phi %s, end slope "
                      "%g of the last\n",
                      trial->length, longer.length, longer.decreased ? "fell" : "did not fall",
                      longer.slope / end_slope));
  if (longer.decreased && std::abs(longer.slope) < std::abs(end_slope))
    PetscCall(take_longer_trial(longer, trial));
  PetscFunctionReturn(0);
}

// Phi at x, the step's inertia and damping included, and the sum of the
// magnitudes of its parts (its round-off scales with that sum).
PetscErrorCode IncrementalSystem::incremental_potential(Vec x, double* value, double* scale) {
  ClothEnergy energy;
  double inertia = 0.0;
  PetscFunctionBeginUser;
  PetscCall(problem_.energy(x, &energy));
  PetscCall(inertia_->energy(x, &inertia));
  *value = energy.total() + inertia;
  *scale = magnitude(energy) + std::abs(inertia);
  PetscFunctionReturn(0);
}

// mu as a power of ten of its floor (level -1: zero), so that its state is
// exact, and the iterations left before the unprojected Hessian is tried
// again.
struct IncrementalSystem::Regularisation {
  double floor = 0.0;
  int level = 0;
  int exact_pause = 0;
  double mu() const { return level < 0 ? 0.0 : floor * std::pow(mu_growth, level); }
};

// The search direction at x, in direction_. Near a solution the unprojected
// Hessian gives Newton's quadratic convergence where the projected one
// converges linearly: tried (*exact) while it gives descent directions that
// the line search takes at least half of, then left for five iterations.
// Else regularised by mu M, mu growing tenfold after each failure; *solved
// is false when twelve tries give no descent direction.
PetscErrorCode IncrementalSystem::search_direction(Vec x, PetscInt iteration,
                                                   Regularisation* regularisation,
                                                   PetscInt* linear_iterations, bool* solved,
                                                   bool* exact) {
  PetscFunctionBeginUser;
  *solved = false;
  *exact = false;
  if (problem_.projects_hessians() && regularisation->level < 0 &&
      regularisation->exact_pause == 0 && iteration > 0) {
    problem_.exact_hessian = true;
    PetscCall(newton_direction(x, residual_, 0.0, direction_, exact, linear_iterations));
    problem_.exact_hessian = false;
    *solved = *exact;
    if (!*exact) regularisation->exact_pause = 5;
  }
  regularisation->exact_pause = std::max(0, regularisation->exact_pause - 1);
  for (int attempt = 0; attempt < 12 && !*solved; ++attempt) {
    PetscCall(newton_direction(x, residual_, regularisation->mu(), direction_, solved,
                               linear_iterations));
    if (*solved) break;
    ++minimiser_statistics.failed_factorisations;
    regularisation->level = std::max(0, regularisation->level + 1);
  }
  PetscFunctionReturn(0);
}

// The progress line (every progress_interval seconds) and -snes_monitor's.
PetscErrorCode IncrementalSystem::print_minimiser_state(PetscInt iteration, const Trial& current,
                                                        PetscReal tolerance, bool monitor,
                                                        double mu, double bound) {
  PetscFunctionBeginUser;
  if (progress_interval > 0.0) {
    const auto now = std::chrono::steady_clock::now();
    if (std::chrono::duration<double>(now - progress_last).count() >= progress_interval) {
      progress_last = now;
      PetscCall(PetscPrintf(
          problem_.comm(),
          "minimiser: %s, iteration %" PetscInt_FMT ", |F| %.3e N (to %.3e), %.1f s\n",
          progress_label.c_str(), iteration, double(current.residual_norm), double(tolerance),
          std::chrono::duration<double>(now - progress_origin).count()));
    }
  }
  if (monitor) {
    PetscCall(PetscPrintf(problem_.comm(),
                          "  %3" PetscInt_FMT " Minimiser |F| %14.12e  Phi %.10e  mu %.3e  "
                          "step bound %.3e\n",
                          iteration, double(current.residual_norm), current.potential, mu, bound));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode IncrementalSystem::minimise(Vec x, Solve* result) {
  PetscReal atol = 0.0, rtol = 0.0, stol = 0.0;
  PetscInt max_iterations = 0, max_evaluations = 0;
  PetscBool monitor = PETSC_FALSE;
  PetscFunctionBeginUser;
  PetscCall(SNESGetTolerances(snes_, &atol, &rtol, &stol, &max_iterations, &max_evaluations));
  PetscCall(PetscOptionsHasName(nullptr, nullptr, "-snes_monitor", &monitor));
  rtol = std::max(rtol, PetscReal(loose_rtol));
  if (loose_rtol > 0.0 && loose_max_iterations > 0)
    max_iterations = std::min(max_iterations, loose_max_iterations);
  *result = Solve{};
  PetscCall(problem_.hold(x));
  PetscCall(residual(x, residual_));
  PetscReal initial_norm = 0.0;
  PetscCall(VecNorm(residual_, NORM_2, &initial_norm));
  Trial current;
  current.residual_norm = initial_norm;
  PetscCall(incremental_potential(x, &current.potential, &current.potential_scale));
  const PetscReal tolerance = std::max(atol, rtol * initial_norm);
  result->tolerance = tolerance;
  // Every solve starts regularised at mu's floor, and leaves it for mu = 0
  // only after a full Newton step: started at 0, a Hessian singular along a free
  // panel's rigid motions would leave the step along them to round-off.
  Regularisation regularisation;
  double bound = 1.0;
  PetscCall(jacobian(x, jacobian_));
  PetscCall(regularisation_scale(&regularisation.floor));
  int& mu_level = regularisation.level;
  int failed_searches = 0, stalled = 0;
  PetscInt iteration = 0;
  result->reason = SNESConvergedReasons[SNES_DIVERGED_MAX_IT];
  for (;; ++iteration) {
    PetscCall(
        print_minimiser_state(iteration, current, tolerance, monitor, regularisation.mu(), bound));
    if (current.residual_norm <= tolerance) {
      result->converged = true;
      result->reason =
          SNESConvergedReasons[current.residual_norm <= atol ? SNES_CONVERGED_FNORM_ABS
                                                             : SNES_CONVERGED_FNORM_RELATIVE];
      break;
    }
    if (iteration >= max_iterations) break;
    bool solved = false, exact = false;
    PetscCall(search_direction(x, iteration, &regularisation, &result->linear_iterations, &solved,
                               &exact));
    if (!solved) {
      result->reason = SNESConvergedReasons[SNES_DIVERGED_LINEAR_SOLVE];
      break;
    }
    PetscCall(problem_.contact_step_bound(x, direction_, &bound));
    if (bound < 1.0) ++minimiser_statistics.step_bound_cuts;
    stalled = bound < stalled_bound ? stalled + 1 : 0;
    if (end_stalled_solves && stalled >= stalled_iterations) {
      result->reason = step_bound_stalled;
      break;
    }
    Trial next = current;
    // Steps regularised beyond mu's floor are short on purpose (the line
    // search cut the steps before them): they are not lengthened.
    PetscCall(line_search(x, residual_, direction_, bound, mu_level <= 0, &next));
    if (exact && next.length < 0.5 * bound) regularisation.exact_pause = 5;
    if (next.length == 0.0 && exact) continue; // the projected Hessian next
    if (next.length == 0.0) {
      if (++failed_searches > 8) {
        result->reason = SNESConvergedReasons[SNES_DIVERGED_LINE_SEARCH];
        break;
      }
      mu_level = std::max(0, mu_level + 1);
      continue;
    }
    failed_searches = 0;
    if (mu_level >= 0) ++minimiser_statistics.regularised_steps;
    if (exact) ++minimiser_statistics.exact_steps;
    PetscCall(VecCopy(trial_x_, x));
    PetscCall(VecCopy(trial_f_, residual_));
    current = next;
    // A full step: the regularisation is not needed as much (none at all
    // once Newton's own step is taken whole, not cut by the bodies); a step
    // cut below a quarter by the line search (not by the bound): it is.
    if (next.length >= bound) {
      mu_level = std::max(next.length >= 1.0 ? -1 : 0, mu_level - 1);
    } else if (next.length < full_step_fraction * bound) {
      mu_level = std::max(0, mu_level + 1);
    }
  }
  result->newton_iterations = iteration;
  result->residual_norm = current.residual_norm;
  norms_[0] = initial_norm;
  PetscFunctionReturn(0);
}

} // namespace sartor
