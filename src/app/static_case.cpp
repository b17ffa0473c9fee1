#include "app/static_case.hpp"

#include "app/commands.hpp"
#include "common/error.hpp"

namespace sartor {

const std::vector<OptionSpec>& static_option_specs() {
  static const std::vector<OptionSpec> specs = with_module_prefix(
      {
          {"load-steps", "N", "1", "load increments (each halved up to 8 times on failure)"},
          {"static-solver", "KIND", "minimise",
           "static: minimise (Newton on the total potential with a contact step bound, "
           "docs/drape.md) or snes (PETSc's SNES with pseudo-transient continuation); pressure on "
           "a "
           "cloth with a free (unpinned) edge has no potential and takes snes"},
          {"sewing-stages", "N", "1",
           "static: sew in N continuation stages of the seam stiffness, starting from "
           "--sewing-start-tension (1: at once)"},
          {"sewing-start-tension", "N/M", "10",
           "static: with --sewing-stages, each seam's pull per metre of seam at the first stage"},
          {"converge-stages", "", "",
           "static: with --sewing-stages, solve every stage after the first to the full tolerance "
           "(the same equilibrium under any CPU's round-off, for two to three times the Newton "
           "iterations; docs/drape.md)"},
          {"contact-max-depth", "F", "0.5",
           "static: stiffen the contact penalty until no vertex is deeper in the offset layer than "
           "F times --contact-offset (0: never)"},
          {"contact-rounds", "N", "30",
           "static: at most N contact rounds after the last stage: re-solves until the friction "
           "anchors' update leaves the state in equilibrium (and no vertex is too deep)"},
      },
      {"static"});
  return specs;
}

StaticCase read_static_case(const Options& options) {
  StaticCase statics;
  statics.load_steps = count_option(options, "load-steps", 1);
  statics.minimise = minimiser_chosen(options, "static-solver");
  statics.sewing_stages = count_option(options, "sewing-stages", 1);
  if (statics.sewing_stages > 1)
    statics.sewing_start_tension = options.positive_real("sewing-start-tension");
  statics.converge_stages = options.flag("converge-stages");
  if (statics.converge_stages && statics.sewing_stages < 2) {
    throw InputError("option --converge-stages: needs --sewing-stages of 2 or more");
  }
  statics.max_offset_depth = options.nonnegative_real("contact-max-depth");
  statics.max_contact_rounds = int(options.integer_in("contact-rounds", 0, 1000));
  return statics;
}

StaticOptions static_options(const StaticCase& statics, bool sews) {
  if (statics.sewing_stages > 1 && !sews) {
    throw InputError("option --sewing-stages: the case has no seams to sew (or they are merged)");
  }
  StaticOptions solve;
  solve.load_steps = statics.load_steps;
  solve.minimise = statics.minimise;
  solve.sewing_stages = statics.sewing_stages;
  solve.converge_stages = statics.converge_stages;
  solve.first_sewing_stage = statics.first_sewing_stage;
  solve.max_offset_depth = statics.max_offset_depth;
  solve.max_contact_rounds = statics.max_contact_rounds;
  // A static solve that runs long says where it is (docs/drape.md).
  solve.progress_interval = 10.0;
  solve.progress_prefix = statics.progress_prefix;
  return solve;
}

} // namespace sartor
