#pragma once
// What the fit tests share: their generating parameters, thesis Table 5.1,
// written out here rather than read from the fabric presets under test; the
// thesis' constant-force creep test (§5.2.2); and the check that a fit found
// the generating parameters.

#include "solvers/creep_fit.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>

namespace sartor::fit_test_data {

struct TableSet {
  const char* name;
  CreepTestParameters p; // K (taken as 2E, as sartor synth does), E, alpha, lambda_l, lambda_u
};

inline const TableSet table_5_1[] = {
    {"cotton_twill_warp", {65200, 32600, 0.897, 0.0886, 0.002}},
    {"cotton_twill_weft", {28200, 14100, 0.873, 0.0275, 0.00243}},
    {"denim_warp", {51200, 25600, 0.667, 0.0331, 0.0147}},
    {"denim_weft", {85400, 42700, 0.728, 0.054, 0.0031}},
    {"nylon_warp", {99200, 49600, 0.729, 0.0594, 0.00534}},
    {"nylon_weft", {61600, 30800, 0.705, 0.0376, 0.0598}},
    {"polyester_warp", {160800, 80400, 0.674, 0.00508, 0.00197}},
    {"polyester_weft", {21400, 10700, 0.645, 0.0227, 0.0087}},
    {"silk_warp", {108000, 54000, 0.742, 0.0572, 0.00157}},
    {"silk_weft", {43200, 21600, 0.794, 0.311, 0.0019}},
};

constexpr double tension = 196.2 / 0.08; // N/m: 20 kgf on an 8 cm strip, 2452.5 N/m
constexpr double hour = 3600.0;

inline std::array<double, 5> values_of(const CreepTestParameters& p) {
  return {p.elastic_modulus, p.creep_modulus, p.alpha, p.lambda_load, p.lambda_unload};
}

// The fit converged at a certified optimum whose RMSE is the noise to 5 %
// (with n ~ 6,400 samples the RMSE scatters about the noise by
// sqrt(1 / (2 n)) ~ 0.9 %), with every parameter within 3 standard errors of
// the value the data were generated with.
inline void expect_recovers(const CreepFit& fit, const TableSet& set, double noise) {
  EXPECT_TRUE(fit.converged) << set.name << ": " << fit.converged_reason;
  EXPECT_TRUE(fit.optimum_certified) << set.name << ": " << fit.certification;
  EXPECT_NEAR(fit.rmse / noise, 1.0, 0.05) << set.name;
  const auto truth = values_of(set.p);
  for (std::size_t j = 0; j < 5; ++j) {
    const ParameterEstimate& e = fit.estimates[j];
    EXPECT_LT(std::abs(e.value - truth[j]), 3.0 * e.std_error)
        << set.name << " " << creep_test_parameter_names()[j] << ": " << e.value << " +- "
        << e.std_error << ", generated with " << truth[j];
  }
}

} // namespace sartor::fit_test_data
