#include "material/tension_curve.hpp"

#include "common/error.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace sartor {

namespace {

[[noreturn]] void reject(const std::string& context, const CurveRules& rules,
                         const std::string& what) {
  throw InputError(context + ": " + rules.name + ": " + what);
}

std::string point_text(std::size_t index, const CurvePoint& p, const CurveRules& rules) {
  std::ostringstream text;
  text.precision(10);
  text << "point " << index << " (" << rules.abscissa << " " << p.strain << ", " << rules.ordinate
       << " " << p.tension << " " << rules.unit << ")";
  return text.str();
}

void check_points(const std::vector<CurvePoint>& all, const std::string& context,
                  const CurveRules& rules) {
  if (all.size() < 2) reject(context, rules, "needs at least one point besides the origin");
  for (std::size_t i = 1; i < all.size(); ++i) {
    const CurvePoint& p = all[i];
    const std::string point = point_text(i, p, rules);
    if (!std::isfinite(p.strain) || !std::isfinite(p.tension)) {
      reject(context, rules, point + " is not finite");
    }
    if (p.strain <= all[i - 1].strain) {
      reject(context, rules, point + ": " + rules.abscissa + "s must increase strictly from 0");
    }
    if (!rules.softening && p.tension <= all[i - 1].tension) {
      reject(context, rules, point + ": " + rules.ordinate + "s must increase strictly from 0");
    }
    if (rules.softening && p.tension < 0.0) {
      reject(context, rules, point + ": " + rules.ordinate + "s must be >= 0");
    }
  }
  if (rules.softening && all.back().tension < all[all.size() - 2].tension) {
    reject(context, rules,
           point_text(all.size() - 1, all.back(), rules) + ": the last segment, which goes on " +
               "beyond it, must not fall (else the energy has no lower bound)");
  }
}

} // namespace

TensionCurve TensionCurve::linear(double modulus, const std::string& context) {
  if (!std::isfinite(modulus) || modulus <= 0.0) {
    std::ostringstream text;
    text.precision(17);
    text << "elastic modulus = " << modulus << " N/m must be a finite number > 0";
    reject(context, CurveRules{}, text.str());
  }
  return TensionCurve({{0.0, 0.0}, {1.0, modulus}});
}

TensionCurve TensionCurve::piecewise(const std::vector<CurvePoint>& points,
                                     const std::string& context, const CurveRules& rules) {
  std::vector<CurvePoint> all{{0.0, 0.0}};
  // The origin may be given explicitly; it is implied otherwise.
  const bool starts_at_origin =
      !points.empty() && points.front().strain == 0.0 && points.front().tension == 0.0;
  all.insert(all.end(), points.begin() + (starts_at_origin ? 1 : 0), points.end());
  check_points(all, context, rules);
  return TensionCurve(std::move(all));
}

TensionCurve::TensionCurve(std::vector<CurvePoint> points) : points_(std::move(points)) {
  energy_at_point_.push_back(0.0);
  for (std::size_t i = 1; i < points_.size(); ++i) {
    const CurvePoint& a = points_[i - 1];
    const CurvePoint& b = points_[i];
    slopes_.push_back((b.tension - a.tension) / (b.strain - a.strain));
    energy_at_point_.push_back(energy_at_point_.back() +
                               0.5 * (a.tension + b.tension) * (b.strain - a.strain));
  }
}

std::size_t TensionCurve::segment_of_strain(double strain) const {
  // Segment i spans points i..i+1; the end segments extend to infinity.
  const auto upper = std::upper_bound(points_.begin() + 1, points_.end() - 1, strain,
                                      [](double s, const CurvePoint& p) { return s < p.strain; });
  return static_cast<std::size_t>(upper - points_.begin()) - 1;
}

double TensionCurve::tension(double strain) const {
  const std::size_t i = segment_of_strain(strain);
  return points_[i].tension + slopes_[i] * (strain - points_[i].strain);
}

double TensionCurve::stiffness(double strain) const {
  return slopes_[segment_of_strain(strain)];
}

double TensionCurve::energy_density(double strain) const {
  const std::size_t i = segment_of_strain(strain);
  const double d = strain - points_[i].strain;
  return energy_at_point_[i] + points_[i].tension * d + 0.5 * slopes_[i] * d * d;
}

double TensionCurve::strain_at_tension(double tension) const {
  const auto upper = std::upper_bound(points_.begin() + 1, points_.end() - 1, tension,
                                      [](double t, const CurvePoint& p) { return t < p.tension; });
  const std::size_t i = static_cast<std::size_t>(upper - points_.begin()) - 1;
  return points_[i].strain + (tension - points_[i].tension) / slopes_[i];
}

} // namespace sartor
