// Hencky's power-series solution of the clamped circular membrane
// (analysis/hencky.hpp), checked against the literature and against an
// independent numerical solution of the same boundary-value problem.

#include "analysis/hencky.hpp"
#include "common/error.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>

namespace sartor {
namespace {

// The Hencky ODE in its own scaling, N_r = (Eh q^2 a^2)^(1/3) s(xi):
//   s'' + 3 s' / xi + 1 / (8 s^2) = 0,  s'(0) = 0,
// integrated by classical RK4 from a small xi0 (series start) to 1, together
// with the deflection integral I = int xi / (2 s) dxi (= the centre-deflection
// coefficient). Returns {s(1), s'(1), I}.
std::array<double, 3> integrate(double s0, int steps) {
  const double xi0 = 1e-4;
  std::array<double, 3> y{s0 - xi0 * xi0 / (64 * s0 * s0), -xi0 / (32 * s0 * s0),
                          xi0 * xi0 / (4 * s0)};
  const auto f = [](double xi, const std::array<double, 3>& v) {
    return std::array<double, 3>{v[1], -3 * v[1] / xi - 1 / (8 * v[0] * v[0]), xi / (2 * v[0])};
  };
  const double h = (1.0 - xi0) / steps;
  double xi = xi0;
  for (int i = 0; i < steps; ++i) {
    const auto k1 = f(xi, y);
    std::array<double, 3> t;
    for (int j = 0; j < 3; ++j)
      t[j] = y[j] + 0.5 * h * k1[j];
    const auto k2 = f(xi + 0.5 * h, t);
    for (int j = 0; j < 3; ++j)
      t[j] = y[j] + 0.5 * h * k2[j];
    const auto k3 = f(xi + 0.5 * h, t);
    for (int j = 0; j < 3; ++j)
      t[j] = y[j] + h * k3[j];
    const auto k4 = f(xi + h, t);
    for (int j = 0; j < 3; ++j)
      y[j] += h / 6 * (k1[j] + 2 * k2[j] + 2 * k3[j] + k4[j]);
    xi += h;
  }
  return y;
}

// Shooting on s(0) for the clamped edge s'(1) + (1 - nu) s(1) = 0.
std::array<double, 2> shoot(double poisson) {
  double low = 0.3625, high = 0.5; // s(0) = b0 / 4, b0 in [1.45, 2]
  const auto edge = [&](double s0) {
    const auto y = integrate(s0, 4000);
    return y[1] + (1 - poisson) * y[0];
  };
  for (int i = 0; i < 60; ++i) {
    const double middle = 0.5 * (low + high);
    (edge(middle) < 0 ? low : high) = middle;
  }
  const double s0 = 0.5 * (low + high);
  return {4 * s0, integrate(s0, 4000)[2]};
}

TEST(HenckySeries, LiteratureValuesForPoisson03) {
  const HenckySolution solution = hencky_membrane(0.3);
  // Hencky (1915), corrected by Chien (1948): b0 = 1.7244 for nu = 0.3.
  EXPECT_NEAR(solution.b0, 1.7244, 5e-5);
  // Centre deflection w0 = 0.6534 a (q a / Eh)^(1/3) (series value to the
  // digits the independent integration below confirms).
  EXPECT_NEAR(solution.deflection_coefficient, 0.65344334, 5e-9);
  // The series' first coefficients in Hencky's form: b2 = -1 / b0^2,
  // b4 = -2 / (3 b0^5) (from the recurrence by hand).
  EXPECT_NEAR(solution.b[1], -1 / std::pow(solution.b0, 2), 1e-15);
  EXPECT_NEAR(solution.b[2], -2 / (3 * std::pow(solution.b0, 5)), 1e-15);
  // and the centre stress resultant N_r(0) = b0 / 4 (Eh q^2 a^2)^(1/3)
  EXPECT_DOUBLE_EQ(solution.radial_force(0.0), solution.b0 / 4);
}

TEST(HenckySeries, AgreesWithIndependentShooting) {
  for (double poisson : {0.0, 0.25, 0.3, 0.4999}) {
    const HenckySolution series = hencky_membrane(poisson);
    const auto [b0, coefficient] = shoot(poisson);
    EXPECT_NEAR(series.b0, b0, 1e-8) << "nu = " << poisson;
    EXPECT_NEAR(series.deflection_coefficient, coefficient, 1e-8) << "nu = " << poisson;
  }
}

TEST(HenckySeries, SatisfiesTheBoundaryValueProblem) {
  const double nu = 0.3;
  const HenckySolution s = hencky_membrane(nu);
  // w(1) = 0, w decreasing, and the edge condition a N_r' + (1 - nu) N_r = 0.
  EXPECT_NEAR(s.deflection(1.0), 0.0, 1e-14);
  for (double xi = 0.1; xi <= 1.0; xi += 0.1)
    EXPECT_LT(s.deflection(xi), s.deflection(xi - 0.1));
  const double d = 1e-5;
  const double slope = (s.radial_force(1.0) - s.radial_force(1.0 - d)) / d;
  EXPECT_NEAR(slope + (1 - nu) * s.radial_force(1.0), 0.0, 1e-5);
  // Vertical equilibrium at xi: N_r w' = -xi / 2 in these units.
  for (double xi : {0.2, 0.5, 0.9}) {
    const double w_slope = (s.deflection(xi + d) - s.deflection(xi - d)) / (2 * d);
    EXPECT_NEAR(s.radial_force(xi) * w_slope, -xi / 2, 1e-8) << "xi = " << xi;
  }
}

TEST(HenckySeries, CentreDeflectionScales) {
  const double c = hencky_membrane(0.3).deflection_coefficient;
  // cases/fe/hencky.yaml: a = 0.5 m, q = 0.5 Pa, Eh = 1000 N/m.
  EXPECT_NEAR(hencky_centre_deflection(0.5, 0.5, 1000.0, 0.3), 0.0205821756, 1e-10);
  EXPECT_NEAR(hencky_centre_deflection(2.0, 8.0, 1.0, 0.3), c * 2.0 * std::cbrt(16.0), 1e-12);
  EXPECT_NEAR(hencky_centre_deflection(0.5, -0.5, 1000.0, 0.3), -0.0205821756, 1e-10);
  EXPECT_THROW(hencky_membrane(0.6), InputError);
  EXPECT_THROW(hencky_centre_deflection(0.0, 1.0, 1.0, 0.3), InputError);
}

} // namespace
} // namespace sartor
