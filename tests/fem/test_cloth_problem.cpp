// The assembled cloth problem: exactness on a patch test, a consistent
// Jacobian, equilibrium of reactions, and results independent of the number
// of MPI ranks.

#include "common/error.hpp"
#include "fem/cloth_problem.hpp"
#include "mesh/generators.hpp"
#include "solvers/statics.hpp"
#include "tests/fem/jacobian_check.hpp"

#include <gtest/gtest.h>

#include <random>

namespace sartor {
namespace {

ClothMaterial isotropic_stvk(double modulus, double poisson) {
  ClothMaterial m({TensionCurve::linear(modulus, "test"), TensionCurve::linear(modulus, "test"),
                   0.5 * modulus * (1.0 - poisson), poisson});
  m.membrane_model = element::MembraneModel::saint_venant_kirchhoff;
  return m;
}

ClothMaterial cotton(double bending) {
  ClothMaterial m(
      {TensionCurve::linear(65200, "test"), TensionCurve::linear(28200, "test"), 4288.0, 0.0});
  m.bending_stiffness = bending;
  m.areal_density = 0.2;
  return m;
}

std::vector<Eigen::Vector3d> solve(MPI_Comm comm, const TriangleMesh& mesh,
                                   const ClothMaterial& material, const std::vector<int>& pins,
                                   const std::vector<Eigen::Vector3d>& pin_places,
                                   const ClothLoads& loads, int steps, StaticReport* report) {
  ClothProblem problem(comm, mesh, material, pins);
  problem.loads = loads;
  for (std::size_t i = 0; i < pin_places.size(); ++i)
    problem.set_pin_position(i, pin_places[i]);
  Vec x = nullptr;
  EXPECT_EQ(problem.create_solution(&x), 0);
  StaticOptions options;
  options.load_steps = steps;
  EXPECT_EQ(solve_static(problem, x, options, report), 0);
  std::vector<Eigen::Vector3d> positions;
  EXPECT_EQ(problem.positions_everywhere(x, &positions), 0);
  VecDestroy(&x);
  return positions;
}

TEST(ClothPatchTest, UniformStretchIsExactOnAnUnstructuredMesh) {
  // Boundary vertices placed on a uniform biaxial stretch with shear; the
  // interior must follow it exactly, for both membrane models.
  const TriangleMesh mesh = mesh::rectangle(1.0, 0.8, 7, 6, mesh::RectanglePattern::perturbed);
  Eigen::Matrix3d stretch;
  stretch << 1.03, 0.01, 0.0, 0.0, 1.05, 0.0, 0.0, 0.0, 1.0;
  const std::vector<int> pins = boundary_vertices(mesh);
  std::vector<Eigen::Vector3d> places;
  for (int v : pins)
    places.push_back(stretch * mesh.positions[std::size_t(v)]);
  for (auto model :
       {element::MembraneModel::baraff_witkin, element::MembraneModel::saint_venant_kirchhoff}) {
    ClothMaterial material =
        isotropic_stvk(1000.0, model == element::MembraneModel::baraff_witkin ? 0.0 : 0.3);
    material.membrane_model = model;
    StaticReport report;
    const auto positions = solve(PETSC_COMM_WORLD, mesh, material, pins, places, {}, 1, &report);
    ASSERT_TRUE(report.converged) << report.reason;
    for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
      EXPECT_LT((positions[v] - stretch * mesh.positions[v]).norm(), 1e-10) << "vertex " << v;
    }
  }
}

TEST(ClothJacobian, MatchesFiniteDifferencesOfTheResidual) {
  // Random state of a small sheet with membrane, bending, gravity and a
  // follower pressure: J v against central differences of F.
  TriangleMesh mesh = mesh::rectangle(0.4, 0.3, 4, 3, mesh::RectanglePattern::perturbed);
  std::mt19937_64 random(3);
  std::uniform_real_distribution<double> jitter(-0.01, 0.01);
  for (auto& p : mesh.positions)
    p += Eigen::Vector3d(jitter(random), jitter(random), 2 * jitter(random));
  for (auto model : {element::BendingModel::discrete_shell, element::BendingModel::quadratic,
                     element::BendingModel::patch}) {
    ClothMaterial material = cotton(1e-3);
    material.bending_model = model;
    ClothProblem problem(PETSC_COMM_WORLD, mesh, material, {0});
    problem.loads.gravity = {0, 0, -9.81};
    problem.loads.pressure = 5.0;
    problem.nonelastic.assign(mesh.triangle_count(), {0.01, 0.02});
    Vec x = nullptr, v = nullptr;
    ASSERT_EQ(problem.create_solution(&x), 0);
    VecDuplicate(x, &v);
    PetscRandom generator = nullptr;
    PetscRandomCreate(PETSC_COMM_WORLD, &generator);
    VecSetRandom(v, generator);
    PetscRandomDestroy(&generator);
    const double error = testing::directional_jacobian_error(problem, x, v, 1e-6, NORM_2);
    EXPECT_GE(error, 0.0) << "assembly failed";
    EXPECT_LT(error, 1e-6) << "bending model " << model.index();
    VecDestroy(&x);
    VecDestroy(&v);
  }
}

TEST(ClothStatics, HangingSheetPinsCarryItsWeight) {
  TriangleMesh mesh = mesh::rectangle(1.0, 1.0, 8, 8);
  for (auto& p : mesh.positions)
    p = Eigen::Vector3d(p[0], 0.0, p[1]); // hang in the x-z plane
  std::vector<int> pins;
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
    const auto& p = mesh.positions[v];
    if (p[2] == 1.0 && (p[0] == 0.0 || p[0] == 1.0)) pins.push_back(int(v));
  }
  ASSERT_EQ(pins.size(), 2u);
  ClothProblem problem(PETSC_COMM_WORLD, mesh, cotton(1e-5), pins);
  problem.loads.gravity = {0, 0, -9.80665};
  Vec x = nullptr;
  ASSERT_EQ(problem.create_solution(&x), 0);
  StaticReport report;
  ASSERT_EQ(solve_static(problem, x, {}, &report), 0);
  ASSERT_TRUE(report.converged) << report.reason;
  Eigen::Vector3d reaction;
  ASSERT_EQ(problem.pin_reaction(x, &reaction), 0);
  const double weight = 0.2 * 1.0 * 9.80665;
  EXPECT_NEAR(reaction[2], weight, 1e-8 * weight);
  EXPECT_NEAR(reaction[0], 0.0, 1e-8 * weight);
  EXPECT_NEAR(reaction[1], 0.0, 1e-8 * weight);
  VecDestroy(&x);
}

TEST(ClothStaticsMpi, ResultIndependentOfTheNumberOfRanks) {
  // Solved on all ranks together and on each rank alone: same positions.
  TriangleMesh mesh = mesh::rectangle(1.0, 1.0, 12, 12);
  for (auto& p : mesh.positions)
    p = Eigen::Vector3d(p[0], 0.0, p[1]);
  std::vector<int> pins;
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
    const auto& p = mesh.positions[v];
    if (p[2] == 1.0 && (p[0] == 0.0 || p[0] == 1.0)) pins.push_back(int(v));
  }
  ClothLoads loads;
  loads.gravity = {0, 0, -9.80665};
  StaticReport together, alone;
  const auto parallel = solve(PETSC_COMM_WORLD, mesh, cotton(1e-5), pins, {}, loads, 1, &together);
  const auto serial = solve(PETSC_COMM_SELF, mesh, cotton(1e-5), pins, {}, loads, 1, &alone);
  ASSERT_TRUE(together.converged && alone.converged);
  double largest = 0.0, scale = 0.0;
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
    largest = std::max(largest, (parallel[v] - serial[v]).norm());
    scale = std::max(scale, (serial[v] - mesh.positions[v]).norm());
  }
  // Both solves stop at Newton's tolerance, each with its own factorisation.
  // The unknowns are positions of about 1 m, so 1e-8 of this 0.2 mm sag
  // (2e-12 m) is their round-off (4 ranks with SuperLU_DIST differed by
  // 2.6e-11 m); 1e-6 of the sag is still far below any real dependence on
  // the partition.
  EXPECT_LT(largest, 1e-6 * scale);
}

TEST(ClothMaterials, StripsInSeriesStretchInverselyToTheirModuli) {
  // A 1 m x 0.1 m strip, the half x < 0.5 of modulus k and the other of 3k,
  // stretched by 0.01 m between its pinned ends: one tension T through both
  // halves, T = delta / (0.5/k + 0.5/(3k)), and the joint at x = 0.5 moves by
  // 0.5 T / k.
  TriangleMesh mesh = mesh::rectangle(1.0, 0.1, 8, 1);
  const double k = 1000.0, delta = 0.01;
  ClothMaterial soft = isotropic_stvk(k, 0.0), stiff = isotropic_stvk(3.0 * k, 0.0);
  soft.membrane_model = stiff.membrane_model = element::MembraneModel::baraff_witkin;
  // Bending holds the flat strip out of plane before it is in tension; the
  // stretched state does not bend it.
  soft.bending_stiffness = 1e-4;
  stiff.bending_stiffness = 3e-4;
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    double centroid = 0.0;
    for (int v : mesh.triangles[t])
      centroid += mesh.positions[std::size_t(v)].x() / 3.0;
    mesh.material_ids.push_back(centroid < 0.5 ? 0 : 1);
  }
  std::vector<int> pins;
  std::vector<int> joint;
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
    const double x = mesh.positions[v].x();
    if (x == 0.0 || x == 1.0) pins.push_back(int(v));
    if (std::abs(x - 0.5) < 1e-12) joint.push_back(int(v));
  }
  ClothProblem problem(PETSC_COMM_WORLD, mesh, {soft, stiff}, pins);
  for (std::size_t i = 0; i < pins.size(); ++i) {
    const Eigen::Vector3d& place = mesh.positions[std::size_t(pins[i])];
    if (place.x() == 1.0) problem.set_pin_position(i, place + Eigen::Vector3d(delta, 0, 0));
  }
  Vec x = nullptr;
  ASSERT_EQ(problem.create_solution(&x), 0);
  StaticReport report;
  ASSERT_EQ(solve_static(problem, x, StaticOptions{}, &report), 0);
  ASSERT_TRUE(report.converged) << report.reason;
  const double tension = delta / (0.5 / k + 0.5 / (3.0 * k));
  std::vector<Eigen::Vector3d> positions;
  ASSERT_EQ(problem.gather_positions(x, &positions), 0);
  Eigen::Vector3d reaction;
  ASSERT_EQ(problem.pin_reaction(x, &reaction), 0);
  EXPECT_NEAR(reaction.x(), 0.0, 1e-9 * tension); // equal and opposite at the two ends
  if (!positions.empty()) {
    for (int v : joint) {
      EXPECT_NEAR(positions[std::size_t(v)].x() - 0.5, 0.5 * tension / k, 1e-10) << "vertex " << v;
    }
  }
  VecDestroy(&x);
}

TEST(ClothMaterials, MaterialIdsOutOfRangeAreRejected) {
  TriangleMesh mesh = mesh::rectangle(1.0, 1.0, 2, 2);
  mesh.material_ids.assign(mesh.triangle_count(), 0);
  mesh.material_ids[3] = 2;
  try {
    ClothProblem problem(PETSC_COMM_WORLD, mesh, {cotton(0.0), cotton(0.0)}, {});
    FAIL() << "no error";
  } catch (const InputError& error) {
    EXPECT_STREQ(error.what(),
                 "cloth mesh: triangle 3 has material id 2, but there are 2 material(s)");
  }
}

} // namespace
} // namespace sartor
