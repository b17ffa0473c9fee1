#pragma once
// The pacing and wording of the progress lines of long runs (dynamics,
// creep): at most one line per interval of wall time (10 s), each with the
// wall time elapsed and, from the fraction of the simulated time done, an
// estimate of the wall time that remains (docs/user-guide.md#progress).

#include <chrono>
#include <cstdio>
#include <string>

namespace sartor {

class ProgressClock {
public:
  using Clock = std::chrono::steady_clock;

  explicit ProgressClock(double interval_seconds = 10.0)
      : interval_(interval_seconds), started_(Clock::now()), last_line_(started_) {}

  // Whether a line is due: an interval after the previous one (or the
  // start), or the `last` line; when it is, the clock counts from now.
  bool due(bool last = false) {
    const Clock::time_point now = Clock::now();
    if (!last && seconds(last_line_, now) < interval_) return false;
    last_line_ = now;
    return true;
  }

  // "12.3 s elapsed, about 45 s left" for `fraction` of the work done; no
  // estimate while nothing is done, none once all is.
  std::string timing(double fraction) const {
    const double elapsed = seconds(started_, Clock::now());
    char text[96];
    if (fraction > 0.0 && fraction < 1.0) {
      std::snprintf(text, sizeof text, "%.1f s elapsed, about %s left", elapsed,
                    duration(elapsed * (1.0 - fraction) / fraction).c_str());
    } else {
      std::snprintf(text, sizeof text, "%.1f s elapsed", elapsed);
    }
    return text;
  }

private:
  // In seconds, minutes or hours, whole numbers but for hours: an estimate.
  static std::string duration(double time) {
    char text[32];
    if (time < 120.0) {
      std::snprintf(text, sizeof text, "%.0f s", time);
    } else if (time < 7200.0) {
      std::snprintf(text, sizeof text, "%.0f min", time / 60.0);
    } else {
      std::snprintf(text, sizeof text, "%.1f h", time / 3600.0);
    }
    return text;
  }

  static double seconds(Clock::time_point from, Clock::time_point to) {
    return std::chrono::duration<double>(to - from).count();
  }

  double interval_;
  Clock::time_point started_;
  Clock::time_point last_line_;
};

} // namespace sartor
