#pragma once
// Quasi-static creep of a cloth over real time (thesis §5.3, Algorithm 2):
// each step solves static equilibrium at the step's end time with the
// elements' unloaded lengths frozen, advances every element's creep state
// over the step (fem/creep_coupling.hpp), solves equilibrium again with the
// new unloaded lengths, and accepts the step. The monolithic scheme instead
// solves once, the creep step of every element inside the residual. Loads follow a load-factor
// history in time, pins and bodies their own histories (ClothProblem::time).
//
// Step size: steps land on the knots of the load history, of the pin and
// body motions, and on output times; otherwise the next step is the last one scaled by
// 0.9 creep_tolerance / (largest non-elastic strain increment), within
// [0.5, 2] times the last and [min_step, max_step]. A step whose increment
// exceeds twice the tolerance, or whose equilibrium fails, is rolled back and
// retried shorter, with the friction anchors and contact penalty of the last
// accepted state. An equilibrium with bodies fails too where its contact
// rounds (StaticOptions::max_contact_rounds > 0) end without settling: the
// residual with the anchors updated is above StaticOptions::contact_tolerance
// (or the solve's own tolerance), or a vertex is deeper in the offset layer
// than allowed.
//
// At a jump of the load, or where pins let go (ClothProblem release times),
// the step ends on the left limit, and the second solve is at the right
// limit, so the creep law sees the jump exactly.

#include "fem/checkpoint.hpp"
#include "fem/cloth_problem.hpp"
#include "fem/creep_coupling.hpp"
#include "solvers/load_history.hpp"
#include "solvers/statics.hpp"

#include <functional>
#include <string>
#include <vector>

namespace sartor {

// How equilibrium and the creep update meet within a step (docs/creep-structure.md).
enum class CreepScheme {
  staggered,  // thesis Algorithm 2: solve with the unloaded lengths frozen, update, solve again
  monolithic, // the creep update inside the residual, with its consistent tangent
};

struct CreepOptions {
  CreepScheme scheme = CreepScheme::staggered;
  double time_end = 3600.0;      // s, absolute
  double time_step = 1.0;        // s, the first step
  double min_step = 1e-6;        // s: a step cut below this ends the run
  double max_step = 0.0;         // s; 0: no limit
  double creep_tolerance = 1e-3; // target largest non-elastic strain increment per step
  LoadHistory load;
  double output_interval = 0.0; // s; 0: every step
  StaticOptions equilibrium;    // of the initial solve (load steps, cut-backs)
  // The dynamic variant (the thesis' own simulator): each step's equilibrium
  // is a backward Euler step with the lumped masses and mass-proportional
  // damping (solvers/dynamics.hpp), from the last accepted positions and
  // velocities; the initial state is static equilibrium at rest.
  bool dynamic = false;
  double damping = 0.0;        // alpha, 1/s (dynamic)
  bool print_progress = false; // a line on rank 0 every 10 s of wall time (ProgressClock)
  // The bodies move between the steps (a posed mannequin bending its knees,
  // docs/wear.md#a-body-that-moves), statics only: each step starts with the
  // cloth within follow_reach of a body carried along with it
  // (ClothProblem::carry_with_bodies), what is still inside pushed out
  // (ClothProblem::push_out_of_bodies), and the friction anchors bounded by
  // Coulomb's cone from the step's first solve, so that an anchor the body
  // carried away makes its vertex slide, not pull with the penalty's stiffness.
  bool follow_bodies = false;
  double follow_reach = 0.05; // m
};

struct CreepStepReport {
  long step = 0;     // 0: the initial equilibrium
  double time = 0.0; // s
  double dt = 0.0;   // s
  double load_factor = 0.0;
  PetscInt newton_iterations = 0;
  int rejected = 0;       // attempts rolled back before this step
  double increment = 0.0; // largest non-elastic strain increment of the step
  bool output = false;    // an output time (or the first or last state)
};

struct CreepReport {
  bool completed = false;
  std::string reason; // of the failure when not completed
  std::vector<CreepStepReport> steps;
  PetscInt newton_iterations = 0;
  long rejected_steps = 0;
  double final_time = 0.0;
  double solve_seconds = 0.0;
};

// Called collectively with every accepted state (the initial one too).
using CreepObserver = std::function<PetscErrorCode(const CreepStepReport&, Vec x)>;

// Where a run resumes from (a checkpoint), and when it writes checkpoints.
struct CreepRestart {
  const RunCheckpoint* resume = nullptr; // start from this state instead of solving
  double checkpoint_interval = 0.0;      // s of simulated time; 0: none
  bool every_step = false;               // a checkpoint after every accepted step
  // Writes a checkpoint of the state after `step` (collective; the caller
  // adds what it keeps, such as its history rows). v: the velocities in the
  // dynamic variant, else null.
  std::function<PetscErrorCode(const CreepStepReport& step, Vec x, Vec v, double next_step)> write;
};

// Collective. x: positions, a solution vector of `problem`, advanced in place
// (on failure it holds the last accepted state, problem.time its time).
// Throws InputError for options that make no sense.
PetscErrorCode solve_creep(ClothProblem& problem, CreepCoupling& creep, Vec x,
                           const CreepOptions& options, CreepReport* report,
                           const CreepObserver& observe = {}, const CreepRestart& restart = {});

} // namespace sartor
