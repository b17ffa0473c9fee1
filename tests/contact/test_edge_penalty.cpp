// The edge-sample contact kernel (contact/edge_penalty.hpp): gradient and
// Hessian with respect to both vertices by central differences on curved
// bodies, the sample force split between the vertices as a lever would split
// it, PSD projection of the whole, and where the samples sit on an edge.

#include "contact/analytic_shapes.hpp"
#include "contact/body.hpp"
#include "contact/edge_penalty.hpp"
#include "tests/element/finite_difference.hpp"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>

#include <random>

namespace sartor::contact {
namespace {

using Eigen::Vector3d;
using element::Want;
using element::testing::numeric_gradient;
using element::testing::numeric_jacobian;

// Edges whose sample point lies in the offset layer of a moved, scaled
// sphere and of a rounded box, at several parameters s.
TEST(EdgePenalty, DerivativesOnCurvedBodies) {
  const double k = 2.5e4, offset = 0.01;
  Body ball("ball", std::make_shared<Sphere>(Vector3d(0, 0, 0), 0.3), Vector3d::Zero());
  ball.motion.scale.add(0.0, 1.0);
  ball.motion.scale.add(1.0, 1.2);
  Body table("table", std::make_shared<Box>(Vector3d::Zero(), Vector3d(1, 1, 0.1), 0.02),
             Vector3d::Zero());
  std::mt19937 random(5);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  int checked = 0;
  for (const Body* b : {&ball, &table}) {
    for (int i = 0; i < 60; ++i) {
      const Vector3d direction =
          Vector3d(uniform(random), uniform(random), uniform(random)).normalized();
      const Vector3d surface = b->query(2.0 * direction, 0.7).closest;
      const double s = 0.5 + 0.45 * uniform(random);
      // A chord 8 cm long through a point of the contact layer.
      const Vector3d along = direction.cross(Vector3d(uniform(random), 1.0, 0.3)).normalized();
      const Vector3d sample = surface + 0.011 * (uniform(random) + 0.3) * direction;
      Vector6 x;
      x << sample - 0.08 * s * along, sample + 0.08 * (1.0 - s) * along;
      const auto query = [&](const Vector6& y) {
        return b->query(edge_point(y.head<3>(), y.tail<3>(), s), 0.7);
      };
      const auto energy = [&](const Vector6& y) {
        return edge_sample_penalty(k, offset, s, query(y), Want::energy, false).energy;
      };
      const auto gradient = [&](const Vector6& y) {
        return Vector6(edge_sample_penalty(k, offset, s, query(y), Want::gradient, false).gradient);
      };
      const EdgeSampleResult exact =
          edge_sample_penalty(k, offset, s, query(x), Want::hessian, false);
      if (exact.energy == 0.0) continue;
      ++checked;
      EXPECT_LT((numeric_gradient<6>(energy, x, 1e-8) - exact.gradient).norm(),
                1e-6 * exact.gradient.norm());
      EXPECT_LT((numeric_jacobian<6, 6>(gradient, x, 1e-8) - exact.hessian).norm(),
                1e-6 * exact.hessian.norm());
    }
  }
  EXPECT_GT(checked, 40);
}

// On a floor, a sample 2 mm into a 5 mm offset at a quarter of the edge:
// the force k * 3 mm pushes up, and its two vertices carry 3/4 and 1/4 of it
// (the lever rule), whatever their own heights.
TEST(EdgePenalty, ForceIsSharedByTheLeverRule) {
  const double k = 1e3, offset = 5e-3, s = 0.25;
  const Plane floor(Vector3d::Zero(), Vector3d::UnitZ());
  const Vector3d a(0, 0, 1e-3), b(0.1, 0, 9e-3); // the quarter point is at 3 mm
  const EdgeSampleResult r =
      edge_sample_penalty(k, offset, s, floor.query(edge_point(a, b, s)), Want::hessian, false);
  const double force = k * (offset - 3e-3);
  EXPECT_NEAR(r.force.z(), force, 1e-9 * force);
  EXPECT_NEAR(-r.gradient[2], 0.75 * force, 1e-9 * force);
  EXPECT_NEAR(-r.gradient[5], 0.25 * force, 1e-9 * force);
  EXPECT_NEAR(r.energy, 0.5 * k * (offset - 3e-3) * (offset - 3e-3), 1e-12);
  EXPECT_NEAR(r.hessian(2, 5), 0.75 * 0.25 * k, 1e-9 * k);
}

// Inside a ball the curvature term makes the point Hessian indefinite; the
// projected 6x6 Hessian has no negative eigenvalue, the unprojected one has.
TEST(EdgePenalty, ProjectionMakesTheWholeHessianSemiDefinite) {
  const double k = 1e4, offset = 0.05;
  const Sphere ball(Vector3d::Zero(), 0.1);
  const Vector3d a(0.12, -0.02, 0.0), b(0.12, 0.03, 0.0);
  const SurfaceQuery q = ball.query(edge_point(a, b, 0.4));
  const auto lowest = [&](bool project) {
    const Matrix6 h = edge_sample_penalty(k, offset, 0.4, q, Want::hessian, project).hessian;
    return Eigen::SelfAdjointEigenSolver<Matrix6>(h).eigenvalues().minCoeff();
  };
  EXPECT_LT(lowest(false), -1e-3 * k);
  EXPECT_GT(lowest(true), -1e-9 * k);
}

TEST(EdgePenalty, SamplesNoFurtherApartThanTheSpacing) {
  EXPECT_TRUE(edge_sample_parameters(0.019, 0.02).empty());
  EXPECT_TRUE(edge_sample_parameters(0.08, 0.0).empty());
  const std::vector<double> half = edge_sample_parameters(0.04, 0.02); // exactly two pieces
  ASSERT_EQ(half.size(), 1u);
  EXPECT_DOUBLE_EQ(half[0], 0.5);
  const std::vector<double> quarters = edge_sample_parameters(0.075, 0.02);
  ASSERT_EQ(quarters.size(), 3u);
  EXPECT_DOUBLE_EQ(quarters[0], 0.25);
  EXPECT_DOUBLE_EQ(quarters[2], 0.75);
}

} // namespace
} // namespace sartor::contact
