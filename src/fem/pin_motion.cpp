#include "fem/pin_motion.hpp"

#include "common/error.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace sartor {

namespace {

std::string trimmed(const std::string& text) {
  const auto first = text.find_first_not_of(" \t\n\r");
  if (first == std::string::npos) return "";
  const auto last = text.find_last_not_of(" \t\n\r");
  return text.substr(first, last - first + 1);
}

double parse_number(const std::string& text, const std::string& where) {
  const std::string item = trimmed(text);
  try {
    std::size_t used = 0;
    const double value = std::stod(item, &used);
    if (used == item.size() && std::isfinite(value)) return value;
  } catch (const std::exception&) {
  }
  throw InputError(where + ": '" + item + "' is not a finite number");
}

} // namespace

PinHistory::PinHistory(std::vector<PinKnot> knots, const std::string& what)
    : knots_(std::move(knots)) {
  if (knots_.empty()) throw InputError(what + ": a motion history needs at least one knot");
  for (std::size_t k = 0; k < knots_.size(); ++k) {
    const PinKnot& knot = knots_[k];
    if (!std::isfinite(knot.time) || !knot.translation.allFinite() || !std::isfinite(knot.angle)) {
      throw InputError(what + ": knot " + std::to_string(k + 1) +
                       " has a number that is not finite");
    }
    if (k > 0 && !(knot.time > knots_[k - 1].time)) {
      std::ostringstream message;
      message << what << ": knot times must increase, but knot " << k + 1 << " is at " << knot.time
              << " after " << knots_[k - 1].time;
      throw InputError(message.str());
    }
  }
}

PinHistory PinHistory::parse(const std::string& text, const std::string& what) {
  std::vector<PinKnot> knots;
  std::stringstream stream(text);
  std::string item;
  while (std::getline(stream, item, ';')) {
    item = trimmed(item);
    if (item.empty()) continue; // a trailing ';'
    const std::string where =
        what + ", knot " + std::to_string(knots.size() + 1) + " '" + item + "'";
    const auto colon = item.find(':');
    if (colon == std::string::npos) {
      throw InputError(where + ": expected TIME:DX,DY,DZ or TIME:DX,DY,DZ,ANGLE_DEG");
    }
    PinKnot knot;
    knot.time = parse_number(item.substr(0, colon), where);
    std::vector<double> values;
    std::stringstream numbers(item.substr(colon + 1));
    std::string number;
    while (std::getline(numbers, number, ','))
      values.push_back(parse_number(number, where));
    if (values.size() != 3 && values.size() != 4) {
      throw InputError(where +
                       ": expected 3 displacements (m) and optionally an angle (degrees), got " +
                       std::to_string(values.size()) + " numbers");
    }
    knot.translation = {values[0], values[1], values[2]};
    if (values.size() == 4) knot.angle = values[3] * M_PI / 180.0;
    knots.push_back(knot);
  }
  return PinHistory(std::move(knots), what);
}

PinKnot PinHistory::at(double clock) const {
  if (knots_.empty()) return {};
  if (clock <= knots_.front().time) return knots_.front();
  if (clock >= knots_.back().time) return knots_.back();
  const auto after = std::upper_bound(knots_.begin(), knots_.end(), clock,
                                      [](double t, const PinKnot& knot) { return t < knot.time; });
  const PinKnot& b = *after;
  const PinKnot& a = *(after - 1);
  const double s = (clock - a.time) / (b.time - a.time);
  PinKnot knot;
  knot.time = clock;
  knot.translation = (1.0 - s) * a.translation + s * b.translation;
  knot.angle = (1.0 - s) * a.angle + s * b.angle;
  return knot;
}

Eigen::Vector3d PinGroupMotion::place(const Eigen::Vector3d& reference, double clock) const {
  const PinKnot knot = history.at(clock);
  if (knot.angle == 0.0) return reference + knot.translation;
  const Eigen::AngleAxisd rotation(knot.angle, axis);
  return center + rotation * (reference - center) + knot.translation;
}

} // namespace sartor
