#pragma once
// Closed-form response of a strip in the thesis' constant-force creep test:
// tension sigma applied at load_time, removed at unload_time. This is what
// `sartor fit` fits; it equals simulate_strip() with a linear elastic curve.
//
//   loading  (t0 <= t < t1):  eps = (1 + sigma/K)(1 + s (1 - e^{-lambda_l (t - t0)})) - 1
//   recovery (t >= t1):       eps = c (alpha + (1 - alpha) e^{-lambda_u (t - t1)})
//   with s = sigma/E and c = s (1 - e^{-lambda_l (t1 - t0)}); eps = 0 before t0.

#include <array>
#include <cstddef>

namespace sartor {

struct CreepTestParameters {
  double elastic_modulus = 0.0; // K, N/m: secant modulus of the immediate response
  double creep_modulus = 0.0;   // E, N/m
  double alpha = 0.0;
  double lambda_load = 0.0;   // 1/s
  double lambda_unload = 0.0; // 1/s
};

enum class TestPhase { before_load = 0, loading = 1, recovery = 2 };

struct CreepTest {
  double tension = 0.0;     // N/m
  double load_time = 0.0;   // s
  double unload_time = 0.0; // s

  TestPhase phase(double time) const {
    if (time < load_time) return TestPhase::before_load;
    return time < unload_time ? TestPhase::loading : TestPhase::recovery;
  }
};

// The fit works in q = (ln K, ln E, alpha, ln lambda_l, ln lambda_u): positive
// parameters stay positive and the problem is better scaled.
constexpr std::size_t creep_test_parameter_count = 5;
using CreepTestVector = std::array<double, creep_test_parameter_count>;
CreepTestVector to_fit_variables(const CreepTestParameters& p);
CreepTestParameters from_fit_variables(const CreepTestVector& q);

// Strain at `count` times, sorted in increasing order; when `jacobian` is not null it receives
// d strain_i / d q_j at jacobian[j * leading_dimension + i] (column-major).
void evaluate_creep_test(const CreepTest& test, const CreepTestParameters& p, const double* times,
                         std::size_t count, double* strain, double* jacobian = nullptr,
                         std::size_t leading_dimension = 0);

} // namespace sartor
