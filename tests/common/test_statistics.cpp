// Quantiles against published table values (Abramowitz & Stegun, Tables 26.1
// and 26.10), to the digits the tables give.
#include "common/statistics.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

namespace {

TEST(Statistics, NormalQuantileMatchesTable) {
  EXPECT_NEAR(sartor::normal_quantile(0.975), 1.959963985, 1e-9);
  EXPECT_NEAR(sartor::normal_quantile(0.995), 2.575829304, 1e-9);
  EXPECT_NEAR(sartor::normal_quantile(0.5), 0.0, 1e-15);
  EXPECT_NEAR(sartor::normal_quantile(0.025), -1.959963985, 1e-9);
}

TEST(Statistics, StudentTQuantileMatchesTable) {
  // Small dof, where an asymptotic expansion in 1/dof is off by percent.
  EXPECT_NEAR(sartor::student_t_quantile(0.975, 1.0), 12.7062047, 1e-6);
  EXPECT_NEAR(sartor::student_t_quantile(0.975, 2.0), 4.30265273, 1e-7);
  EXPECT_NEAR(sartor::student_t_quantile(0.975, 5.0), 2.57058184, 1e-7);
  EXPECT_NEAR(sartor::student_t_quantile(0.975, 30.0), 2.04227246, 1e-7);
  EXPECT_NEAR(sartor::student_t_quantile(0.95, 10.0), 1.81246112, 1e-7);
}

TEST(Statistics, QuantilesRejectProbabilitiesOutsideTheOpenInterval) {
  EXPECT_THROW(sartor::normal_quantile(1.0), std::domain_error);
  EXPECT_THROW(sartor::student_t_quantile(0.0, 5.0), std::domain_error);
  EXPECT_THROW(sartor::student_t_quantile(0.9, 0.0), std::domain_error);
}

} // namespace
