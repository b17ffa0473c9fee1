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
#include <vector>

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

// Any load protocol (ramps, several levels, cycles, creep then recovery): the
// tension is piecewise linear between knots, sorted by time; two knots at one
// time make a jump. Before the first knot the tension is the first knot's,
// after the last it is held at the last knot's. The specimen is virgin at the
// earliest of the first knot and the first sample.
struct LoadKnot {
  double time = 0.0;    // s
  double tension = 0.0; // N/m
};
using LoadHistory = std::vector<LoadKnot>;

// Tension at `time`, right-continuous at a jump.
double tension_at(const LoadHistory& history, double time);

// The creep strains of unit amplitude at the samples from `first_stored` on:
// with E = 1 N/m the law gives eps_v = (1 - alpha) V and eps_p = alpha P, where
// V and P depend only on the rates (scaling the law's targets scales its
// strains and keeps every branch), so eps_v + eps_p = ((1 - alpha) V + alpha P) / E.
struct UnitCreep {
  std::vector<double> tension;      // sigma at the samples, N/m
  std::vector<double> viscoelastic; // V, N/m
  std::vector<double> permanent;    // P, N/m
};
void unit_creep(const LoadHistory& history, double lambda_load, double lambda_unload,
                const double* times, std::size_t count, std::size_t first_stored, UnitCreep* out);

// Strain of a strip under `history` at `count` sorted times: the immediate
// elastic stretch (1 + sigma(t)/K) times the creep stretch (1 + eps_v + eps_p),
// the creep law (creep_law.hpp) stepped exactly through the knots and the
// samples. Only samples from `first_stored` on are written (at index
// i - first_stored), so that one rank's block of samples can be evaluated; the
// earlier times are still integrated. `jacobian` as in evaluate_creep_test,
// with leading_dimension >= count - first_stored.
void evaluate_load_history(const LoadHistory& history, const CreepTestParameters& p,
                           const double* times, std::size_t count, std::size_t first_stored,
                           double* strain, double* jacobian = nullptr,
                           std::size_t leading_dimension = 0);

} // namespace sartor
