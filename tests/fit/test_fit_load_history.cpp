// The creep fit on real protocols: the load as a piecewise-linear history (a
// 5 s ramp up, 1 h hold, 5 s ramp down, 1 h recovery; two load levels in
// sequence), sampled as testing machines do (log-spaced after each load
// change, dropouts, noise). The data come from the creep law's ODE (thesis
// eqs. 5.7, 5.8) integrated here by classical Runge-Kutta with small steps,
// independently of the exact stepping under test.

#include "fit_test_data.hpp"
#include "solvers/creep_fit.hpp"

#include <gtest/gtest.h>

#include <petscsys.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <random>
#include <string>
#include <vector>

namespace sartor {
namespace {

using fit_test_data::expect_recovers;
using fit_test_data::hour;
using fit_test_data::table_5_1;
using fit_test_data::TableSet;
using fit_test_data::tension;
using fit_test_data::values_of;
constexpr double ramp = 5.0; // s

// 5 s ramp to the test tension, held 1 h, 5 s ramp down, 1 h of recovery.
const LoadHistory ramped_test = {
    {0.0, 0.0}, {ramp, tension}, {ramp + hour, tension}, {2 * ramp + hour, 0.0}};
// Half the tension for 1 h, then the full tension for 1 h, then 1 h of recovery.
const LoadHistory two_level_test = {
    {0.0, 0.0},          {ramp, 0.5 * tension}, {hour, 0.5 * tension}, {hour + ramp, tension},
    {2 * hour, tension}, {2 * hour + ramp, 0.0}};

double history_tension(const LoadHistory& h, double t) {
  if (t <= h.front().time) return h.front().tension;
  for (std::size_t k = 1; k < h.size(); ++k) {
    if (t < h[k].time) {
      const double f = (t - h[k - 1].time) / (h[k].time - h[k - 1].time);
      return h[k - 1].tension + f * (h[k].tension - h[k - 1].tension);
    }
  }
  return h.back().tension;
}

// The creep law's ODE: eps_v' = lambda (tau_v - eps_v), lambda_load below the
// target, lambda_unload above; eps_p' = lambda_load (tau_p - eps_p) while below.
struct Strains {
  double v = 0.0, p = 0.0;
};

Strains rate_of(const CreepTestParameters& q, const Strains& s, double sigma) {
  const double saturation = std::max(sigma, 0.0) / q.creep_modulus;
  const double tau_v = (1 - q.alpha) * saturation, tau_p = q.alpha * saturation;
  const double lambda_v = s.v < tau_v ? q.lambda_load : q.lambda_unload;
  return {lambda_v * (tau_v - s.v), s.p < tau_p ? q.lambda_load * (tau_p - s.p) : 0.0};
}

// Runge-Kutta from t = 0 through the sorted `times`, steps of at most 0.02 s
// that end at every knot (the tension is smooth within each step).
std::vector<double> reference_strain(const LoadHistory& h, const CreepTestParameters& q,
                                     const std::vector<double>& times) {
  std::vector<double> stops;
  for (const LoadKnot& k : h)
    stops.push_back(k.time);
  std::vector<double> strain;
  Strains s;
  double now = 0.0;
  std::size_t knot = 0;
  const auto integrate_to = [&](double end) {
    while (now < end) {
      const double dt = std::min(0.02, end - now);
      const auto at = [&](double t, const Strains& x) {
        return rate_of(q, x, history_tension(h, t));
      };
      const Strains k1 = at(now, s);
      const Strains k2 = at(now + dt / 2, {s.v + dt / 2 * k1.v, s.p + dt / 2 * k1.p});
      const Strains k3 = at(now + dt / 2, {s.v + dt / 2 * k2.v, s.p + dt / 2 * k2.p});
      const Strains k4 = at(now + dt, {s.v + dt * k3.v, s.p + dt * k3.p});
      s.v += dt / 6 * (k1.v + 2 * k2.v + 2 * k3.v + k4.v);
      s.p += dt / 6 * (k1.p + 2 * k2.p + 2 * k3.p + k4.p);
      now += dt;
    }
    now = end;
  };
  for (double t : times) {
    for (; knot < stops.size() && stops[knot] <= t; ++knot)
      integrate_to(stops[knot]);
    integrate_to(t);
    const double sigma = history_tension(h, t);
    strain.push_back((1 + sigma / q.elastic_modulus) * (1 + s.v + s.p) - 1);
  }
  return strain;
}

// Log-spaced after each load change (start of every ramp), 1 ms to the next
// change, about 1% dropped.
std::vector<double> machine_times(const std::vector<double>& changes, double end, int per_phase,
                                  std::mt19937_64& generator) {
  std::vector<double> times;
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  for (std::size_t c = 0; c < changes.size(); ++c) {
    const double until = (c + 1 < changes.size() ? changes[c + 1] : end) - changes[c];
    const double low = std::log(1e-3), high = std::log(until);
    for (int i = 0; i < per_phase; ++i) {
      const double since = std::exp(low + (high - low) * i / (per_phase - 1));
      const double t = changes[c] + std::min(since, until * (1 - 1e-9));
      if (uniform(generator) >= 0.01) times.push_back(t);
    }
  }
  return times;
}

CreepTestData history_data(const LoadHistory& h, const std::vector<double>& changes, double end,
                           const CreepTestParameters& p, double noise, unsigned seed) {
  std::mt19937_64 generator(seed);
  std::normal_distribution<double> gaussian(0.0, noise);
  CreepTestData data;
  data.path = "log-sampled synthetic load history";
  data.history = h;
  data.test = {tension, ramp, ramp + hour};
  data.time = machine_times(changes, end, 6500 / int(changes.size()), generator);
  data.strain = reference_strain(h, p, data.time);
  for (double& e : data.strain)
    e += gaussian(generator);
  data.line.assign(data.time.size(), 0);
  return data;
}

void expect_fit_recovers(const CreepTestData& data, const TableSet& set, double noise) {
  const ThesisEstimate start = start_estimate(data);
  CreepFit fit;
  ASSERT_EQ(fit_creep_test(PETSC_COMM_WORLD, data, start.parameters, 0.95, &fit), 0);
  expect_recovers(fit, set, noise);
}

TEST(CreepLoadHistory, ExactSteppingMatchesRungeKutta) {
  // Times straddling every knot, on both protocols, for a slow and a fast set.
  std::vector<double> times;
  for (double t = 0.37; t < 3 * hour; t *= 1.05)
    times.push_back(t);
  for (const LoadHistory& h : {ramped_test, two_level_test}) {
    for (const TableSet& set : {table_5_1[0], table_5_1[9], table_5_1[5]}) {
      std::vector<double> model(times.size());
      evaluate_load_history(h, set.p, times.data(), times.size(), 0, model.data());
      const std::vector<double> reference = reference_strain(h, set.p, times);
      for (std::size_t i = 0; i < times.size(); ++i) {
        // Runge-Kutta's error here is below 1e-9 of the strain (~0.1).
        ASSERT_NEAR(model[i], reference[i], 1e-8) << set.name << " at t = " << times[i];
      }
    }
  }
}

TEST(CreepLoadHistory, JacobianMatchesDifferences) {
  std::vector<double> times;
  for (double t = 0.5; t < 3 * hour; t *= 1.3)
    times.push_back(t);
  const CreepTestParameters& p = table_5_1[2].p;
  const std::size_t n = times.size(), skip = 4; // a rank's block: samples from 4 on
  std::vector<double> strain(n - skip), jacobian(5 * (n - skip));
  evaluate_load_history(two_level_test, p, times.data(), n, skip, strain.data(), jacobian.data(),
                        n - skip);
  const CreepTestVector q = to_fit_variables(p);
  for (std::size_t j = 0; j < 5; ++j) {
    const double h = 1e-6;
    CreepTestVector plus = q, minus = q;
    plus[j] += h;
    minus[j] -= h;
    std::vector<double> up(n), down(n);
    evaluate_load_history(two_level_test, from_fit_variables(plus), times.data(), n, 0, up.data());
    evaluate_load_history(two_level_test, from_fit_variables(minus), times.data(), n, 0,
                          down.data());
    for (std::size_t i = skip; i < n; ++i) {
      const double difference = (up[i] - down[i]) / (2 * h);
      EXPECT_NEAR(jacobian[j * (n - skip) + i - skip], difference,
                  1e-6 * std::max(1e-3, std::abs(difference)))
          << "parameter " << j << " at t = " << times[i];
    }
  }
}

TEST(CreepLoadHistory, FitsARampedTestOfEveryTable51Set) {
  constexpr double noise = 2e-4;
  unsigned seed = 71;
  for (const TableSet& set : table_5_1) {
    const CreepTestData data =
        history_data(ramped_test, {0.0, ramp + hour}, 2 * ramp + 2 * hour, set.p, noise, seed++);
    expect_fit_recovers(data, set, noise);
  }
}

TEST(CreepLoadHistory, FitsATwoLevelTestOfEveryTable51Set) {
  constexpr double noise = 2e-4;
  unsigned seed = 91;
  for (const TableSet& set : table_5_1) {
    const CreepTestData data =
        history_data(two_level_test, {0.0, hour, 2 * hour}, 3 * hour, set.p, noise, seed++);
    expect_fit_recovers(data, set, noise);
  }
}

TEST(CreepLoadHistory, FitsARampedAndATwoLevelTestTogether) {
  // Two tests of one fabric, each from a virgin specimen, in one fit: the
  // samples of the second test restart at t = 0 and see only its own load.
  constexpr double noise = 2e-4;
  unsigned seed = 131;
  for (const TableSet& set : table_5_1) {
    const CreepTestData ramped =
        history_data(ramped_test, {0.0, ramp + hour}, 2 * ramp + 2 * hour, set.p, noise, seed++);
    const CreepTestData two_level =
        history_data(two_level_test, {0.0, hour, 2 * hour}, 3 * hour, set.p, noise, seed++);
    const CreepTestData both = combine_tests({ramped, two_level});
    ASSERT_EQ(both.segments.size(), 2u);
    ASSERT_EQ(both.time.size(), ramped.time.size() + two_level.time.size());
    expect_fit_recovers(both, set, noise);
  }
}

TEST(CreepLoadHistory, IntervalsOfRampedFitsCoverTheGeneratingValues) {
  // 200 noisy replicates of the ramped test of one set: the 95% intervals
  // from the Jacobian must cover each generating value 92-98% of the time on
  // average over the five parameters (binomial spread ~1.5% per parameter).
  constexpr double noise = 2e-4;
  constexpr int replicates = 200;
  for (const TableSet& set : {table_5_1[2], table_5_1[9]}) {
    const auto truth = values_of(set.p);
    std::array<int, 5> covered{};
    // One sampling, the Runge-Kutta curve computed once; fresh noise each time.
    const CreepTestData exact =
        history_data(ramped_test, {0.0, ramp + hour}, 2 * ramp + 2 * hour, set.p, 0.0, 500);
    std::mt19937_64 generator(501);
    std::normal_distribution<double> gaussian(0.0, noise);
    for (int r = 0; r < replicates; ++r) {
      CreepTestData data = exact;
      for (double& e : data.strain)
        e += gaussian(generator);
      CreepFit fit;
      ASSERT_EQ(fit_creep_test(PETSC_COMM_WORLD, data, start_estimate(data).parameters, 0.95, &fit),
                0);
      ASSERT_TRUE(fit.converged) << set.name << " replicate " << r;
      for (std::size_t j = 0; j < 5; ++j) {
        const ParameterEstimate& e = fit.estimates[j];
        if (e.ci_low <= truth[j] && truth[j] <= e.ci_high) ++covered[j];
      }
    }
    double mean = 0.0;
    for (std::size_t j = 0; j < 5; ++j) {
      const double fraction = double(covered[j]) / replicates;
      mean += fraction / 5;
      EXPECT_GT(fraction, 0.88) << set.name << " " << creep_test_parameter_names()[j];
    }
    EXPECT_GE(mean, 0.92) << set.name;
    EXPECT_LE(mean, 0.98) << set.name;
  }
}

TEST(CreepLoadHistory, TheFitOfARampedTestPredictsATwoLevelTest) {
  // sartor validate's core: the parameters fitted to one protocol predict the
  // other within the noise, and about 95% of the samples fall inside the 95%
  // prediction interval (band and noise).
  constexpr double noise = 2e-4;
  unsigned seed = 171;
  for (const TableSet& set : {table_5_1[0], table_5_1[5], table_5_1[6]}) {
    const CreepTestData ramped =
        history_data(ramped_test, {0.0, ramp + hour}, 2 * ramp + 2 * hour, set.p, noise, seed++);
    const CreepTestData two_level =
        history_data(two_level_test, {0.0, hour, 2 * hour}, 3 * hour, set.p, noise, seed++);
    CreepFit fit;
    ASSERT_EQ(
        fit_creep_test(PETSC_COMM_WORLD, ramped, start_estimate(ramped).parameters, 0.95, &fit), 0);
    ASSERT_TRUE(fit.converged) << set.name;
    const CreepPrediction prediction = predict_creep_test(two_level, fit);
    EXPECT_NEAR(prediction.rmse / noise, 1.0, 0.05) << set.name;
    // ~6,400 samples: the fraction scatters by ~0.3%.
    EXPECT_NEAR(prediction.within_prediction_interval, 0.95, 0.02) << set.name;
    // The band is the parameters' share: far inside the noise on such data.
    EXPECT_GT(prediction.band_rms, 0.0) << set.name;
    EXPECT_LT(prediction.band_rms, 0.5 * noise) << set.name;
  }
}

TEST(CreepLoadHistory, PredictionBandsCoverTheTrueCurve) {
  // The delta-method band of a prediction is honest: over 200 fits of noisy
  // ramped tests, the 95% band of the predicted two-level curve contains the
  // true (noise-free) curve 92-98% of the time, averaged over its samples.
  constexpr double noise = 2e-4;
  constexpr int replicates = 200;
  const TableSet& set = table_5_1[3];
  const CreepTestData exact_ramped =
      history_data(ramped_test, {0.0, ramp + hour}, 2 * ramp + 2 * hour, set.p, 0.0, 600);
  const CreepTestData true_two_level =
      history_data(two_level_test, {0.0, hour, 2 * hour}, 3 * hour, set.p, 0.0, 601);
  std::mt19937_64 generator(602);
  std::normal_distribution<double> gaussian(0.0, noise);
  double covered = 0.0;
  for (int r = 0; r < replicates; ++r) {
    CreepTestData data = exact_ramped;
    for (double& e : data.strain)
      e += gaussian(generator);
    CreepFit fit;
    ASSERT_EQ(fit_creep_test(PETSC_COMM_WORLD, data, start_estimate(data).parameters, 0.95, &fit),
              0);
    ASSERT_TRUE(fit.converged) << "replicate " << r;
    const CreepPrediction prediction = predict_creep_test(true_two_level, fit);
    long inside = 0;
    for (std::size_t i = 0; i < prediction.error.size(); ++i)
      inside += std::abs(prediction.error[i]) <= prediction.band[i];
    covered += double(inside) / double(prediction.error.size()) / replicates;
  }
  EXPECT_GE(covered, 0.92);
  EXPECT_LE(covered, 0.98);
}

TEST(CreepLoadHistory, ReadsTheForceColumnOfARampedTestAsItsHistory) {
  // The file a tensile tester writes: force in N on an 8 cm strip, ramped;
  // the reader must take the column as the load history, not refuse it.
  const TableSet& set = table_5_1[4];
  const CreepTestData generated =
      history_data(ramped_test, {0.0, ramp + hour}, 2 * ramp + 2 * hour, set.p, 2e-4, 5);
  const std::string path = std::string(P_tmpdir) + "/sartor_ramped_test.csv";
  {
    std::ofstream out(path);
    out.precision(17);
    out << "Time (s),Force (N),Strain\n";
    for (std::size_t i = 0; i < generated.time.size(); ++i) {
      out << generated.time[i] << ',' << history_tension(ramped_test, generated.time[i]) * 0.08
          << ',' << generated.strain[i] << '\n';
    }
  }
  CreepTestDescription given;
  given.width = 0.08;
  const CreepTestData data = read_creep_test_data(path, given);
  std::remove(path.c_str());
  ASSERT_EQ(data.history.size(), generated.time.size());
  EXPECT_NEAR(data.test.tension, tension, 1e-6 * tension);
  EXPECT_NEAR(data.test.load_time, 0.5 * ramp, 0.1);
  EXPECT_NEAR(data.test.unload_time, hour + 1.5 * ramp, 0.1);
  expect_fit_recovers(data, set, 2e-4);
}

} // namespace
} // namespace sartor
