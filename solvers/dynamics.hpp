#pragma once
// Implicit dynamics of a cloth: backward Euler on the positions with lumped
// masses M. Each step from (x_n, v_n) over dt minimises the incremental potential
//     E(x) - f.x + |x - x_n - dt v_n|^2_M / (2 dt^2) + alpha |x - x_n|^2_M / (2 dt)
// (the last term: mass-proportional Rayleigh damping, force -alpha M v), with
// the pins at their prescribed places at the step's end time; then
// v_{n+1} = (x_{n+1} - x_n) / dt. The SNES is the statics' (same options
// database; where SNES fails on a potential, the minimiser solves the step
// from x_n, IncrementalSystem::solve). A step neither solves is halved up
// to `max_cutbacks` times;
// after that the run stops with SNES's reason in the report (x, v and
// problem.time hold the last accepted step). After a cut, dt doubles back
// towards time_step as steps succeed; steps land on the output times (the
// multiples of output_interval), on the problem's event times (knots of pin
// and body motions, pin releases: ClothProblem::event_times) and on
// time_end (solvers/step_controller.hpp).
//
// Kinetic damping (Sensitive Couture §7): whenever the kinetic energy passes a
// peak (it drops below the previous step's), every velocity is set to zero.
// With it the motion creeps into the nearest minimum of E - f.x: a robust path
// to static equilibrium from far starts. `rest_tolerance` then ends the run
// once the static residual |grad E - f| falls below that fraction of its
// value at the start.
//
// `settle` finishes a relaxation with a static solve (no inertia; statics'
// solve_static at the full load, with its contact rounds: re-solved with the
// friction anchors updated until that update leaves the state in
// equilibrium) from the last state, at rest or at time_end: kinetic damping
// brings the cloth near its equilibrium cheaply, and Newton's quadratic
// convergence closes the last gap, so that the reactions balance the loads
// to solver tolerance.
//
// problem.time is the clock: prescribed pin motions and body motions are
// evaluated at it (solve_dynamic sets pins_follow_time). Friction anchors are
// set for what touches a body at the start (problem.update_contact) and
// problem.accept_step runs after every accepted step (and after the settle).

#include "fem/cloth_problem.hpp"

#include <functional>
#include <string>
#include <vector>

namespace sartor {

struct DynamicOptions {
  double time_end = 1.0;   // s, absolute (the run starts at problem.time)
  double time_step = 0.01; // s
  double damping = 0.0;    // alpha, 1/s
  bool kinetic_damping = false;
  int max_cutbacks = 8;         // halvings of one step before the run stops
  double output_interval = 0.0; // s; 0: every step
  double rest_tolerance = 0.0;  // 0: run to time_end
  bool print_progress = false;  // a line on rank 0 every 10 s of wall time (ProgressClock)
  bool settle = false;          // finish with a static solve (solve_static)
  // Each step by the static minimiser on the incremental potential
  // (IncrementalSystem::minimise_time_steps) instead of SNES.
  bool minimise = false;
};

struct DynamicStepReport {
  PetscInt step = 0; // 0: the initial state
  double time = 0.0; // s, at the step's end
  double dt = 0.0;   // s
  PetscInt newton_iterations = 0;
  PetscInt linear_iterations = 0;
  int rejected = 0; // attempts cut back before this one succeeded
  std::string reason;
  double kinetic_energy = 0.0;       // J, 1/2 v.Mv before any kinetic-damping reset
  double potential_energy = 0.0;     // J, E - f.x (ClothEnergy::total)
  double static_residual_norm = 0.0; // |grad E - f| at the step's state, N
  bool velocities_reset = false;     // by kinetic damping
  bool output = false;               // an output time (or the first or last state)
};

struct DynamicReport {
  bool completed = false;               // reached time_end, or rest
  bool at_rest = false;                 // stopped by rest_tolerance
  std::string reason;                   // of the failure when not completed
  std::vector<DynamicStepReport> steps; // the initial state first
  PetscInt newton_iterations = 0;
  PetscInt linear_iterations = 0;
  PetscInt rejected_steps = 0;
  PetscInt velocity_resets = 0;
  double final_time = 0.0;
  double solve_seconds = 0.0;
  // With DynamicOptions::settle: the final static solve (its iterations are
  // also counted in newton_iterations and linear_iterations).
  bool settled = false;
  std::string settle_reason;
  PetscInt settle_newton_iterations = 0; // contact rounds included
  int settle_contact_rounds = 0;         // re-solves with the friction anchors updated
  // The last contact round did not converge (the state before it is kept).
  bool settle_contact_round_failed = false;
  // N, |grad E - f| of the settled state, with the anchors it was solved with.
  double settle_residual_norm = 0.0;
};

// Called collectively with the state after every accepted step (and with the
// initial state, step 0).
using DynamicObserver = std::function<PetscErrorCode(const DynamicStepReport&, Vec x, Vec v)>;

// The step controller between two accepted steps: what a run continues from
// besides x, v, problem.time, the friction anchors and the report so far
// (docs/reliability.md#checkpoints-and-restart).
struct DynamicControl {
  double start = 0.0;            // s, the run's start time
  double time = 0.0;             // s, of the last accepted step
  double next_step = 0.0;        // s, the next attempt's dt
  PetscInt step = 0;             // accepted steps so far
  double previous_kinetic = 0.0; // J, for kinetic damping's peak test
  double initial_residual = 0.0; // N, for rest_tolerance
};

// Checkpoints of a run: `write` is called collectively after every accepted
// step that ends at or past a multiple of `interval` (s of simulated time;
// 0: never), once the observer has seen it. With `resume` the run continues
// from that controller state; the caller has put the checkpoint's x, v,
// problem.time, anchors and report (steps and counts) in place.
struct DynamicCheckpoints {
  const DynamicControl* resume = nullptr;
  double interval = 0.0;
  std::function<PetscErrorCode(const DynamicControl&, Vec x, Vec v)> write;
};

// Collective. x: positions (free dofs), v: velocities (m/s), both solution
// vectors of `problem`, advanced in place. Throws InputError for options that
// make no sense (time_end before problem.time, dt <= 0, ...).
PetscErrorCode solve_dynamic(ClothProblem& problem, Vec x, Vec v, const DynamicOptions& options,
                             DynamicReport* report, const DynamicObserver& observe = {},
                             const DynamicCheckpoints& checkpoints = {});

} // namespace sartor
