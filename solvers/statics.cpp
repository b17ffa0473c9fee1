#include "solvers/statics.hpp"

#include "solvers/incremental_system.hpp"
#include "solvers/step_controller.hpp"

#include <algorithm>
#include <chrono>
#include <limits>
#include <string>

namespace sartor {

namespace {

void add(const IncrementalSystem::Solve& solve, LoadStepReport* step) {
  step->newton_iterations += solve.newton_iterations;
  step->linear_iterations += solve.linear_iterations;
  step->residual_norm = solve.residual_norm;
  step->tolerance = solve.tolerance;
  step->reason = solve.reason;
}

// One SNES solve from x; its statistics are added to `step`.
PetscErrorCode newton(IncrementalSystem& system, Vec x, LoadStepReport* step, bool* converged) {
  IncrementalSystem::Solve solve;
  PetscFunctionBeginUser;
  PetscCall(system.solve(x, &solve));
  add(solve, step);
  *converged = solve.converged;
  PetscFunctionReturn(0);
}

// Pseudo-transient continuation towards equilibrium at the current load:
// inertia about the last pseudo-step's state, 1/dt^2 M.
PetscErrorCode continuation(IncrementalSystem& system, Vec x, const StaticOptions& options,
                            LoadStepReport* step, bool* converged) {
  Vec anchor = system.inertia().predicted();
  PetscFunctionBeginUser;
  *converged = false;
  double dt = options.initial_pseudo_step;
  PetscCall(VecCopy(x, anchor));
  for (int k = 0; k < options.max_pseudo_steps && dt > 1e-12; ++k) {
    system.inertia().inertia_weight = 1.0 / (dt * dt);
    bool stepped = false;
    PetscCall(newton(system, x, step, &stepped));
    if (!stepped) {
      PetscCall(VecCopy(anchor, x));
      dt *= 0.25;
      continue;
    }
    ++step->pseudo_steps;
    PetscReal motion = 0.0, size = 0.0;
    PetscCall(VecAXPY(anchor, -1.0, x));
    PetscCall(VecNorm(anchor, NORM_INFINITY, &motion));
    PetscCall(VecNorm(x, NORM_INFINITY, &size));
    PetscCall(VecCopy(x, anchor));
    dt *= 2.0;
    // Near rest, or every tenth step, try the undamped problem.
    if (motion < 1e-3 * size || k % 10 == 9) {
      system.inertia().inertia_weight = 0.0;
      PetscCall(newton(system, x, step, converged));
      if (*converged) break;
      PetscCall(VecCopy(anchor, x));
    }
  }
  system.inertia().inertia_weight = 0.0;
  PetscFunctionReturn(0);
}

// StaticOptions::checkpoint of the state after a load step, stage or round.
PetscErrorCode checkpoint(IncrementalSystem& system, Vec x, const StaticOptions& options,
                          StaticReport* report) {
  PetscFunctionBeginUser;
  if (!options.checkpoint) PetscFunctionReturn(0);
  report->minimiser = system.minimiser_statistics;
  report->contact_stiffness_scale = system.problem().contact.stiffness_scale;
  PetscCall(options.checkpoint(x, *report));
  PetscFunctionReturn(0);
}

// Ramps the load from options.start_load_factor to `target` in load steps,
// halving an increment that fails, as the header says; from where
// report->ramp stands when it is under way (a resumed checkpoint).
PetscErrorCode ramp_load(IncrementalSystem& system, Vec x, const StaticOptions& options,
                         double target, Vec last, StaticReport* report, bool* converged) {
  ClothProblem& problem = system.problem();
  PetscFunctionBeginUser;
  const double start = options.start_load_factor;
  const auto load_at = [&](double fraction) { return start + fraction * (target - start); };
  LoadRamp& ramp = report->ramp;
  if (!ramp.under_way) ramp = {true, 0.0, 1.0 / std::max(1, options.load_steps), 0};
  // The clock of the ramp runs over its fraction, from where it stands.
  StepController fraction(0.0, 1.0, 0.0);
  fraction.resume(ramp.reached);
  while (!fraction.finished()) {
    const StepPlan next = fraction.plan(ramp.increment);
    problem.load_factor = next.to < 1.0 ? load_at(next.to) : target;
    PetscCall(VecCopy(x, last));
    LoadStepReport step;
    step.load_factor = problem.load_factor;
    PetscCall(newton(system, x, &step, &step.converged));
    if (!step.converged && !system.minimises()) {
      PetscCall(VecCopy(last, x));
      PetscCall(continuation(system, x, options, &step, &step.converged));
    }
    report->steps.push_back(step);
    report->newton_iterations += step.newton_iterations;
    report->linear_iterations += step.linear_iterations;
    report->pseudo_steps += step.pseudo_steps;
    report->reason = step.reason;
    if (step.converged) {
      fraction.accept(next);
      ramp.reached = next.to;
      PetscCall(problem.accept_step(x));
      if (ramp.reached < 1.0) PetscCall(checkpoint(system, x, options, report));
      continue;
    }
    PetscCall(VecCopy(last, x));
    if (++ramp.cutbacks > options.max_cutbacks) {
      problem.load_factor = load_at(ramp.reached);
      break;
    }
    ramp.increment *= 0.5;
    PetscCall(PetscInfo(system.snes(), "load step to %g failed (%s); retrying with increment %g\n",
                        problem.load_factor, step.reason.c_str(),
                        ramp.increment * (target - start)));
  }
  *converged = fraction.finished();
  ramp.under_way = false;
  PetscFunctionReturn(0);
}

// One more solve at the full load (a later sewing stage, a contact round).
PetscErrorCode solve_again(IncrementalSystem& system, Vec x, Vec last, StaticReport* report,
                           bool* converged) {
  ClothProblem& problem = system.problem();
  PetscFunctionBeginUser;
  PetscCall(VecCopy(x, last));
  LoadStepReport step;
  step.load_factor = problem.load_factor;
  PetscCall(newton(system, x, &step, &step.converged));
  report->steps.push_back(step);
  report->newton_iterations += step.newton_iterations;
  report->linear_iterations += step.linear_iterations;
  report->reason = step.reason;
  *converged = step.converged;
  if (step.converged) {
    PetscCall(problem.accept_step(x));
  } else {
    PetscCall(VecCopy(last, x));
  }
  PetscFunctionReturn(0);
}

// A sewing stage before the last, solved loosely; its iterate is kept.
PetscErrorCode sewing_stage(IncrementalSystem& system, Vec x, StaticReport* report) {
  PetscFunctionBeginUser;
  LoadStepReport step;
  step.load_factor = system.problem().load_factor;
  system.end_stalled_solves = true; // resew_stalled_stage goes on from there
  PetscCall(newton(system, x, &step, &step.converged));
  system.end_stalled_solves = false;
  report->steps.push_back(step);
  report->newton_iterations += step.newton_iterations;
  report->linear_iterations += step.linear_iterations;
  PetscCall(system.problem().accept_step(x));
  PetscFunctionReturn(0);
}

// The deepest vertex or edge sample in the offset layers, the anchors that
// slid, over all bodies, and the residual with the anchors as updated (into f).
PetscErrorCode measure_contact(ClothProblem& problem, Vec x, Vec f, StaticReport* report) {
  std::vector<BodyContact> bodies;
  PetscFunctionBeginUser;
  PetscCall(problem.contact_report(x, &bodies));
  report->sliding_vertices = 0;
  report->deepest_offset_depth = 0.0;
  report->smallest_distance = std::numeric_limits<double>::max();
  for (const BodyContact& body : bodies) {
    report->sliding_vertices += body.sliding_vertices;
    report->deepest_offset_depth =
        std::max({report->deepest_offset_depth, body.max_penetration, body.edge_max_penetration});
    report->smallest_distance = std::min(report->smallest_distance, body.min_distance);
  }
  PetscCall(problem.residual(x, f));
  PetscCall(VecNorm(f, NORM_2, &report->anchored_residual_norm));
  report->friction_consistent = report->anchored_residual_norm <= report->consistency_tolerance;
  PetscFunctionReturn(0);
}

// The adaptive penalty: stiffer contact where a vertex ended deeper than
// allowed in the offset layer (by the ratio of depths, twice over, at most
// tenfold). Whether it stiffened.
bool stiffen_contact(ClothProblem& problem, const StaticOptions& options,
                     const StaticReport& report) {
  if (!contact_too_deep(problem, options, report)) return false;
  const double allowed = options.max_offset_depth * problem.contact.offset;
  problem.contact.stiffness_scale *= std::min(10.0, 2.0 * report.deepest_offset_depth / allowed);
  return true;
}

// A sewing stage whose minimiser the step bound stalled (a vertex pushed
// into the body harder than the penalty holds it) is solved again with the
// adaptive penalty's stiffer contact, at most three times: without, the
// stage spent its whole -snes_max_it moving nothing (the skirt's 8 cm
// level prolonged from 12 cm, --level-sewing last-two).
PetscErrorCode resew_stalled_stage(IncrementalSystem& system, Vec x, const StaticOptions& options,
                                   Vec f, StaticReport* report) {
  ClothProblem& problem = system.problem();
  PetscFunctionBeginUser;
  for (int again = 0; again < 3; ++again) {
    if (report->steps.back().reason != IncrementalSystem::step_bound_stalled) break;
    PetscCall(measure_contact(problem, x, f, report));
    if (!stiffen_contact(problem, options, *report)) break;
    ++report->stalled_stage_resolves;
    PetscCall(sewing_stage(system, x, report));
  }
  PetscFunctionReturn(0);
}

// Solves the last stage again while the contact rounds of the header ask
// for it: friction not consistent yet, or a vertex too deep.
PetscErrorCode contact_rounds(IncrementalSystem& system, Vec x, const StaticOptions& options,
                              Vec last, Vec f, StaticReport* report) {
  ClothProblem& problem = system.problem();
  PetscFunctionBeginUser;
  if (problem.bodies.empty()) PetscFunctionReturn(0);
  report->consistency_tolerance = std::max(
      options.contact_tolerance, report->steps.empty() ? 0.0 : report->steps.back().tolerance);
  PetscCall(measure_contact(problem, x, f, report));
  if (!system.minimises()) PetscFunctionReturn(0);
  // Sliding within a solve from here on; the solved states of the stages
  // (and their paths) are those of plain springs. After an update, every
  // spring is within its bound, so the two agree at the state reached.
  const bool bounded = problem.contact.bounded_friction;
  problem.contact.bounded_friction = true;
  while (report->converged && report->contact_rounds < options.max_contact_rounds) {
    if (report->friction_consistent && !contact_too_deep(problem, options, *report)) break;
    const double scale = problem.contact.stiffness_scale;
    stiffen_contact(problem, options, *report);
    ++report->contact_rounds;
    system.progress_label =
        options.progress_prefix + "contact round " + std::to_string(report->contact_rounds);
    ContactRound round;
    round.contact_stiffness_scale = problem.contact.stiffness_scale;
    const PetscInt before = report->newton_iterations;
    bool solved = false;
    PetscCall(solve_again(system, x, last, report, &solved));
    round.newton_iterations = report->newton_iterations - before;
    if (!solved) {
      // The state before the round stays, with the anchors and penalty it
      // was measured with; the round's failure is reported.
      problem.contact.stiffness_scale = scale;
      report->contact_round_failed = true;
      PetscCall(measure_contact(problem, x, f, report));
      report->rounds.push_back(round);
      break;
    }
    PetscCall(measure_contact(problem, x, f, report));
    round.residual_norm = report->anchored_residual_norm;
    round.sliding_vertices = report->sliding_vertices;
    report->rounds.push_back(round);
    PetscCall(PetscInfo(system.snes(),
                        "contact round %d: %" PetscInt_FMT " Newton iterations; with the anchors "
                        "updated: residual %g N (consistent at %g N), %ld anchors slid\n",
                        report->contact_rounds, round.newton_iterations, round.residual_norm,
                        report->consistency_tolerance, round.sliding_vertices));
    PetscCall(checkpoint(system, x, options, report));
  }
  problem.contact.bounded_friction = bounded;
  report->contact_stiffness_scale = problem.contact.stiffness_scale;
  PetscFunctionReturn(0);
}

} // namespace

bool contact_too_deep(const ClothProblem& problem, const StaticOptions& options,
                      const StaticReport& report) {
  const double allowed = options.max_offset_depth * problem.contact.offset;
  return allowed > 0.0 && report.deepest_offset_depth > allowed;
}

PetscErrorCode solve_static(ClothProblem& problem, Vec x, const StaticOptions& options,
                            StaticReport* report) {
  PetscFunctionBeginUser;
  IncrementalSystem system(problem, x);
  PetscCall(solve_static(system, x, options, report));
  PetscFunctionReturn(0);
}

PetscErrorCode solve_static(IncrementalSystem& system, Vec x, const StaticOptions& options,
                            StaticReport* report) {
  Vec f = nullptr, last = nullptr;
  ClothProblem& problem = system.problem();
  PetscFunctionBeginUser;
  const auto started = std::chrono::steady_clock::now();
  system.inertia().inertia_weight = 0.0;
  system.inertia().damping_weight = 0.0;
  system.minimise_statics = options.minimise;
  system.minimiser_statistics = {};
  if (options.resume) {
    *report = *options.resume;
    system.minimiser_statistics = report->minimiser;
  }
  system.progress_interval = options.progress_interval;
  system.progress_origin = system.progress_last = started;
  report->minimised = system.minimises();
  for (Vec* v : {&f, &last})
    PetscCall(VecDuplicate(x, v));
  const double target = problem.load_factor;
  const bool sews = problem.sewing_tension > 0.0 && problem.seam_coupling();
  const int stages = sews ? std::max(1, options.sewing_stages) : 1;
  // A resumed ramp goes on within its stage, with the anchors it had.
  const bool resumes_ramp = options.resume && options.resume->ramp.under_way;
  const int sewn = std::clamp(options.first_sewing_stage, 0, stages - 1);
  const int first_stage = !options.resume ? sewn : options.resume->sewing_stages - resumes_ramp;
  for (int stage = first_stage; stage < stages; ++stage) {
    problem.sewing_stage = stages == 1 ? 1.0 : double(stage) / double(stages - 1);
    // The loads grow with the seams' stiffness: the first stage sews the
    // panels round the body unloaded, so that they are closed before their
    // weight pulls them down (without friction while sewing).
    const double stage_load =
        options.start_load_factor + problem.sewing_stage * (target - options.start_load_factor);
    problem.load_factor = stage_load;
    const bool final_stage = stage + 1 == stages;
    // The stage before the last is solved to the full tolerance too: the
    // last sets the friction anchors at its end, and a stage cut off at its
    // iteration budget passed on a state that round-off had already moved
    // (the coarse T-shirt's anchors froze it 1.8 mm apart under another
    // CPU's BLAS kernels); Newton's convergence removes that difference.
    const bool converged_stage = stage + 2 >= stages || (options.converge_stages && stage > 0);
    system.loose_rtol = converged_stage ? 0.0 : options.stage_rtol;
    system.loose_max_iterations = options.stage_max_iterations;
    if (!(resumes_ramp && stage == first_stage)) {
      // Friction anchors for what touches a body now (none while sewing).
      if (stage > 0 || options.update_anchors_at_start) PetscCall(problem.update_contact(x));
      if (stage == sewn) {
        PetscCall(problem.residual(x, f));
        PetscCall(VecNorm(f, NORM_2, &report->initial_residual_norm));
      }
    }
    report->sewing_stages = stage + 1;
    system.progress_label = options.progress_prefix + "stage " + std::to_string(stage + 1) +
                            " of " + std::to_string(stages);
    if (!final_stage) {
      // A stage before the last only starts the next: its iterate is kept
      // even where it did not reach the loose tolerance in its budget.
      PetscCall(sewing_stage(system, x, report));
      PetscCall(resew_stalled_stage(system, x, options, f, report));
      if (converged_stage && !report->steps.back().converged)
        report->unconverged_stages.push_back(stage + 1);
      // Seams pulling cloth against a body: the next stage's stiffer
      // springs need a stiffer penalty to hold it outside.
      if (system.minimises() && !problem.bodies.empty() && options.max_contact_rounds > 0) {
        PetscCall(measure_contact(problem, x, f, report));
        stiffen_contact(problem, options, *report);
      }
    } else if (stage == 0) {
      PetscCall(ramp_load(system, x, options, stage_load, last, report, &report->converged));
    } else {
      PetscCall(solve_again(system, x, last, report, &report->converged));
    }
    PetscCall(checkpoint(system, x, options, report));
  }
  system.loose_rtol = 0.0;
  problem.sewing_stage = 1.0;
  PetscCall(contact_rounds(system, x, options, last, f, report));
  report->minimiser = system.minimiser_statistics;
  // The minimiser's last residual is that of the friction anchors it solved
  // with; with bodies, the one with the anchors updated after it is the
  // state's.
  if (report->minimised && !problem.bodies.empty()) {
    report->final_residual_norm = report->anchored_residual_norm;
  } else if (report->minimised && report->converged && !report->steps.empty()) {
    report->final_residual_norm = report->steps.back().residual_norm;
  } else {
    PetscCall(problem.residual(x, f));
    PetscCall(VecNorm(f, NORM_2, &report->final_residual_norm));
  }
  report->solve_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  for (Vec* v : {&f, &last})
    PetscCall(VecDestroy(v));
  PetscFunctionReturn(0);
}

} // namespace sartor
