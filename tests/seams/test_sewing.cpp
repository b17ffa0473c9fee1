// Sewing in the assembled problem: two half-cylinder panels that start
// 15 cm apart are pulled together by their seams (statics with continuation),
// hanging from the back panel's top edge under gravity. The seams must close,
// the sewn ring must have the panels' length, the Jacobian must include the
// seam couplings, and the result must not depend on the number of ranks.

#include "fem/cloth_problem.hpp"
#include "mesh/merge.hpp"
#include "mesh/panels.hpp"
#include "solvers/statics.hpp"
#include "tests/fem/jacobian_check.hpp"

#include <gtest/gtest.h>

namespace sartor {
namespace {

const double width = 0.4, height = 0.3, gap = 0.15;
const double modulus = 30000.0; // N/m

ClothMaterial fabric(element::BendingModel model) {
  ClothMaterial m(
      {TensionCurve::linear(modulus, "test"), TensionCurve::linear(modulus, "test"), 3000.0, 0.0});
  m.bending_model = model;
  m.bending_stiffness = 1e-4;
  m.areal_density = 0.2;
  return m;
}

// The back panel's top row.
std::vector<int> top_of_back_panel(const mesh::PanelMesh& tube) {
  std::vector<int> pins;
  for (int v = 0; v < tube.panel_start[1]; ++v) {
    if (tube.mesh.positions[std::size_t(v)].z() == height) pins.push_back(v);
  }
  return pins;
}

struct Sewn {
  StaticReport report;
  std::vector<Eigen::Vector3d> positions; // every rank
  double gap = 0.0;
  double seam_energy = 0.0;
  PetscInt cross_rank_springs = 0;
};

Sewn sew(MPI_Comm comm, const TriangleMesh& mesh, const std::vector<SeamSpring>& springs,
         const std::vector<int>& pins, element::BendingModel model = element::BendingModel::patch) {
  ClothProblem problem(comm, mesh, fabric(model), pins);
  problem.loads.gravity = {0.0, 0.0, -9.80665};
  if (!springs.empty()) problem.set_seams(springs);
  Sewn sewn;
  if (problem.seam_coupling())
    sewn.cross_rank_springs = problem.seam_coupling()->cross_rank_springs();
  Vec x = nullptr;
  EXPECT_EQ(problem.create_solution(&x), 0);
  EXPECT_EQ(solve_static(problem, x, {}, &sewn.report), 0);
  EXPECT_EQ(problem.seam_gap(x, &sewn.gap), 0);
  ClothEnergy energy;
  EXPECT_EQ(problem.energy(x, &energy), 0);
  sewn.seam_energy = energy.seam;
  EXPECT_EQ(problem.gather_positions(x, &sewn.positions), 0);
  std::size_t count = sewn.positions.size();
  MPI_Bcast(&count, 1, MPI_UNSIGNED_LONG, 0, comm);
  sewn.positions.resize(count);
  MPI_Bcast(sewn.positions.data(), int(3 * count), MPI_DOUBLE, 0, comm);
  VecDestroy(&x);
  return sewn;
}

// Length of the closed ring through the mid-height rows of both panels
// (each row's polyline plus the two seam crossings between them), m.
double mid_height_ring(const mesh::PanelMesh& tube, const std::vector<Eigen::Vector3d>& x, int nx,
                       int ny, int nx_front, int ny_front) {
  const auto row = [](int offset, int columns, int rows) {
    std::vector<int> line;
    for (int i = 0; i <= columns; ++i)
      line.push_back(offset + (rows / 2) * (columns + 1) + i);
    return line;
  };
  std::vector<int> ring = row(0, nx, ny);
  const std::vector<int> front = row(tube.panel_start[1], nx_front, ny_front);
  ring.insert(ring.end(), front.begin(), front.end());
  double length = 0.0;
  for (std::size_t i = 0; i < ring.size(); ++i) {
    length += (x[std::size_t(ring[(i + 1) % ring.size()])] - x[std::size_t(ring[i])]).norm();
  }
  return length;
}

std::vector<SeamSpring> springs_of(const mesh::PanelMesh& tube) {
  SeamStiffness stiffness;
  stiffness.modulus = modulus;
  return seam_springs(tube.mesh, tube.seams, stiffness);
}

// Seams of zero rest length close to the penalty's residual gap, about
// strain * h / penalty (here well below a micrometre); a ring of chords
// whose rest lengths add up to 2 width is 2 width long up to the membrane
// strain, which self-weight keeps near rho g height / E = 2e-5.
void expect_sewn_tube(const mesh::PanelMesh& tube, const Sewn& sewn, int nx, int ny, int nx_front,
                      int ny_front) {
  ASSERT_TRUE(sewn.report.converged) << sewn.report.reason;
  EXPECT_LT(sewn.gap, 1e-5);
  const double ring = mid_height_ring(tube, sewn.positions, nx, ny, nx_front, ny_front);
  EXPECT_NEAR(ring / (2 * width), 1.0, 1e-3);
  std::printf("sewn tube %dx%d + %dx%d: %d Newton iterations, %d pseudo-time steps, "
              "gap %.3e m, ring %.6f m (2w = %.6f m), %.2f s\n",
              nx, ny, nx_front, ny_front, int(sewn.report.newton_iterations),
              int(sewn.report.pseudo_steps), sewn.gap, ring, 2 * width, sewn.report.solve_seconds);
}

TEST(Sewing, JacobianIncludesTheSeamCouplings) {
  const mesh::PanelMesh tube = mesh::tube_panels(width, height, 4, 3, 5, 2, gap);
  ClothProblem problem(PETSC_COMM_WORLD, tube.mesh, fabric(element::BendingModel::patch),
                       top_of_back_panel(tube));
  problem.set_seams(springs_of(tube));
  Vec x = nullptr, v = nullptr;
  ASSERT_EQ(problem.create_solution(&x), 0);
  VecDuplicate(x, &v);
  PetscRandom generator = nullptr;
  PetscRandomCreate(PETSC_COMM_WORLD, &generator);
  VecSetRandom(v, generator);
  PetscRandomDestroy(&generator);
  // Through create_jacobian: a seam coupling missing from the preallocation fails.
  const double error = testing::directional_jacobian_error(problem, x, v, 1e-6, NORM_2);
  EXPECT_GE(error, 0.0) << "assembly failed";
  EXPECT_LT(error, 1e-6);
  VecDestroy(&x);
  VecDestroy(&v);
}

TEST(Sewing, TubeClosesFromAFarStartWithVertexToVertexSeams) {
  const mesh::PanelMesh tube = mesh::tube_panels(width, height, 10, 6, 10, 6, gap);
  const Sewn sewn = sew(PETSC_COMM_WORLD, tube.mesh, springs_of(tube), top_of_back_panel(tube));
  expect_sewn_tube(tube, sewn, 10, 6, 10, 6);
  EXPECT_GT(sewn.seam_energy, 0.0);
}

TEST(Sewing, TubeClosesWithVertexToEdgeSeams) {
  const mesh::PanelMesh tube = mesh::tube_panels(width, height, 10, 6, 12, 4, gap);
  const Sewn sewn = sew(PETSC_COMM_WORLD, tube.mesh, springs_of(tube), top_of_back_panel(tube));
  expect_sewn_tube(tube, sewn, 10, 6, 12, 4);
}

TEST(Sewing, MergedTubeStaysWhereTheSeamsClosedIt) {
  const mesh::PanelMesh tube = mesh::tube_panels(width, height, 10, 6, 10, 6, gap);
  const std::vector<int> pins = top_of_back_panel(tube);
  const Sewn sewn = sew(PETSC_COMM_WORLD, tube.mesh, springs_of(tube), pins);
  ASSERT_TRUE(sewn.report.converged);
  TriangleMesh closed = tube.mesh;
  closed.positions = sewn.positions;
  const MergedMesh merged = merge_vertices(closed, matched_vertex_pairs(closed, tube.seams));
  ASSERT_EQ(merged.mesh.vertex_count(), tube.mesh.vertex_count() - 2 * 7);
  std::vector<int> merged_pins;
  for (int v : pins)
    merged_pins.push_back(merged.vertex_map[std::size_t(v)]);
  const Sewn resolved = sew(PETSC_COMM_WORLD, merged.mesh, {}, merged_pins);
  ASSERT_TRUE(resolved.report.converged) << resolved.report.reason;
  // The seam's residual gap and the bending now carried across the seam
  // (the sewn seam is a hinge) move the tube a little: it stays within 1 % of
  // its height of the sewn state. How much depends on the kink the sewn seam
  // settled into, which the continuation path decides: 0.09 mm with the line
  // search on the potential to the end, 1.8 mm with the Newton hand-over.
  double moved = 0.0;
  for (std::size_t v = 0; v < tube.mesh.vertex_count(); ++v) {
    moved = std::max(
        moved, (resolved.positions[std::size_t(merged.vertex_map[v])] - sewn.positions[v]).norm());
  }
  EXPECT_LT(moved, 0.01 * height);
  std::printf("merged tube: %zu -> %zu vertices, %d Newton iterations, moved %.3e m\n",
              tube.mesh.vertex_count(), merged.mesh.vertex_count(),
              int(resolved.report.newton_iterations), moved);
}

TEST(SewingMpi, SameSewnTubeOnAnyNumberOfRanks) {
  // Solved on all ranks together and on each rank alone. With several ranks
  // the partitioner puts the panels' seam lines on different ranks. From
  // panels 2 cm apart: from 15 cm the sewing path folds the panels, and
  // which of the tube's equilibria it ends in turned on round-off (2 cm
  // apart on 1 and 2 ranks under OPENBLAS_CORETYPE=Prescott, 1.5 cm on 4
  // ranks once in three runs), which this test of the parallel assembly
  // must not see.
  const double near_gap = 0.02;
  const mesh::PanelMesh tube = mesh::tube_panels(width, height, 10, 6, 12, 4, near_gap);
  const auto springs = springs_of(tube);
  const auto pins = top_of_back_panel(tube);
  // With the discrete shell. With the patch model the far-start sewing ends
  // in different equilibria of the tube on 1 and 2 ranks (measured 4.3 cm
  // apart, both converged): the path through the folding panels there turns
  // on round-off, which this test of the parallel assembly must not see.
  const auto hinges = element::BendingModel::discrete_shell;
  const Sewn together = sew(PETSC_COMM_WORLD, tube.mesh, springs, pins, hinges);
  const Sewn alone = sew(PETSC_COMM_SELF, tube.mesh, springs, pins, hinges);
  ASSERT_TRUE(together.report.converged && alone.report.converged);
  PetscMPIInt size = 1;
  MPI_Comm_size(PETSC_COMM_WORLD, &size);
  if (size > 1) {
    EXPECT_GT(together.cross_rank_springs, 0);
  }
  double largest = 0.0, scale = 0.0;
  for (std::size_t v = 0; v < tube.mesh.vertex_count(); ++v) {
    largest = std::max(largest, (together.positions[v] - alone.positions[v]).norm());
    scale = std::max(scale, (alone.positions[v] - tube.mesh.positions[v]).norm());
  }
  // Within the solve's tolerance, not at round-off: a solve that stops one
  // Newton iteration earlier on some ranks ends 1e-7 of the sag away (2 ranks
  // here: 1.3e-7; bit-identical paths give 4e-14).
  EXPECT_LT(largest, 1e-6 * scale);
  if (PetscGlobalRank != 0) return; // the report line once
  std::printf("%d rank(s): %ld seam springs cross ranks, largest difference %.3e m "
              "(relative %.3e)\n",
              int(size), long(together.cross_rank_springs), largest, largest / scale);
}

} // namespace
} // namespace sartor
