#pragma once
// A fabric strip under a prescribed tension history (force control): the
// material-point response that `sartor creep` reports and `sartor fit` fits.
//
// Kinematics follow the structural model: the strip's unloaded length grows
// by the non-elastic strain, and the elastic strain is measured from it, so
//   1 + strain_total = (1 + eps_elastic) (1 + eps_v + eps_p).
// All reported strains are elongations over the rest length and add up:
//   strain_total = strain_elastic + eps_v + eps_p,
//   strain_elastic = eps_elastic (1 + eps_v + eps_p).

#include "material/fabric.hpp"

#include <string>
#include <vector>

namespace sartor {

// Piecewise-linear tension (N/m) in time (s). A jump is two breakpoints at
// the same time.
struct TensionBreakpoint {
  double time = 0.0;
  double tension = 0.0;
};

class TensionHistory {
public:
  // The thesis' constant-force creep test: the load is applied at t = 0,
  // held for `load_duration`, removed, and recovery observed for
  // `recovery_duration`.
  static TensionHistory creep_recovery(double tension, double load_duration,
                                       double recovery_duration);
  // Columns time_s and tension_n_per_m (or time, tension); see docs/formats.md.
  static TensionHistory from_csv(const std::string& path);
  explicit TensionHistory(std::vector<TensionBreakpoint> points);

  const std::vector<TensionBreakpoint>& points() const { return points_; }
  double start_time() const { return points_.front().time; }
  double end_time() const { return points_.back().time; }

private:
  std::vector<TensionBreakpoint> points_;
};

struct StripState {
  double time = 0.0;
  double tension = 0.0; // N/m
  double strain_total = 0.0;
  double strain_elastic = 0.0; // immediate-elastic elongation over the rest length
  double strain_viscoelastic = 0.0;
  double strain_permanent = 0.0;
};

// `per_decade` log-spaced times after every change of the history's value or
// slope, from `first_offset` seconds on, to its end; sorted, no repeats.
std::vector<double> log_sample_times(const TensionHistory& history, double first_offset,
                                     int per_decade);
// Every `interval` seconds from the start of the history.
std::vector<double> uniform_sample_times(const TensionHistory& history, double interval);

// The response at every breakpoint (both sides of a jump) and at `sample_times`
// (sorted; a time equal to a breakpoint's adds no row). Exact: the creep law
// is integrated in closed form between rows.
std::vector<StripState> simulate_strip(const DirectionalMaterial& material,
                                       const TensionHistory& history,
                                       const std::vector<double>& sample_times);

} // namespace sartor
