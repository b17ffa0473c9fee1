#pragma once
// Immediate-elastic response of one fabric direction: a piecewise-linear
// tension-strain curve through the origin (Wang et al. style), written as an
// energy density so that a Newton solver sees its true derivatives.
//
// Strain is the elastic strain relative to the unloaded length; tension is
// force per unit width (N/m). Beyond the last point the last segment is
// extended; in compression the first segment is.

#include <string>
#include <vector>

namespace sartor {

struct CurvePoint {
  double strain = 0.0;
  double tension = 0.0; // N/m
};

// What a curve's points are called in errors, and whether its ordinate may
// fall between points. A falling segment (a measured softening) keeps the
// energy well defined; the ordinate must stay >= 0 and the last segment,
// which extends to infinity, must not fall, so the energy never decreases
// with the magnitude of the strain.
struct CurveRules {
  std::string name = "tension-strain curve";
  std::string abscissa = "strain";
  std::string ordinate = "tension";
  std::string unit = "N/m";
  bool softening = false;
};

class TensionCurve {
public:
  // A straight line through the origin with slope `modulus` (N/m).
  static TensionCurve linear(double modulus, const std::string& context);
  // Points after the origin, with strictly increasing strain and tension
  // (or, with rules.softening, tension >= 0). Throws InputError naming
  // `context`, the curve and the offending point.
  static TensionCurve piecewise(const std::vector<CurvePoint>& points, const std::string& context,
                                const CurveRules& rules = {});

  double tension(double strain) const;            // N/m
  double stiffness(double strain) const;          // d tension / d strain, N/m
  double energy_density(double strain) const;     // J/m^2: integral of tension over strain
  double strain_at_tension(double tension) const; // a curve without softening

  const std::vector<CurvePoint>& points() const { return points_; }
  bool is_linear() const { return points_.size() == 2; }
  double initial_modulus() const { return slopes_.front(); }

private:
  explicit TensionCurve(std::vector<CurvePoint> points);
  std::size_t segment_of_strain(double strain) const;

  std::vector<CurvePoint> points_; // starts at the origin
  std::vector<double> slopes_;     // one per segment
  std::vector<double> energy_at_point_;
};

} // namespace sartor
