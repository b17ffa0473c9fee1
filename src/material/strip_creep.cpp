#include "material/strip_creep.hpp"

#include "common/csv.hpp"
#include "common/error.hpp"

#include <algorithm>
#include <cmath>

namespace sartor {

TensionHistory::TensionHistory(std::vector<TensionBreakpoint> points) : points_(std::move(points)) {
  if (points_.size() < 2) throw InputError("a tension history needs at least two points");
  for (std::size_t i = 0; i < points_.size(); ++i) {
    const auto& p = points_[i];
    if (!std::isfinite(p.time) || !std::isfinite(p.tension)) {
      throw InputError("tension history point " + std::to_string(i) + " is not finite");
    }
    if (p.tension < 0.0) {
      throw InputError("tension history point " + std::to_string(i) + ": tension " +
                       format_number(p.tension) + " N/m < 0 (a strip carries no compression)");
    }
    if (i > 0 && p.time < points_[i - 1].time) {
      throw InputError("tension history point " + std::to_string(i) + ": time decreases");
    }
  }
  if (end_time() <= start_time()) throw InputError("a tension history must span some time");
}

TensionHistory TensionHistory::creep_recovery(double tension, double load_duration,
                                              double recovery_duration) {
  if (!(tension > 0.0) || !std::isfinite(tension)) {
    throw InputError("creep test tension " + format_number(tension) + " N/m must be > 0");
  }
  if (!(load_duration > 0.0) || !(recovery_duration >= 0.0) || !std::isfinite(load_duration) ||
      !std::isfinite(recovery_duration)) {
    throw InputError("creep test durations must be finite, loading > 0 and recovery >= 0 s");
  }
  std::vector<TensionBreakpoint> points{
      {0.0, 0.0}, {0.0, tension}, {load_duration, tension}, {load_duration, 0.0}};
  if (recovery_duration > 0.0) points.push_back({load_duration + recovery_duration, 0.0});
  return TensionHistory(std::move(points));
}

TensionHistory TensionHistory::from_csv(const std::string& path) {
  const CsvTable table = read_csv(path);
  const std::size_t time = table.require({"time_s", "time"}, "time in s");
  const std::size_t tension =
      table.require({"tension_n_per_m", "tension"}, "membrane tension in N/m");
  require_nondecreasing(table, time);
  std::vector<TensionBreakpoint> points;
  for (std::size_t row = 0; row < table.rows(); ++row) {
    const double value = table.columns[tension][row];
    if (value < 0.0) {
      throw InputError(path, table.lines[row],
                       "tension " + format_number(value) +
                           " N/m is negative (a strip carries no compression)");
    }
    points.push_back({table.columns[time][row], value});
  }
  if (points.size() < 2 || points.back().time <= points.front().time) {
    throw InputError(path + ": the history must have at least two rows spanning some time");
  }
  return TensionHistory(std::move(points));
}

std::vector<double> log_sample_times(const TensionHistory& history, double first_offset,
                                     int per_decade) {
  std::vector<double> times;
  const auto& points = history.points();
  const auto slope = [&points](std::size_t i) {
    return (points[i + 1].tension - points[i].tension) / (points[i + 1].time - points[i].time);
  };
  for (std::size_t i = 0; i + 1 < points.size(); ++i) {
    if (points[i + 1].time == points[i].time) continue; // a jump: sample after its last point
    const bool after_jump = i > 0 && points[i - 1].time == points[i].time;
    if (i > 0 && !after_jump && slope(i) == slope(i - 1)) continue;
    const double start = points[i].time;
    const double stop = history.end_time();
    for (int k = 0;; ++k) {
      const double t = start + first_offset * std::pow(10.0, double(k) / per_decade);
      if (t >= stop) break;
      times.push_back(t);
    }
  }
  std::sort(times.begin(), times.end());
  times.erase(std::unique(times.begin(), times.end()), times.end());
  return times;
}

std::vector<double> uniform_sample_times(const TensionHistory& history, double interval) {
  std::vector<double> times;
  const double span = history.end_time() - history.start_time();
  const auto count = static_cast<long>(std::floor(span / interval));
  for (long k = 1; k <= count; ++k)
    times.push_back(history.start_time() + double(k) * interval);
  return times;
}

namespace {

StripState strip_state(const DirectionalMaterial& material, double time, double tension,
                       const CreepState& creep) {
  const double nonelastic = creep.nonelastic();
  const double elastic = material.elastic.strain_at_tension(tension);
  StripState s;
  s.time = time;
  s.tension = tension;
  s.strain_elastic = elastic * (1.0 + nonelastic);
  s.strain_viscoelastic = creep.viscoelastic;
  s.strain_permanent = creep.permanent;
  s.strain_total = s.strain_elastic + nonelastic;
  return s;
}

} // namespace

std::vector<StripState> simulate_strip(const DirectionalMaterial& material,
                                       const TensionHistory& history,
                                       const std::vector<double>& sample_times) {
  const auto& points = history.points();
  std::vector<StripState> rows;
  rows.reserve(points.size() + sample_times.size());
  CreepState creep;
  double time = points.front().time;
  double tension = points.front().tension;
  rows.push_back(strip_state(material, time, tension, creep));
  auto sample = std::upper_bound(sample_times.begin(), sample_times.end(), time);
  for (std::size_t i = 1; i < points.size(); ++i) {
    const TensionBreakpoint& a = points[i - 1];
    const TensionBreakpoint& b = points[i];
    const auto step_to = [&](double t, double next_tension) {
      creep = advance(material.creep, creep, tension, next_tension, t - time);
      time = t;
      tension = next_tension;
      rows.push_back(strip_state(material, time, tension, creep));
    };
    for (; sample != sample_times.end() && *sample < b.time; ++sample) {
      if (*sample <= a.time) continue;
      const double fraction = (*sample - a.time) / (b.time - a.time);
      step_to(*sample, a.tension + fraction * (b.tension - a.tension));
    }
    step_to(b.time, b.tension);
  }
  return rows;
}

} // namespace sartor
