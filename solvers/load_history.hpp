#pragma once
// A load factor over time: piecewise linear between knots, with jumps where
// two knots share a time (the left limit is the first knot's value, the
// right limit the last's); constant before the first knot and after the last.
//
// Text form, as in case files: knots "T:FACTOR" separated by ';', e.g. the
// thesis' creep test, loaded for an hour and then unloaded:
//     "0:1; 3600:1; 3600:0"

#include <string>
#include <vector>

namespace sartor {

struct LoadKnot {
  double time = 0.0;   // s
  double factor = 0.0; // multiplies the case's loads
};

class LoadHistory {
public:
  LoadHistory() = default; // no knots: a factor of 1 at all times
  // Throws InputError, prefixed by `what`, for non-finite numbers, times
  // that decrease, or more than two knots at one time.
  LoadHistory(std::vector<LoadKnot> knots, const std::string& what);
  static LoadHistory parse(const std::string& text, const std::string& what);

  double before(double time) const; // left limit at `time`
  double after(double time) const;  // right limit at `time`
  // The knot times (each once), where a stepper should land.
  std::vector<double> times() const;
  bool empty() const { return knots_.empty(); }

private:
  std::vector<LoadKnot> knots_;
};

} // namespace sartor
