// Benchmarks of the PSD projections of element Hessians: the full
// eigenproblem of membrane triangles and hinges, and of the bending patch
// against its projection in the Hessian's 14-dimensional range.
// They measure; they never fail.
// Run: build/tests/bench/sartor-bench --benchmark_filter=Project

#include "element/element.hpp"
#include "element/patch_bending.hpp"

#include <benchmark/benchmark.h>

#include <random>

namespace sartor::element {
namespace {

// An indefinite Hessian of a translation-invariant energy over `Nodes`
// points: D^T A D, D the differences to the first point, A symmetric.
template <int Nodes>
Eigen::Matrix<double, 3 * Nodes, 3 * Nodes> translation_free_hessian() {
  constexpr int n = 3 * Nodes, m = 3 * (Nodes - 1);
  std::mt19937 random(7);
  std::normal_distribution<double> normal;
  Eigen::Matrix<double, m, m> a;
  for (int i = 0; i < m; ++i) {
    for (int j = 0; j < m; ++j)
      a(i, j) = normal(random);
  }
  Eigen::Matrix<double, m, n> differences = Eigen::Matrix<double, m, n>::Zero();
  for (int i = 1; i < Nodes; ++i) {
    differences.template block<3, 3>(3 * (i - 1), 0) = -Eigen::Matrix3d::Identity();
    differences.template block<3, 3>(3 * (i - 1), 3 * i) = Eigen::Matrix3d::Identity();
  }
  return differences.transpose() * (a + a.transpose()) * differences;
}

template <int Nodes>
void BM_ProjectFull(benchmark::State& state) {
  const auto hessian = translation_free_hessian<Nodes>();
  for (auto _ : state) {
    auto projected = hessian;
    project_to_psd<3 * Nodes>(projected);
    benchmark::DoNotOptimize(projected);
  }
}
BENCHMARK_TEMPLATE(BM_ProjectFull, 3);
BENCHMARK_TEMPLATE(BM_ProjectFull, 4);

// A bent patch of an irregular mesh (a triangle, the nodes across its edges).
struct BentPatch {
  PatchRest rest;
  Vector36 x;
  Eigen::Matrix<double, 36, 36> hessian;
};

BentPatch bent_patch() {
  using Eigen::Vector2d;
  const std::array<Vector2d, 6> uv = {Vector2d(0.0, 0.0), Vector2d(1.0, 0.1),  Vector2d(0.3, 0.9),
                                      Vector2d(1.1, 1.0), Vector2d(-0.6, 0.4), Vector2d(0.6, -0.8)};
  const BendingRigidity rigidity{2.0, 0.7, 0.3, 0.4};
  const auto own = midedge_slopes<double>({uv[0], uv[1], uv[2]}, {uv[3], uv[4], uv[5]},
                                          {true, true, true}, rigidity);
  std::array<Eigen::Matrix<double, 1, 12>, 3> slopes;
  for (std::size_t k = 0; k < 3; ++k) {
    slopes[k].setZero();
    slopes[k].head<6>() = own[k];
  }
  BentPatch patch;
  patch.rest = patch_rest({uv[0], uv[1], uv[2]}, slopes, rigidity, Eigen::Vector3d(-1.5, 0.8, 0.5));
  for (int i = 0; i < 12; ++i) {
    const Vector2d p = uv[std::size_t(i % 6)] + Vector2d(0.1 * (i / 6), 0.0);
    patch.x.segment<3>(3 * i) = Eigen::Vector3d(1.2 * p.x(), p.y(), 1.5 * p.x() * p.x());
  }
  patch.hessian = patch_bending(patch.rest, patch.x, Want::hessian).hessian;
  return patch;
}

void BM_ProjectPatchFull(benchmark::State& state) {
  const BentPatch patch = bent_patch();
  for (auto _ : state) {
    auto projected = patch.hessian;
    project_to_psd<36>(projected);
    benchmark::DoNotOptimize(projected);
  }
}
BENCHMARK(BM_ProjectPatchFull);

void BM_ProjectPatchInItsRange(benchmark::State& state) {
  const BentPatch patch = bent_patch();
  for (auto _ : state) {
    auto projected = patch.hessian;
    project_patch_hessian_to_psd(patch.rest, patch.x, projected);
    benchmark::DoNotOptimize(projected);
  }
}
BENCHMARK(BM_ProjectPatchInItsRange);

} // namespace
} // namespace sartor::element
