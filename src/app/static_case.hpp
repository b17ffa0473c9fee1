#pragma once
// The static solve of a cloth case (solvers/statics.hpp): load steps, the
// solver, sewing by continuation stages and the contact rounds after them.
// The options are read once into a typed StaticCase.

#include "app/cli.hpp"
#include "solvers/statics.hpp"

#include <string>
#include <vector>

namespace sartor {

// --load-steps, --static-solver, --sewing-stages, --sewing-start-tension,
// --converge-stages, --contact-max-depth, --contact-rounds.
const std::vector<OptionSpec>& static_option_specs();

struct StaticCase {
  int load_steps = 1;
  bool minimise = true;             // --static-solver minimise (else snes)
  int sewing_stages = 1;            // continuation stages of the seam stiffness
  double sewing_start_tension = 10; // N/m, the first stage's pull (with stages)
  bool converge_stages = false;     // every stage after the first to the full tolerance
  int first_sewing_stage = 0;       // StaticOptions::first_sewing_stage (not an option)
  double max_offset_depth = 0.5;    // of the contact offset (0: never stiffen)
  int max_contact_rounds = 30;
  std::string progress_prefix; // StaticOptions::progress_prefix (not an option)
};

// Throws InputError naming the option for a malformed value, or for
// --converge-stages without stages.
StaticCase read_static_case(const Options& options);

// The static solver's settings. `sews`: the problem has seam springs to sew
// (stages need them; InputError otherwise).
StaticOptions static_options(const StaticCase& statics, bool sews);

} // namespace sartor
