// Run with mpiexec -n 2: the residual and Jacobian rows of the fit are spread
// over the ranks; the result must equal the one-rank fit to solver tolerance.

#include "solvers/creep_fit.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace sartor {
namespace {

TEST(CreepFitMpi, TwoRanksGiveTheOneRankResult) {
  PetscMPIInt size = 1;
  MPI_Comm_size(PETSC_COMM_WORLD, &size);
  ASSERT_GE(size, 2) << "run this test under mpiexec -n 2";
  for (const char* name : {"cotton_twill_warp", "silk_weft", "polyester_warp"}) {
    const CreepTestData data =
        read_creep_test_data(std::string(SARTOR_CASES_DIR) + "/fit/" + name + ".csv", {});
    const ThesisEstimate start = thesis_estimate(data);
    CreepFit parallel, serial;
    ASSERT_EQ(fit_creep_test(PETSC_COMM_WORLD, data, start.parameters, 0.95, &parallel), 0);
    ASSERT_EQ(fit_creep_test(PETSC_COMM_SELF, data, start.parameters, 0.95, &serial), 0);
    ASSERT_TRUE(parallel.converged && serial.converged) << name;
    for (std::size_t j = 0; j < creep_test_parameter_count; ++j) {
      const double a = parallel.estimates[j].value;
      const double b = serial.estimates[j].value;
      EXPECT_NEAR(a, b, 1e-8 * std::abs(b)) << name << " " << creep_test_parameter_names()[j];
      EXPECT_NEAR(parallel.estimates[j].std_error, serial.estimates[j].std_error,
                  1e-6 * serial.estimates[j].std_error);
    }
    EXPECT_NEAR(parallel.rmse, serial.rmse, 1e-10 * serial.rmse);
    EXPECT_NEAR(parallel.autocorrelation.lag1, serial.autocorrelation.lag1, 1e-8);
    // The bootstrap draws the same replicates on any number of ranks.
    BootstrapEstimate parallel_bootstrap, serial_bootstrap;
    ASSERT_EQ(bootstrap_creep_fit(PETSC_COMM_WORLD, data, parallel, 40, 5, &parallel_bootstrap), 0);
    ASSERT_EQ(bootstrap_creep_fit(PETSC_COMM_SELF, data, serial, 40, 5, &serial_bootstrap), 0);
    for (std::size_t j = 0; j < creep_test_parameter_count; ++j) {
      EXPECT_NEAR(parallel_bootstrap.estimates[j].ci_low, serial_bootstrap.estimates[j].ci_low,
                  1e-3 * serial.estimates[j].std_error);
      EXPECT_NEAR(parallel_bootstrap.estimates[j].ci_high, serial_bootstrap.estimates[j].ci_high,
                  1e-3 * serial.estimates[j].std_error);
    }
  }
}

TEST(CreepFitMpi, TwoRanksGiveTheOneRankResultForSeveralTests) {
  // Two tests in one fit (the load-history path): the ranks' blocks split the
  // first test in the middle, so rank 1 integrates the law up to its block.
  const CreepTestData whole =
      read_creep_test_data(std::string(SARTOR_CASES_DIR) + "/fit/denim_warp.csv", {});
  CreepTestData shorter = whole;
  shorter.time.resize(5000);
  shorter.strain.resize(5000);
  shorter.line.resize(5000);
  const CreepTestData data = combine_tests({whole, shorter});
  const ThesisEstimate start = start_estimate(data);
  CreepFit parallel, serial;
  ASSERT_EQ(fit_creep_test(PETSC_COMM_WORLD, data, start.parameters, 0.95, &parallel), 0);
  ASSERT_EQ(fit_creep_test(PETSC_COMM_SELF, data, start.parameters, 0.95, &serial), 0);
  ASSERT_TRUE(parallel.converged && serial.converged);
  for (std::size_t j = 0; j < creep_test_parameter_count; ++j) {
    EXPECT_NEAR(parallel.estimates[j].value, serial.estimates[j].value,
                1e-8 * std::abs(serial.estimates[j].value))
        << creep_test_parameter_names()[j];
  }
  EXPECT_NEAR(parallel.rmse, serial.rmse, 1e-10 * serial.rmse);
}

} // namespace
} // namespace sartor
