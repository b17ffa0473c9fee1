#pragma once
// Prescribed motions of pinned vertices over a clock: piecewise-linear
// histories of a translation and of a rotation angle about a fixed axis.
//
// A pin whose reference position is p sits, at clock t, at
//     c + R(a(t)) (p - c) + d(t)
// with d(t) and a(t) interpolated linearly between knots and held constant
// before the first knot and after the last; R(a) rotates by a radians about
// the unit `axis` through the `center` c. The clock is the load factor in
// statics and the time in dynamics (ClothProblem::pins_follow_time).
//
// Text form, as in case files: knots separated by ';', each
//     T:DX,DY,DZ          or     T:DX,DY,DZ,ANGLE
// (T in the clock's unit, displacements in m, ANGLE in degrees), e.g.
//     "0:0,0,0; 1:0,0,0.1; 2:0,0,0".

#include <Eigen/Core>

#include <string>
#include <vector>

namespace sartor {

struct PinKnot {
  double time = 0.0;
  Eigen::Vector3d translation = Eigen::Vector3d::Zero(); // m
  double angle = 0.0;                                    // rad
};

class PinHistory {
public:
  PinHistory() = default;
  // Throws InputError, prefixed by `what` (e.g. "option --pin-motion"), when
  // there is no knot, a number is not finite or the times do not increase.
  PinHistory(std::vector<PinKnot> knots, const std::string& what);
  static PinHistory parse(const std::string& text, const std::string& what);

  // Translation and angle at `clock`.
  PinKnot at(double clock) const;
  const std::vector<PinKnot>& knots() const { return knots_; }
  bool empty() const { return knots_.empty(); }

private:
  std::vector<PinKnot> knots_;
};

struct PinGroupMotion {
  std::vector<std::size_t> pins; // indices into ClothProblem::pinned()
  PinHistory history;
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ(); // unit vector
  Eigen::Vector3d center = Eigen::Vector3d::Zero();

  // Where a pin with this reference position is at `clock`.
  Eigen::Vector3d place(const Eigen::Vector3d& reference, double clock) const;
};

} // namespace sartor
