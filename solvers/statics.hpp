#pragma once
// Static equilibrium of a cloth: the loads ramped up in steps, each solved by
// IncrementalSystem: for a potential, the static minimiser (Newton on the
// total potential, regularised by mu M, its steps bounded by the bodies'
// signed distances, with a line search on the potential; solvers/minimiser.cpp,
// docs/drape.md#the-static-minimiser); otherwise (pressure on a surface with
// a free edge, or
// `minimise` off) PETSc's SNES, and a load step it cannot solve from the
// previous state is approached by pseudo-transient continuation: heavily
// damped backward-Euler steps, each minimising
//     E(x) - f.x + |x - x_k|^2_M / (2 dt^2)       (M: lumped masses)
// with dt growing while steps succeed, until plain Newton converges
// (Sensitive Couture §7's robust path from far-from-equilibrium starts). If
// that fails too, the load increment is halved, up to `max_cutbacks` times,
// and the solve stops with the solver's reason.
//
// Sewing by continuation: with problem.sewing_tension > 0 and seams, the
// seams close in `sewing_stages` stages of their stiffness (the geometric
// ramp of gradual sewing, fem/forms/seam_coupling.hpp, at progress 0, 1/(n-1),
// ..., 1), the loads growing from start_load_factor to the target with the
// same progress, the bodies without friction until the last; every stage but the
// last two is solved to `stage_rtol` of its first residual or for at most
// `stage_max_iterations` Newton iterations (it only starts the next), the
// last two to the full tolerance (the last sets its friction anchors at
// the state the one before ends in). With `converge_stages`, every stage
// after the first is solved to the full tolerance: a stage cut off in
// Newton's transient hands on a state that round-off has moved, and the
// frictionless stages that follow amplify that into another equilibrium;
// a converged stage's equilibrium attracts and removes it (the 4 cm blouse
// ends 2.5e-9 m from its run under another CPU's BLAS kernels instead of
// in another friction-held state, for two to three times the Newton
// iterations; docs/drape.md). The first stage, the seams pulling the
// unloaded garment round the body without friction, has no well-defined
// equilibrium to converge to quickly and keeps the loose budget. The
// friction anchors are lagged: set for what touches a body at the start of
// a stage, and updated (Coulomb's law) between solves.
//
// Contact rounds (minimiser, bodies): friction is lagged, so a solved state
// is an equilibrium with the anchors it was solved with; updating them
// (Coulomb's return mapping: an anchor whose spring pulls beyond the cone of
// the normal force now slides onto it, along the slip) may leave it out of
// equilibrium. After the last stage, the last stage is solved again while
// the residual with the updated anchors is above the last stage's own
// tolerance (friction not yet consistent: IPC's lagged friction, repeated
// until the anchors and normal forces stop changing) or a vertex ended
// deeper than `max_offset_depth` of the contact offset in the offset layer
// (the adaptive penalty: the contact stiffness grows by the ratio of
// depths, twice over), at most `max_contact_rounds` times; the report says
// whether friction ended consistent, and the residual with the anchors in
// effect at the end is the one reported.
//
// Solver choices come from the options database (-snes_*, -ksp_*, -pc_*).
// Defaults: a direct solve (MUMPS LU) of each Newton system.

#include "fem/cloth_problem.hpp"
#include "solvers/incremental_system.hpp"

#include <petscsnes.h>

#include <functional>
#include <string>
#include <vector>

namespace sartor {

struct StaticReport;

struct StaticOptions {
  // The solve ramps the load factor from here to problem.load_factor.
  double start_load_factor = 0.0;
  int load_steps = 1;
  int max_cutbacks = 8;
  double initial_pseudo_step = 1e-2; // dt of the first continuation step, s
  int max_pseudo_steps = 200;        // per load step
  // The static minimiser for a potential (`sartor run` and drape: on by
  // --static-solver's default; off here, for callers of the SNES path).
  bool minimise = false;
  int sewing_stages = 1;         // with problem.sewing_tension > 0
  double stage_rtol = 1e-3;      // of the stages before the last two
  int stage_max_iterations = 30; // of the stages before the last two
  bool converge_stages = false;  // all but the first to the full tolerance
  // The sewing stages before this one are taken as done: the start is sewn
  // already (a drape's finer level, prolonged from the coarser drape).
  int first_sewing_stage = 0;
  int max_contact_rounds = 30;
  double max_offset_depth = 0.5; // fraction of the contact offset
  // N: the friction is consistent once the residual with the anchors
  // updated is within this (0, or less than the last stage's tolerance:
  // that tolerance). A wear asks for a fraction of its certificate's.
  double contact_tolerance = 0.0;
  // Update the friction anchors at the state the solve starts from (new
  // contacts anchored, Coulomb's law applied, normal forces measured there).
  // A wear step starts from the last accepted state, whose anchors its
  // contact rounds made consistent, carried with a moving body: updated at
  // that unsettled start, the penalty's forces there (tens of kN where the
  // carry left cloth deep in the offset layer, against a few hundred N at
  // equilibrium) bounded the first solve's friction, and the rounds after it
  // started 200 N out.
  bool update_anchors_at_start = true;
  // The minimiser's progress lines (stage or round, iteration, |F|, elapsed
  // wall time), one every this many seconds; 0: none.
  double progress_interval = 0.0;
  // Put before what the progress lines say is being solved ("level 2 of 3, ").
  std::string progress_prefix;
  // Checkpoints (docs/reliability.md#checkpoints-and-restart): called
  // collectively after every load step short of the full load, every sewing
  // stage and every contact round with the state and the report so far.
  // With `resume` the solve continues after the load steps, stages and
  // rounds that report counts, from x; the caller has restored x, the
  // friction anchors and the contact stiffness scale it reports.
  std::function<PetscErrorCode(Vec x, const StaticReport& report)> checkpoint;
  const StaticReport* resume = nullptr;
};

struct LoadStepReport {
  double load_factor = 0.0;
  bool converged = false;
  std::string reason;
  PetscInt newton_iterations = 0;
  PetscInt linear_iterations = 0;
  PetscInt pseudo_steps = 0; // continuation steps taken before the final Newton solve
  double residual_norm = 0.0;
  double tolerance = 0.0; // the minimiser's stopping tolerance of this solve
};

// One contact round: what the solve took and what the update after it left.
struct ContactRound {
  PetscInt newton_iterations = 0;
  double residual_norm = 0.0;           // N: with the anchors updated after the solve
  long sliding_vertices = 0;            // anchors that slid at that update
  double contact_stiffness_scale = 1.0; // the penalty the round was solved with
};

// Where the load ramp of the first stage stands between its load steps.
struct LoadRamp {
  bool under_way = false; // a step short of the full load was the last solved
  double reached = 0.0;   // fraction of the ramp
  double increment = 0.0; // the next step's, as a fraction of the ramp
  int cutbacks = 0;       // increments halved so far
};

struct StaticReport {
  bool converged = false;
  std::string reason; // of the last attempt
  std::vector<LoadStepReport> steps;
  LoadRamp ramp;
  PetscInt newton_iterations = 0;
  PetscInt linear_iterations = 0;
  PetscInt pseudo_steps = 0;
  double initial_residual_norm = 0.0;
  double final_residual_norm = 0.0;
  double solve_seconds = 0.0;
  bool minimised = false; // by the static minimiser
  IncrementalSystem::MinimiserStatistics minimiser;
  int sewing_stages = 0; // solved
  // Sewing stages (from 1) before the last that were to reach the full
  // tolerance (the one before the last; all after the first with
  // converge_stages) and stopped short of it, at -snes_max_it: the stages
  // after them started from a state that round-off moves.
  std::vector<int> unconverged_stages;
  int contact_rounds = 0;               // solves after the last stage
  int stalled_stage_resolves = 0;       // stages solved again, stiffer, after the bound stalled
  double contact_stiffness_scale = 1.0; // of the adaptive penalty at the end
  long sliding_vertices = 0;            // anchors that slid at the last update
  // Friction consistent: the residual with the anchors updated at the end
  // (anchored_residual_norm) is within the last stage's tolerance
  // (consistency_tolerance); rounds: one entry per contact round.
  bool friction_consistent = false;
  double anchored_residual_norm = 0.0;
  double consistency_tolerance = 0.0;
  std::vector<ContactRound> rounds;
  // A contact round that did not converge: the state before it is kept,
  // and sliding_vertices says what it left undone.
  bool contact_round_failed = false;
  // m: largest depth of a vertex or edge sample into the offset layer
  double deepest_offset_depth = 0.0;
  double smallest_distance = 0.0; // m: smallest signed distance to a body (< 0: inside)
};

// Whether the solve's deepest vertex or edge sample ended deeper in the
// offset layer than the adaptive penalty allows (options.max_offset_depth).
bool contact_too_deep(const ClothProblem& problem, const StaticOptions& options,
                      const StaticReport& report);

// Solves in place (the seam springs of a sewing stage do not change the
// problem: problem.sewing_stage is back at 1 on return): `x` holds the start and, on return, the
// last converged state.
PetscErrorCode solve_static(ClothProblem& problem, Vec x, const StaticOptions& options,
                            StaticReport* report);
// The same with a system kept from solve to solve (its SNES and Jacobian),
// as a time stepper that solves equilibrium at every step does.
class IncrementalSystem;
PetscErrorCode solve_static(IncrementalSystem& system, Vec x, const StaticOptions& options,
                            StaticReport* report);

} // namespace sartor
