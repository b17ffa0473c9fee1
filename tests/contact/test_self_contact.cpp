// Cloth self-contact in the assembled problem: pairs found against brute
// force, a consistent Jacobian with pairs in contact (through the structure
// create_jacobian builds), and a sheet hanging from one edge that comes to
// lie on a second sheet instead of falling through it, carried by the
// contact as statics require, the same on any number of ranks.

#include "contact/cloth_pairs.hpp"
#include "element/point_triangle.hpp"
#include "fem/cloth_problem.hpp"
#include "mesh/generators.hpp"
#include "solvers/incremental_system.hpp"
#include "solvers/statics.hpp"
#include "tests/fem/jacobian_check.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <random>

namespace sartor {
namespace {

using Eigen::Vector3d;

constexpr double density = 0.2; // kg/m^2
constexpr double gravity = 9.80665;
constexpr double offset = 2e-3;

ClothMaterial fabric() {
  ClothMaterial m(
      {TensionCurve::linear(2000, "test"), TensionCurve::linear(1500, "test"), 150.0, 0.0});
  m.bending_model = element::BendingModel::discrete_shell;
  m.bending_stiffness = 1e-5;
  m.areal_density = density;
  return m;
}

// The lower sheet (0.4 m square, 8 x 8 cells, at z = 0) and, above it at
// `height`, the upper one (0.3 m, 6 x 6), shifted so that no vertex of one
// lies over a vertex or an edge of the other. Upper vertices come after
// the lower ones.
struct TwoSheets {
  TriangleMesh mesh;
  std::size_t lower_vertices = 0;
};

TwoSheets two_sheets(double height) {
  TwoSheets sheets;
  TriangleMesh lower = mesh::rectangle(0.4, 0.4, 8, 8);
  const TriangleMesh upper = mesh::rectangle(0.3, 0.3, 6, 6);
  sheets.lower_vertices = lower.vertex_count();
  for (const auto& p : upper.positions)
    lower.positions.push_back(p + Vector3d(0.0513, 0.0471, height));
  for (std::size_t t = 0; t < upper.triangle_count(); ++t) {
    auto triangle = upper.triangles[t];
    for (int& v : triangle)
      v += int(sheets.lower_vertices);
    lower.triangles.push_back(triangle);
    lower.material_uv.push_back(upper.material_uv[t]);
  }
  sheets.mesh = std::move(lower);
  return sheets;
}

std::function<double(std::size_t, int)> rest_length(const TriangleMesh& mesh) {
  return [&mesh](std::size_t t, int i) {
    return (mesh.material_uv[t][std::size_t((i + 1) % 3)] - mesh.material_uv[t][std::size_t(i)])
        .norm();
  };
}

TEST(ClothPairs, FindEveryPairThatBruteForceFinds) {
  TwoSheets sheets = two_sheets(0.004);
  std::mt19937 random(3);
  std::uniform_real_distribution<double> jitter(-0.003, 0.003);
  for (auto& p : sheets.mesh.positions)
    p.z() += jitter(random);
  const auto& mesh = sheets.mesh;
  const auto nearby =
      contact::nearby_vertices(mesh.vertex_count(), mesh.triangles, rest_length(mesh), {}, 2, 0.0);
  const std::vector<bool> all(mesh.vertex_count(), true);
  const double radius = 0.005;
  const auto pairs =
      contact::vertex_triangle_pairs(mesh.positions, mesh.triangles, nearby, all, radius);
  std::vector<std::pair<int, int>> expected;
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
    for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
      const auto& tri = mesh.triangles[t];
      const bool close_in_cloth = std::any_of(tri.begin(), tri.end(), [&](int c) {
        return std::binary_search(nearby[v].begin(), nearby[v].end(), c);
      });
      if (close_in_cloth) continue;
      const double d = element::closest_point_on_triangle(
                           mesh.positions[v], mesh.positions[std::size_t(tri[0])],
                           mesh.positions[std::size_t(tri[1])], mesh.positions[std::size_t(tri[2])])
                           .distance;
      if (d < radius) expected.emplace_back(int(v), int(t));
    }
  }
  ASSERT_GT(expected.size(), 100u);
  ASSERT_EQ(pairs.size(), expected.size());
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    EXPECT_EQ(pairs[k].vertex, expected[k].first);
    EXPECT_EQ(pairs[k].triangle, expected[k].second);
  }
}

TEST(ClothPairs, NearbyVerticesFollowEdgesSeamsAndRestLengths) {
  const TriangleMesh strip = mesh::rectangle(0.5, 0.1, 5, 1, mesh::RectanglePattern::right);
  // Vertices 0..5 along the bottom (0.1 m apart), 6..11 along the top; a
  // seam links 0 and 5.
  const auto near = [&](double radius) {
    return contact::nearby_vertices(strip.vertex_count(), strip.triangles, rest_length(strip),
                                    {{0, 5}}, 1, radius)[0];
  };
  const auto has = [](const std::vector<int>& set, int v) {
    return std::binary_search(set.begin(), set.end(), v);
  };
  EXPECT_TRUE(has(near(0.0), 5));
  EXPECT_TRUE(has(near(0.0), 1));
  EXPECT_FALSE(has(near(0.0), 2));
  EXPECT_FALSE(has(near(0.0), 3));
  EXPECT_TRUE(has(near(0.21), 2));  // two bottom edges
  EXPECT_FALSE(has(near(0.19), 2)); // neither two edges nor the diagonal's way
  EXPECT_TRUE(has(near(0.21), 3));  // the seam, then two edges back
}

TEST(SelfContact, JacobianMatchesResidualDifferences) {
  const TwoSheets sheets = two_sheets(0.0015); // every upper vertex in contact
  ClothProblem problem(PETSC_COMM_WORLD, sheets.mesh, fabric(), {});
  problem.loads.gravity = Vector3d(0, 0, -gravity);
  problem.set_self_contact({true, offset, 0.0, 2});
  Vec x = nullptr, v = nullptr;
  ASSERT_EQ(problem.create_solution(&x), 0);
  bool changed = false;
  ASSERT_EQ(problem.refresh_couplings(x, &changed), 0);
  EXPECT_TRUE(changed);
  PetscRandom random = nullptr;
  PetscRandomCreate(PETSC_COMM_WORLD, &random);
  PetscRandomSetInterval(random, -2e-4, 2e-4);
  VecDuplicate(x, &v);
  VecSetRandom(v, random);
  VecAXPY(x, 1.0, v);
  VecSetRandom(v, random);
  fem::SelfContactReport report;
  ASSERT_EQ(problem.self_contact_report(x, &report), 0);
  EXPECT_GT(report.pairs, 40);
  // Self-contact alone, its exact Hessian (steps of 1e-8 and below are
  // round-off's: the error grows as they shrink).
  for (const std::string& name : problem.form_names())
    problem.enable_form(name, name == "self_contact");
  problem.exact_hessian = true;
  const double error = testing::directional_jacobian_error(problem, x, v, 1e-6, NORM_INFINITY);
  EXPECT_GE(error, 0.0) << "assembly failed";
  EXPECT_LT(error, 1e-6);
  bool stale = true;
  ASSERT_EQ(problem.couplings_stale(&stale), 0);
  EXPECT_FALSE(stale);
  PetscRandomDestroy(&random);
  VecDestroy(&v);
  VecDestroy(&x);
}

// The two sheets `gap` apart with self-contact, and the step bound of a
// step moving every lower vertex by `lower` and every upper one by `upper`.
class SheetSteps {
public:
  explicit SheetSteps(double gap)
      : sheets_(two_sheets(gap)), problem_(PETSC_COMM_WORLD, sheets_.mesh, fabric(), {}) {
    problem_.set_self_contact({true, offset, 0.0, 2});
    EXPECT_EQ(problem_.create_solution(&x_), 0);
    VecDuplicate(x_, &d_);
  }
  ~SheetSteps() {
    VecDestroy(&d_);
    VecDestroy(&x_);
  }
  SheetSteps(const SheetSteps&) = delete;
  SheetSteps& operator=(const SheetSteps&) = delete;

  double bound(const Vector3d& lower, const Vector3d& upper) {
    std::vector<Vector3d> motion(sheets_.mesh.vertex_count(), lower);
    for (std::size_t v = sheets_.lower_vertices; v < motion.size(); ++v)
      motion[v] = upper;
    double bound = 0.0;
    EXPECT_EQ(problem_.set_solution(motion, d_), 0);
    EXPECT_EQ(problem_.contact_step_bound(x_, d_, &bound), 0);
    return bound;
  }
  ClothProblem& problem() { return problem_; }

private:
  TwoSheets sheets_;
  ClothProblem problem_;
  Vec x_ = nullptr, d_ = nullptr;
};

TEST(SelfContact, TheStepBoundKeepsEveryVertexOnItsSide) {
  // The upper sheet 3 mm over the lower one, a step moving it 1 cm down.
  const double gap = 0.003, drop = 0.01;
  SheetSteps steps(gap);
  const Vector3d down(0.0, 0.0, -drop);
  // The pair may close to the smaller of half its distance and a tenth of
  // the offset: 0.2 mm of the 3 mm, at (3 - 0.2) / 10 of the step.
  const double allowed = (gap - 0.1 * offset) / drop;
  const double bound = steps.bound(Vector3d::Zero(), down);
  EXPECT_LE(bound, allowed);
  EXPECT_GT(bound, 0.95 * allowed);
  // Without self-contact nothing bounds it.
  steps.problem().enable_form("self_contact", false);
  EXPECT_EQ(steps.bound(Vector3d::Zero(), down), 1.0);
}

TEST(SelfContact, TwoLayersMovingAsOneDoNotBoundTheStep) {
  // The upper sheet lying on the lower one (1.9 mm over it, inside the
  // offset), both moved 5 cm down together (a trouser leg falling as a
  // whole), then the upper one alone 5 cm across: no pair comes closer, so
  // nothing bounds either step. Bounded by the pair's motions alone,
  // |dv| + max |dcorner| = 10 cm, fifty advances of (1.9 - 0.2) mm / 10 cm
  // cut the first to 0.85, and the hung trousers of the wear crawled
  // through 60,000 Newton iterations.
  const double shift = 0.05;
  SheetSteps steps(0.0019);
  EXPECT_EQ(steps.bound(Vector3d(0, 0, -shift), Vector3d(0, 0, -shift)), 1.0);
  EXPECT_EQ(steps.bound(Vector3d::Zero(), Vector3d(shift, 0, 0)), 1.0);
}

// A system that outlives a refresh of the pairs made elsewhere (the
// certificate's, between a wear's steps) creates its Jacobian anew: the
// pairs now assembled are not in the one it had.
TEST(SelfContact, ASystemFollowsARefreshMadeElsewhere) {
  // The upper sheet lying on the lower one (1.9 mm over it, inside the
  // offset), pinned along one edge; the lower one pinned round its edges,
  // so that pairs couple free vertices of both.
  TwoSheets sheets = two_sheets(0.0019);
  std::vector<int> pinned;
  for (std::size_t v = 0; v < sheets.mesh.vertex_count(); ++v) {
    const Vector3d& p = sheets.mesh.positions[v];
    const bool rim = std::min({p.x(), p.y(), 0.4 - p.x(), 0.4 - p.y()}) < 1e-9;
    if ((v < sheets.lower_vertices && rim) || std::abs(p.y() - 0.0471) < 1e-9)
      pinned.push_back(int(v));
  }
  ClothProblem problem(PETSC_COMM_WORLD, sheets.mesh, fabric(), pinned);
  problem.loads.gravity = Vector3d(0, 0, -gravity);
  problem.set_self_contact({true, offset, 0.0, 2});
  Vec x = nullptr;
  ASSERT_EQ(problem.create_solution(&x), 0);
  IncrementalSystem system(problem, x); // its Jacobian without pairs
  bool changed = false;
  ASSERT_EQ(problem.refresh_couplings(x, &changed), 0); // made elsewhere
  ASSERT_TRUE(changed);
  StaticOptions options;
  options.minimise = true;
  StaticReport report;
  ASSERT_EQ(solve_static(system, x, options, &report), 0);
  fem::SelfContactReport contact;
  ASSERT_EQ(problem.self_contact_report(x, &contact), 0);
  EXPECT_TRUE(report.converged);
  EXPECT_GT(contact.pairs, 20);
  VecDestroy(&x);
}

struct Landing {
  StaticReport report;
  std::vector<Vector3d> positions;
  fem::SelfContactReport contact;
};

// The upper sheet pinned along its edge y = 0 at 2 cm over the lower one,
// which is pinned flat everywhere.
Landing land(bool self_contact) {
  const TwoSheets sheets = two_sheets(0.02);
  std::vector<int> pinned;
  for (std::size_t v = 0; v < sheets.mesh.vertex_count(); ++v) {
    const bool lower = v < sheets.lower_vertices;
    if (lower || std::abs(sheets.mesh.positions[v].y() - 0.0471) < 1e-9) pinned.push_back(int(v));
  }
  ClothProblem problem(PETSC_COMM_WORLD, sheets.mesh, fabric(), pinned);
  problem.loads.gravity = Vector3d(0, 0, -gravity);
  if (self_contact) problem.set_self_contact({true, offset, 0.0, 2});
  Landing out;
  Vec x = nullptr;
  EXPECT_EQ(problem.create_solution(&x), 0);
  StaticOptions options;
  options.load_steps = 4;
  options.minimise = true;
  EXPECT_EQ(solve_static(problem, x, options, &out.report), 0);
  EXPECT_EQ(problem.positions_everywhere(x, &out.positions), 0);
  EXPECT_EQ(problem.self_contact_report(x, &out.contact), 0);
  VecDestroy(&x);
  return out;
}

TEST(SelfContact, ASheetLiesOnASheetInsteadOfFallingThroughIt) {
  const Landing landed = land(true);
  EXPECT_TRUE(landed.report.converged);
  const std::size_t lower = 81;
  double lowest = INFINITY;
  for (std::size_t v = lower; v < landed.positions.size(); ++v)
    lowest = std::min(lowest, landed.positions[v].z());
  // On the lower sheet (z = 0), at the offset less the penalty's give: no
  // more than twice the heaviest vertex's weight (six 5 cm triangles' third)
  // over the stiffness (the largest modulus), micrometres.
  const double heaviest = density * gravity * 6.0 * (0.05 * 0.05 / 2.0) / 3.0;
  EXPECT_GT(lowest, offset - 2.0 * heaviest / 2000.0);
  EXPECT_LT(lowest, offset);
  EXPECT_GT(landed.contact.pairs, 20);
  EXPECT_GT(landed.contact.min_distance, 0.9 * offset);
  // The contact carries what the pinned edge does not: a positive share of
  // the sheet's weight, less than all of it.
  const double weight = density * 0.3 * 0.3 * gravity;
  EXPECT_GT(landed.contact.normal_force, 0.3 * weight);
  EXPECT_LT(landed.contact.normal_force, weight);

  // Without self-contact the same sheet hangs through the lower one.
  const Landing through = land(false);
  double lowest_through = INFINITY;
  for (std::size_t v = lower; v < through.positions.size(); ++v)
    lowest_through = std::min(lowest_through, through.positions[v].z());
  EXPECT_LT(lowest_through, -0.1);
}

} // namespace
} // namespace sartor
