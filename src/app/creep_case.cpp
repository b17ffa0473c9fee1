#include "app/creep_case.hpp"

#include "app/case_checks.hpp"
#include "app/commands.hpp"
#include "common/csv.hpp"
#include "common/error.hpp"
#include "fem/petsc_call.hpp"
#include "material/fabric.hpp"

#include <algorithm>
#include <sstream>

namespace sartor {

const std::vector<OptionSpec>& creep_option_specs() {
  static const std::vector<OptionSpec> specs = with_module_prefix(
      {
          {"load-history", "HISTORY", "",
           "creep: load factor in time 'T:F; ...' (s; two knots at one time: a jump) [1 always]"},
          {"creep-tolerance", "EPS", "1e-3",
           "creep: target largest non-elastic strain increment of a time step"},
          {"min-time-step", "S", "1e-6", "creep: a step cut below this ends the run, s"},
          {"max-time-step", "S", "0", "creep: largest time step, s (0: no limit)"},
          {"creep-scheme", "NAME", "staggered",
           "creep: staggered (thesis Algorithm 2: solve, update, solve) or monolithic (the creep "
           "update inside Newton's residual, consistent tangent)"},
          {"creep-dynamics", "", "",
           "creep: each step a backward Euler step with inertia (--density) and --damping "
           "instead of static equilibrium (the dynamic variant)"},
          {"creep-parameters", "E,ALPHA,LL,LU", "",
           "creep: E (N/m), alpha, lambda_load, lambda_unload (1/s) for both directions [the "
           "fabric's]"},
      },
      {"creep"});
  return specs;
}

CreepCase read_creep_case(const Options& options) {
  CreepCase creep;
  creep.min_step = options.positive_real("min-time-step");
  creep.max_step = options.nonnegative_real("max-time-step");
  creep.tolerance = options.positive_real("creep-tolerance");
  const std::string scheme = options.text("creep-scheme");
  if (scheme == "monolithic") {
    creep.scheme = CreepScheme::monolithic;
  } else if (scheme != "staggered") {
    throw InputError("option --creep-scheme: unknown scheme '" + scheme +
                     "' (staggered, monolithic)");
  }
  if (options.is_set("load-history")) {
    creep.load = LoadHistory::parse(options.text("load-history"), "option --load-history");
  }
  creep.dynamic = options.flag("creep-dynamics");
  if (options.is_set("creep-parameters")) {
    const std::vector<double> values = option_numbers(options, "creep-parameters", 0);
    if (values.size() != 4) {
      throw InputError("option --creep-parameters: expected E,ALPHA,LAMBDA_LOAD,LAMBDA_UNLOAD, "
                       "got " +
                       std::to_string(values.size()) + " number(s)");
    }
    CreepMaterial given;
    given.warp = {values[0], values[1], values[2], values[3]};
    given.weft = given.warp;
    validate(given.warp, "option --creep-parameters");
    creep.given = given;
  }
  return creep;
}

std::string creep_scheme_name(CreepScheme scheme) {
  return scheme == CreepScheme::monolithic ? "monolithic" : "staggered";
}

CreepMaterial creep_material(const CreepCase& creep, const std::string& fabric_name) {
  if (creep.given) return *creep.given;
  const Fabric fabric = resolve_fabrics(fabric_name).front().fabric;
  print_warnings(fabric.warnings);
  fabric.check_creep();
  return {fabric.in(Direction::warp).creep, fabric.in(Direction::weft).creep};
}

namespace {

CreepOptions creep_options(const CreepCase& settings, const TimeCase& time, int load_steps) {
  CreepOptions creep;
  creep.time_end = time.time_end;
  creep.time_step = time.time_step;
  creep.min_step = settings.min_step;
  creep.max_step = settings.max_step;
  creep.creep_tolerance = settings.tolerance;
  creep.scheme = settings.scheme;
  creep.load = settings.load;
  creep.dynamic = settings.dynamic;
  creep.damping = time.damping;
  creep.output_interval = time.output_interval;
  creep.equilibrium.load_steps = load_steps;
  creep.print_progress = true;
  return creep;
}

std::string history_header(bool probe) {
  return std::string("time_s,dt_s,load_factor,newton_iterations,rejected,creep_increment,"
                     "max_viscoelastic_strain,max_permanent_strain,max_tension_N_per_m") +
         (probe ? ",probe_dx_m,probe_dy_m,probe_dz_m" : "") + "\n";
}

RunCheckpoint checked_checkpoint(const std::string& path, const ClothProblem& problem,
                                 bool dynamic) {
  RunCheckpoint checkpoint = read_checkpoint(path);
  if (checkpoint.before || !checkpoint.state.empty()) {
    throw InputError(path + ": the checkpoint is not of a creep run (a drape's or a wear's?); "
                            "resume it as one");
  }
  const TriangleMesh& mesh = problem.mesh();
  if (checkpoint.positions.size() != mesh.vertex_count() ||
      checkpoint.creep.size() != mesh.triangle_count()) {
    throw InputError(path + ": the checkpoint has " + std::to_string(checkpoint.positions.size()) +
                     " vertices and " + std::to_string(checkpoint.creep.size()) +
                     " triangles, the case " + std::to_string(mesh.vertex_count()) + " and " +
                     std::to_string(mesh.triangle_count()) +
                     ": it belongs to another case or mesh");
  }
  if (dynamic != !checkpoint.velocities.empty()) {
    throw InputError(path + ": the checkpoint is of a " +
                     (dynamic ? "quasi-static" : "dynamic (--creep-dynamics)") +
                     " run; resume it as one");
  }
  return checkpoint;
}

} // namespace

CreepRunResult run_creep_case(const CreepCase& creep_case, const TimeCase& time, int load_steps,
                              ClothProblem& problem, Vec x, const CaseCheckpointing& checkpointing,
                              long probe_vertex, CreepCoupling& creep,
                              const CreepStateObserver& observe) {
  const CreepOptions settings = creep_options(creep_case, time, load_steps);
  CreepRunResult result;
  result.scheme = creep_scheme_name(creep_case.scheme);
  std::optional<RunCheckpoint> resume;
  if (!checkpointing.restart_file.empty()) {
    resume = checked_checkpoint(checkpointing.restart_file, problem, settings.dynamic);
    result.resumed = true;
    result.resumed_time = resume->time;
    result.history_csv = resume->history;
    SartorPetscCall(PetscPrintf(problem.comm(), "sartor run: resuming from %s at t = %g s\n",
                                checkpointing.restart_file.c_str(), resume->time));
  } else {
    result.history_csv = history_header(probe_vertex >= 0);
  }

  const CreepObserver record = [&](const CreepStepReport& step, Vec state) -> PetscErrorCode {
    std::vector<ElementCreep> states;
    std::vector<Eigen::Vector3d> positions;
    PetscFunctionBeginUser;
    PetscCall(creep.gather(&states));
    if (probe_vertex >= 0) PetscCall(problem.gather_positions(state, &positions));
    if (is_root()) {
      double viscoelastic = 0.0, permanent = 0.0, tension = 0.0;
      for (const ElementCreep& s : states) {
        viscoelastic = std::max({viscoelastic, s.warp.viscoelastic, s.weft.viscoelastic});
        permanent = std::max({permanent, s.warp.permanent, s.weft.permanent});
        tension = std::max({tension, s.tension_warp, s.tension_weft});
      }
      std::ostringstream row;
      row << format_number(step.time) << ',' << format_number(step.dt) << ','
          << format_number(step.load_factor) << ',' << step.newton_iterations << ','
          << step.rejected << ',' << format_number(step.increment) << ','
          << format_number(viscoelastic) << ',' << format_number(permanent) << ','
          << format_number(tension);
      if (probe_vertex >= 0) {
        const auto v = std::size_t(probe_vertex);
        const Eigen::Vector3d d = positions[v] - problem.mesh().positions[v];
        row << ',' << format_number(d.x()) << ',' << format_number(d.y()) << ','
            << format_number(d.z());
      }
      result.history_csv += row.str() + "\n";
    }
    if (observe) observe(state, step);
    PetscFunctionReturn(0);
  };

  CreepRestart restart;
  restart.resume = resume ? &*resume : nullptr;
  restart.checkpoint_interval = checkpointing.interval;
  check_time_divisions(time.time_end, "time-end", checkpointing.interval, "checkpoint-interval");
  restart.write = [&](const CreepStepReport& step, Vec state, Vec velocity,
                      double next_step) -> PetscErrorCode {
    RunCheckpoint checkpoint;
    PetscFunctionBeginUser;
    checkpoint.time = step.time;
    checkpoint.next_step = next_step;
    checkpoint.step = step.step;
    checkpoint.load_factor = problem.load_factor;
    PetscCall(problem.gather_positions(state, &checkpoint.positions));
    if (velocity) {
      PetscCall(problem.gather_positions(velocity, &checkpoint.velocities));
      for (int pin : problem.pinned()) // gathered as their places: a pin's velocity is not a dof
        if (!checkpoint.velocities.empty()) checkpoint.velocities[std::size_t(pin)].setZero();
    }
    PetscCall(creep.gather(&checkpoint.creep));
    PetscCall(problem.gather_anchors(&checkpoint.anchors));
    checkpoint.history = result.history_csv;
    if (is_root()) write_checkpoint(checkpointing.file, checkpoint);
    ++result.checkpoints_written;
    PetscFunctionReturn(0);
  };
  SartorPetscCall(solve_creep(problem, creep, x, settings, &result.report, record, restart));
  return result;
}

} // namespace sartor
