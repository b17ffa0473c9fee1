#pragma once
// The analysis of a cloth case and its time grid: statics, implicit
// dynamics or creep over real time, and for the last two the end time, the
// (first) step, damping and the output interval. The options are read once
// into a typed TimeCase, each checked on its own and only those the
// analysis uses (a static case reads no time).

#include "app/cli.hpp"
#include "solvers/dynamics.hpp"

#include <string>
#include <vector>

namespace sartor {

// The analysis and time options, declared by this module.
const std::vector<OptionSpec>& time_option_specs();

struct TimeCase {
  std::string analysis = "static"; // static, dynamic or creep
  // Dynamic and creep runs:
  double time_end = 1.0;        // s
  double time_step = 0.01;      // s (creep: the first step)
  double damping = 0.0;         // mass-proportional alpha, 1/s
  double output_interval = 0.0; // s; 0: every step
  // Dynamic runs:
  bool kinetic_damping = false;
  double rest_tolerance = 0.0;
  bool settle = false;
  bool minimise = false; // --dynamic-solver minimise

  bool dynamic() const { return analysis == "dynamic"; }
  bool creep() const { return analysis == "creep"; }
};

// Throws InputError naming the option for an unknown analysis, a malformed
// value or a time grid of too many steps; warns of a grid that looks given
// in the wrong unit.
TimeCase read_time_case(const Options& options);

// The dynamic solver's settings of a dynamic case.
DynamicOptions dynamic_options(const TimeCase& time);

} // namespace sartor
