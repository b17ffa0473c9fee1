#include "app/time_case.hpp"

#include "app/case_checks.hpp"
#include "app/commands.hpp"
#include "common/error.hpp"

namespace sartor {

const std::vector<OptionSpec>& time_option_specs() {
  static const std::vector<OptionSpec> specs = with_module_prefix(
      {
          {"analysis", "KIND", "static",
           "static (equilibrium), dynamic (implicit time stepping) or creep (quasi-static creep "
           "over real time)"},
          {"time-end", "S", "1", "dynamic, creep: end time, s"},
          {"time-step", "S", "0.01",
           "dynamic: time step, s (halved up to 8 times on failure); creep: the first step"},
          {"damping", "1/S", "0",
           "dynamic, creep: mass-proportional damping alpha (force -alpha M v), 1/s (creep: with "
           "--creep-dynamics)"},
          {"kinetic-damping", "", "", "dynamic: zero every velocity at each kinetic-energy peak"},
          {"rest-tolerance", "R", "0",
           "dynamic: stop once the static residual is below R times its initial value (0: never)"},
          {"dynamic-solver", "KIND", "snes",
           "dynamic: snes (PETSc's SNES from the predicted positions) or minimise (drape's static "
           "minimiser on each step's incremental potential, from the last state, with the contact "
           "step bound; docs/drape.md#time-steps-by-the-minimiser)"},
          {"settle", "", "",
           "dynamic: finish (at rest or at --time-end) with a static solve from the last state, "
           "with "
           "the static solve's contact rounds (friction made consistent)"},
          {"output-interval", "S", "0",
           "dynamic, creep: time between the states written to series.h5, s (0: every step)"},
      },
      {"dynamic", "time"}, {{"analysis", "analysis"}, {"output-interval", "time-output-interval"}});
  return specs;
}

TimeCase read_time_case(const Options& options) {
  TimeCase time;
  time.analysis = options.text("analysis");
  if (time.analysis != "static" && !time.dynamic() && !time.creep()) {
    throw InputError("option --analysis: unknown kind '" + time.analysis +
                     "' (static, dynamic, creep)");
  }
  if (time.analysis == "static") return time;
  time.time_end = options.positive_real("time-end");
  time.time_step = options.positive_real("time-step");
  time.damping = options.nonnegative_real("damping");
  time.output_interval = options.nonnegative_real("output-interval");
  check_simulated_time(time.time_end, "time-end");
  if (time.dynamic()) check_time_divisions(time.time_end, "time-end", time.time_step, "time-step");
  check_time_divisions(time.time_end, "time-end", time.output_interval, "output-interval");
  if (!time.dynamic()) return time;
  time.kinetic_damping = options.flag("kinetic-damping");
  time.rest_tolerance = options.nonnegative_real("rest-tolerance");
  time.settle = options.flag("settle");
  time.minimise = minimiser_chosen(options, "dynamic-solver");
  if (time.time_step > 1.0 || time.time_end > 600.0) {
    print_warnings({"--time-step " + options.text("time-step") + " s, --time-end " +
                    options.text("time-end") +
                    " s: a cloth swings in seconds with steps of milliseconds (times in ms?)"});
  }
  return time;
}

DynamicOptions dynamic_options(const TimeCase& time) {
  DynamicOptions dynamic;
  dynamic.time_end = time.time_end;
  dynamic.time_step = time.time_step;
  dynamic.damping = time.damping;
  dynamic.kinetic_damping = time.kinetic_damping;
  dynamic.rest_tolerance = time.rest_tolerance;
  dynamic.output_interval = time.output_interval;
  dynamic.settle = time.settle;
  dynamic.minimise = time.minimise;
  dynamic.print_progress = true;
  return dynamic;
}

} // namespace sartor
