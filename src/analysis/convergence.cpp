#include "analysis/convergence.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>

namespace sartor {

namespace {

constexpr double nan = std::numeric_limits<double>::quiet_NaN();

// log(a / b) / log(c), NaN unless a, b > 0 and finite.
double ratio_order(double a, double b, double c) {
  if (!(a > 0.0) || !(b > 0.0) || !std::isfinite(a) || !std::isfinite(b)) return nan;
  return std::log(a / b) / std::log(c);
}

} // namespace

ConvergenceAnalysis analyse_convergence(const std::vector<double>& h,
                                        const std::vector<double>& values,
                                        std::optional<double> reference) {
  if (h.size() != values.size()) {
    throw std::invalid_argument("analyse_convergence: as many mesh sizes as values needed");
  }
  for (std::size_t k = 0; k < h.size(); ++k) {
    if (!(h[k] > 0.0) || (k > 0 && !(h[k] < h[k - 1]))) {
      throw std::invalid_argument("analyse_convergence: mesh sizes must decrease and be > 0");
    }
  }
  ConvergenceAnalysis analysis;
  analysis.reference = reference;
  const std::size_t n = h.size();
  for (std::size_t k = 0; k < n; ++k) {
    if (reference) {
      analysis.error.push_back(std::abs(values[k] - *reference));
    } else {
      analysis.error.push_back(k == 0 ? nan : std::abs(values[k] - values[k - 1]));
    }
  }
  if (reference) {
    for (std::size_t k = 0; k + 1 < n; ++k) {
      analysis.pairs.push_back(
          {int(k), ratio_order(analysis.error[k], analysis.error[k + 1], h[k] / h[k + 1])});
    }
  }
  for (std::size_t k = 0; k + 2 < n; ++k) {
    ConvergenceTriplet triplet;
    triplet.from = int(k);
    const double d01 = values[k + 1] - values[k];
    const double d12 = values[k + 2] - values[k + 1];
    triplet.monotone = d01 * d12 > 0.0;
    triplet.order = nan;
    triplet.extrapolated = nan;
    triplet.gci = nan;
    if (triplet.monotone)
      triplet.order = ratio_order(std::abs(d01), std::abs(d12), h[k] / h[k + 1]);
    if (std::isfinite(triplet.order) && triplet.order > 0.0) {
      const double factor = std::pow(h[k + 1] / h[k + 2], triplet.order) - 1.0;
      triplet.extrapolated = values[k + 2] + d12 / factor;
      if (values[k + 2] != 0.0) triplet.gci = 1.25 * std::abs(d12 / values[k + 2]) / factor;
    }
    analysis.triplets.push_back(triplet);
  }
  // Least squares on (log h, log e).
  double sx = 0.0, sy = 0.0, sxx = 0.0, sxy = 0.0;
  int count = 0;
  for (std::size_t k = 0; k < n; ++k) {
    const double e = analysis.error[k];
    if (!(e > 0.0) || !std::isfinite(e)) continue;
    const double x = std::log(h[k]);
    const double y = std::log(e);
    sx += x;
    sy += y;
    sxx += x * x;
    sxy += x * y;
    ++count;
  }
  analysis.fitted_points = count;
  analysis.fitted_order = nan;
  analysis.fitted_constant = nan;
  const double denominator = count * sxx - sx * sx;
  if (count >= 2 && denominator > 0.0) {
    analysis.fitted_order = (count * sxy - sx * sy) / denominator;
    analysis.fitted_constant = std::exp((sy - analysis.fitted_order * sx) / count);
  }
  return analysis;
}

} // namespace sartor
