#include "analysis/hencky.hpp"

#include "common/error.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace sartor {

namespace {

constexpr std::size_t max_terms = 1000;
constexpr double negligible = 1e-18;

// b_n from b_0 by the recurrence of B^2 (B'' + 3 B' / xi) = -8, until the
// terms are negligible. L_k = 4 (k+1)(k+2) b_(k+1) is the xi^2k coefficient of
// B'' + 3 B' / xi, c_k that of B^2: sum_(m<=k) c_(k-m) L_m = -8 [k = 0].
std::vector<double> series(double b0) {
  std::vector<double> b{b0};
  std::vector<double> c{b0 * b0};
  std::vector<double> L;
  while (b.size() < max_terms) {
    const std::size_t k = L.size();
    double sum = k == 0 ? -8.0 : 0.0;
    for (std::size_t m = 0; m < k; ++m)
      sum -= c[k - m] * L[m];
    L.push_back(sum / c[0]);
    b.push_back(L.back() / (4.0 * double(k + 1) * double(k + 2)));
    const std::size_t n = b.size() - 1;
    double square = 0.0;
    for (std::size_t i = 0; i <= n; ++i)
      square += b[i] * b[n - i];
    c.push_back(square);
    if (std::abs(b.back()) < negligible * b0 && n > 4) return b;
  }
  throw std::logic_error("Hencky series: no convergence for b0 = " + std::to_string(b0));
}

// sum (2n + 1 - nu) b_n: a N_r'(a) + (1 - nu) N_r(a), in units of N_r's scale.
double edge_condition(double b0, double poisson) {
  const std::vector<double> b = series(b0);
  double sum = 0.0;
  for (std::size_t n = 0; n < b.size(); ++n)
    sum += (2.0 * double(n) + 1.0 - poisson) * b[n];
  return sum;
}

} // namespace

double HenckySolution::deflection(double xi) const {
  const double xi2 = xi * xi;
  double power = xi2; // xi^(2n+2)
  double sum = 0.0;
  for (std::size_t n = 0; n < d.size(); ++n) {
    sum += d[n] * (1.0 - power) / double(n + 1);
    power *= xi2;
  }
  return sum;
}

double HenckySolution::radial_force(double xi) const {
  const double xi2 = xi * xi;
  double power = 1.0;
  double sum = 0.0;
  for (double coefficient : b) {
    sum += coefficient * power;
    power *= xi2;
  }
  return 0.25 * sum;
}

HenckySolution hencky_membrane(double poisson) {
  if (!(poisson > -1.0 && poisson <= 0.5)) {
    throw InputError("Hencky's membrane: Poisson's ratio must lie in (-1, 0.5], got " +
                     std::to_string(poisson));
  }
  // The edge condition is negative at b0 = 1.45 and positive at 2.5 for every
  // admissible nu (b0 runs from about 1.48 at nu = -1 to 1.845 at nu = 0.5),
  // and the series converges on that bracket.
  double low = 1.45;
  double high = 2.5;
  if (!(edge_condition(low, poisson) < 0.0 && edge_condition(high, poisson) > 0.0)) {
    throw std::logic_error("Hencky series: b0 not bracketed");
  }
  for (int iteration = 0; iteration < 200 && high - low > 4e-16 * high; ++iteration) {
    const double middle = 0.5 * (low + high);
    (edge_condition(middle, poisson) < 0.0 ? low : high) = middle;
  }
  HenckySolution solution;
  solution.poisson = poisson;
  solution.b0 = 0.5 * (low + high);
  solution.b = series(solution.b0);
  // 1 / B as a series: d_0 = 1 / b_0, d_k = -(sum_(i=1..k) b_i d_(k-i)) / b_0,
  // as many terms as B has plus enough for d_k to be negligible too.
  solution.d.push_back(1.0 / solution.b0);
  while (solution.d.size() < max_terms) {
    const std::size_t k = solution.d.size();
    double sum = 0.0;
    for (std::size_t i = 1; i <= k && i < solution.b.size(); ++i)
      sum += solution.b[i] * solution.d[k - i];
    solution.d.push_back(-sum / solution.b0);
    if (k >= solution.b.size() && std::abs(solution.d.back()) < negligible * solution.d[0]) break;
  }
  solution.deflection_coefficient = solution.deflection(0.0);
  return solution;
}

double hencky_centre_deflection(double radius, double pressure, double tensile_stiffness,
                                double poisson) {
  if (!(radius > 0.0) || !(tensile_stiffness > 0.0)) {
    throw InputError("Hencky's membrane: radius and tensile stiffness must be > 0");
  }
  const double coefficient = hencky_membrane(poisson).deflection_coefficient;
  return std::copysign(
      coefficient * radius * std::cbrt(std::abs(pressure) * radius / tensile_stiffness), pressure);
}

} // namespace sartor
