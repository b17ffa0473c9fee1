// The arithmetic of `sartor converge` (analysis/convergence.hpp) on sequences
// whose orders are known exactly.

#include "analysis/convergence.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

namespace sartor {
namespace {

TEST(ConvergenceOrders, ExactPowerLawWithReference) {
  // q = 2 + 0.3 h^2 on h = 0.4, 0.2, 0.1, 0.05
  std::vector<double> h{0.4, 0.2, 0.1, 0.05}, q;
  for (double x : h)
    q.push_back(2.0 + 0.3 * x * x);
  const ConvergenceAnalysis a = analyse_convergence(h, q, 2.0);
  ASSERT_EQ(a.error.size(), 4u);
  EXPECT_NEAR(a.error[3], 0.3 * 0.05 * 0.05, 1e-15);
  ASSERT_EQ(a.pairs.size(), 3u);
  for (const auto& pair : a.pairs)
    EXPECT_NEAR(pair.order, 2.0, 1e-9);
  EXPECT_NEAR(a.fitted_order, 2.0, 1e-9);
  EXPECT_NEAR(a.fitted_constant, 0.3, 1e-9);
  EXPECT_EQ(a.fitted_points, 4);
  ASSERT_EQ(a.triplets.size(), 2u);
  for (const auto& triplet : a.triplets) {
    EXPECT_TRUE(triplet.monotone);
    EXPECT_NEAR(triplet.order, 2.0, 1e-9);
    EXPECT_NEAR(triplet.extrapolated, 2.0, 1e-12);
  }
}

TEST(ConvergenceOrders, SelfConvergence) {
  // q = 1 - h^1.5 on halving h, no reference: the order from three levels,
  // the Richardson estimate and the GCI are exact.
  const std::vector<double> h{0.6, 0.3, 0.15};
  std::vector<double> q;
  for (double x : h)
    q.push_back(1.0 - std::pow(x, 1.5));
  const ConvergenceAnalysis a = analyse_convergence(h, q, std::nullopt);
  EXPECT_TRUE(std::isnan(a.error[0]));
  EXPECT_NEAR(a.error[1], std::pow(0.6, 1.5) - std::pow(0.3, 1.5), 1e-15);
  EXPECT_TRUE(a.pairs.empty());
  ASSERT_EQ(a.triplets.size(), 1u);
  EXPECT_NEAR(a.triplets[0].order, 1.5, 1e-12);
  EXPECT_NEAR(a.triplets[0].extrapolated, 1.0, 1e-12);
  // GCI = 1.25 |q2 - q1| / |q2| / (r^p - 1)
  const double r = 2.0;
  EXPECT_NEAR(a.triplets[0].gci, 1.25 * std::abs((q[2] - q[1]) / q[2]) / (std::pow(r, 1.5) - 1),
              1e-15);
  EXPECT_NEAR(a.fitted_order, 1.5, 1e-12); // changes ~ h^1.5 at a constant ratio
}

TEST(ConvergenceOrders, OscillationIsNotExtrapolated) {
  const ConvergenceAnalysis a =
      analyse_convergence({0.4, 0.2, 0.1}, {1.0, 1.1, 1.05}, std::nullopt);
  ASSERT_EQ(a.triplets.size(), 1u);
  EXPECT_FALSE(a.triplets[0].monotone);
  EXPECT_TRUE(std::isnan(a.triplets[0].order));
  EXPECT_TRUE(std::isnan(a.triplets[0].extrapolated));
  EXPECT_TRUE(std::isnan(a.triplets[0].gci));
}

TEST(ConvergenceOrders, ZeroErrorHasNoOrder) {
  const ConvergenceAnalysis a = analyse_convergence({0.2, 0.1}, {1.0, 1.0}, 1.0);
  ASSERT_EQ(a.pairs.size(), 1u);
  EXPECT_TRUE(std::isnan(a.pairs[0].order));
  EXPECT_TRUE(std::isnan(a.fitted_order));
  EXPECT_EQ(a.fitted_points, 0);
}

TEST(ConvergenceOrders, SingleLevel) {
  const ConvergenceAnalysis a = analyse_convergence({0.2}, {1.0}, std::nullopt);
  EXPECT_TRUE(a.pairs.empty());
  EXPECT_TRUE(a.triplets.empty());
  EXPECT_TRUE(std::isnan(a.fitted_order));
}

TEST(ConvergenceOrders, RejectsBadSizes) {
  EXPECT_THROW(analyse_convergence({0.2, 0.2}, {1.0, 2.0}, std::nullopt), std::invalid_argument);
  EXPECT_THROW(analyse_convergence({0.2, 0.1}, {1.0}, std::nullopt), std::invalid_argument);
  EXPECT_THROW(analyse_convergence({-0.2}, {1.0}, std::nullopt), std::invalid_argument);
}

} // namespace
} // namespace sartor
