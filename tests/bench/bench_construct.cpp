// Benchmarks of TAGCON garment construction (thesis ch. 3) on the sample
// patterns: placement and seam finding (garment::construct), and the panel
// meshing that follows, per garment, around the built-in mannequin (built
// once, outside the timing). They measure; they never fail.
// Run: ./dev bench --benchmark_filter=Construct

#include "contact/mannequin.hpp"
#include "contact/mesh_shape.hpp"
#include "garment/garment_mesh.hpp"
#include "garment/pattern.hpp"
#include "garment/tagcon.hpp"

#include <benchmark/benchmark.h>

#include <memory>
#include <string>

namespace sartor {
namespace {

const char* const garments[] = {"skirt", "tshirt", "pants", "dress", "blouse", "hooded_top"};

// The mannequin and its distance queries, as `sartor construct` sets them up.
struct Body {
  const Mannequin& mannequin = default_mannequin();
  std::unique_ptr<contact::Shape> shape = contact::make_mannequin_shape();
  garment::BodyDistance distance = [this](const Eigen::Vector3d& p, Eigen::Vector3d* gradient) {
    const contact::SurfaceQuery q = shape->query(p);
    if (gradient) *gradient = q.normal;
    return q.distance;
  };
};

const Body& body() {
  static const Body built;
  return built;
}

garment::Pattern sample(long index) {
  return garment::read_pattern(std::string(SARTOR_PATTERN_SAMPLES_DIR) + "/" + garments[index] +
                               ".json");
}

// Placement and seam finding; counters split the time between the two.
void BM_Construct(benchmark::State& state) {
  const garment::Pattern pattern = sample(state.range(0));
  state.SetLabel(garments[state.range(0)]);
  double placement = 0.0, seams = 0.0;
  std::size_t seam_count = 0;
  for (auto _ : state) {
    const garment::Construction construction =
        garment::construct(pattern, body().mannequin, body().distance);
    placement += construction.placement_seconds;
    seams += construction.seam_seconds;
    seam_count = construction.seams.size();
  }
  const double runs = double(state.iterations());
  state.counters["placement_ms"] = 1e3 * placement / runs;
  state.counters["seams_ms"] = 1e3 * seams / runs;
  state.counters["seams"] = double(seam_count);
}
BENCHMARK(BM_Construct)->DenseRange(0, 5)->Unit(benchmark::kMillisecond);

// Meshing the placed panels (CGAL) at `sartor construct`'s default 2 cm edges.
void BM_ConstructMesh(benchmark::State& state) {
  const garment::Pattern pattern = sample(state.range(0));
  state.SetLabel(garments[state.range(0)]);
  const garment::Construction construction =
      garment::construct(pattern, body().mannequin, body().distance);
  std::size_t triangles = 0;
  for (auto _ : state) {
    const garment::GarmentMesh mesh = garment::build_garment_mesh(construction, {});
    triangles = mesh.mesh.triangle_count();
  }
  state.counters["triangles"] = double(triangles);
}
BENCHMARK(BM_ConstructMesh)->DenseRange(0, 5)->Unit(benchmark::kMillisecond);

} // namespace
} // namespace sartor
