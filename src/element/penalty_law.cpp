#include "element/penalty_law.hpp"

namespace sartor::element {

PenaltyLaw penalty_law(double stiffness, double band, double depth) {
  PenaltyLaw law;
  if (depth <= 0.0) return law;
  if (depth >= band) {
    // E(b) = 5 k b^2 / 12 from the onset's integral, k g^2 / 2 after.
    law.energy = 0.5 * stiffness * depth * depth - stiffness * band * band / 12.0;
    law.force = stiffness * depth;
    law.stiffness = stiffness;
    return law;
  }
  const double t = depth / band;
  law.energy = stiffness * depth * depth * t * (2.0 / 3.0 - 0.25 * t);
  law.force = stiffness * depth * t * (2.0 - t);
  law.stiffness = stiffness * t * (4.0 - 3.0 * t);
  return law;
}

} // namespace sartor::element
