// Benchmarks of the creep law, the strip simulation and the creep fit at the
// thesis' size (86,400 samples: 2 h at 12 Hz). They measure; they never fail.
// Run: ./dev bench  (or build/tests/bench/sartor-bench --benchmark_filter=Fit)

#include "material/creep_law.hpp"
#include "material/creep_recovery_model.hpp"
#include "material/strip_creep.hpp"
#include "solvers/creep_fit.hpp"

#include <benchmark/benchmark.h>
#include <petscsys.h>

#include <random>

namespace sartor {
namespace {

constexpr std::size_t thesis_samples = 86400;
const CreepTestParameters cotton_twill_warp{65200, 32600, 0.897, 0.0886, 0.002};
const CreepTest thesis_test{196.133 / 0.08, 0.0, 3600.0};

CreepTestData synthetic_measurement(std::size_t samples) {
  CreepTestData data;
  data.path = "benchmark";
  data.test = thesis_test;
  std::mt19937_64 generator(1);
  std::normal_distribution<double> noise(0.0, 2e-4);
  for (std::size_t i = 0; i < samples; ++i)
    data.time.push_back(7200.0 * double(i) / double(samples));
  data.strain.resize(samples);
  evaluate_creep_test(data.test, cotton_twill_warp, data.time.data(), samples, data.strain.data());
  for (double& s : data.strain)
    s += noise(generator);
  data.line.assign(samples, 0);
  return data;
}

void BM_CreepLawStep(benchmark::State& state) {
  const CreepParameters p{32600, 0.897, 0.0886, 0.002};
  CreepState s;
  double tension = 2451.0;
  for (auto _ : state) {
    s = advance(p, s, tension, tension, 0.1);
    tension = tension > 1000.0 ? 0.0 : 2451.0; // alternate loading and recovery
    benchmark::DoNotOptimize(s);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_CreepLawStep);

void BM_CreepSimulation(benchmark::State& state) {
  const DirectionalMaterial material{{32600, 0.897, 0.0886, 0.002},
                                     TensionCurve::linear(65200, "benchmark")};
  const auto history = TensionHistory::creep_recovery(thesis_test.tension, 3600.0, 3600.0);
  const auto times = uniform_sample_times(history, 7200.0 / double(state.range(0)));
  for (auto _ : state)
    benchmark::DoNotOptimize(simulate_strip(material, history, times));
  state.SetItemsProcessed(state.iterations() * state.range(0));
}
BENCHMARK(BM_CreepSimulation)->Arg(thesis_samples)->Unit(benchmark::kMillisecond);

void BM_FitThesisEstimate(benchmark::State& state) {
  const CreepTestData data = synthetic_measurement(std::size_t(state.range(0)));
  for (auto _ : state)
    benchmark::DoNotOptimize(thesis_estimate(data));
  state.SetItemsProcessed(state.iterations() * state.range(0));
}
BENCHMARK(BM_FitThesisEstimate)->Arg(thesis_samples)->Unit(benchmark::kMillisecond);

// What `sartor fit` does after reading the file: the thesis estimate, then the
// joint Levenberg-Marquardt refinement, its certificate and the uncertainties.
void BM_Fit(benchmark::State& state) {
  const CreepTestData data = synthetic_measurement(std::size_t(state.range(0)));
  long iterations = 0;
  for (auto _ : state) {
    const ThesisEstimate start = thesis_estimate(data);
    CreepFit fit;
    if (fit_creep_test(PETSC_COMM_SELF, data, start.parameters, 0.95, &fit) != 0 ||
        !fit.converged) {
      state.SkipWithError("fit failed");
      break;
    }
    iterations = fit.iterations;
  }
  state.counters["lm_iterations"] = double(iterations);
  state.SetItemsProcessed(state.iterations() * state.range(0));
}
BENCHMARK(BM_Fit)->Arg(7200)->Arg(thesis_samples)->Unit(benchmark::kMillisecond);

} // namespace
} // namespace sartor

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (PetscInitialize(&argc, &argv, nullptr, nullptr) != 0) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return PetscFinalize() == 0 ? 0 : 1;
}
