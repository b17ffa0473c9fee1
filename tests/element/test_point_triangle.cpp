// The vertex-triangle penalty of cloth self-contact: its distance against
// an independent construction (the plane's foot when it falls inside, else
// the nearest of the three segments), its derivatives against finite
// differences on every feature (with and without an onset band), its force
// against the law's closed form, and its vanishing beyond the offset, with a
// band smoothly (C^2: no jump of the Hessian where a point enters the layer).

#include "element/point_triangle.hpp"
#include "finite_difference.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

namespace sartor::element {
namespace {

using Eigen::Vector3d;
using testing::numeric_gradient;
using testing::numeric_jacobian;
using testing::relative_error;

double segment_distance(const Vector3d& p, const Vector3d& a, const Vector3d& b) {
  double best = std::min((p - a).norm(), (p - b).norm());
  const Vector3d e = b - a;
  const double t = (p - a).dot(e) / e.dot(e);
  if (t > 0.0 && t < 1.0) best = std::min(best, (p - (a + t * e)).norm());
  return best;
}

// The plane's foot if it lies inside (by the signs of the three sub-areas),
// else the nearest edge.
double reference_distance(const Vector3d& p, const Vector3d& a, const Vector3d& b,
                          const Vector3d& c) {
  const Vector3d n = (b - a).cross(c - a).normalized();
  const Vector3d foot = p - (p - a).dot(n) * n;
  const bool inside = (b - a).cross(foot - a).dot(n) >= 0.0 &&
                      (c - b).cross(foot - b).dot(n) >= 0.0 &&
                      (a - c).cross(foot - c).dot(n) >= 0.0;
  if (inside) return std::abs((p - a).dot(n));
  return std::min(
      {segment_distance(p, a, b), segment_distance(p, b, c), segment_distance(p, c, a)});
}

Vector12 stacked(const Vector3d& p, const Vector3d& a, const Vector3d& b, const Vector3d& c) {
  Vector12 x;
  x << p, a, b, c;
  return x;
}

const Vector3d a(0.0, 0.0, 0.0), b(0.01, 0.001, 0.0), c(0.003, 0.009, 0.001);

TEST(PointTriangle, DistanceMatchesTheFootOrTheNearestEdge) {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> coordinate(-0.01, 0.02);
  for (int k = 0; k < 2000; ++k) {
    const Vector3d p(coordinate(random), coordinate(random), coordinate(random) - 0.005);
    const ClosestPoint q = closest_point_on_triangle(p, a, b, c);
    EXPECT_NEAR(q.distance, reference_distance(p, a, b, c), 1e-15) << "point " << p.transpose();
    const Vector3d foot = q.barycentric[0] * a + q.barycentric[1] * b + q.barycentric[2] * c;
    EXPECT_NEAR((p - foot).norm(), q.distance, 1e-15);
    EXPECT_NEAR(q.barycentric.sum(), 1.0, 1e-14);
    EXPECT_GE(q.barycentric.minCoeff(), -1e-14);
  }
}

// A point above each feature, within the offset.
struct FeatureCase {
  TriangleFeature feature;
  Vector3d point;
};

std::vector<FeatureCase> feature_cases() {
  const Vector3d n = (b - a).cross(c - a).normalized();
  const Vector3d centre = (a + b + c) / 3.0;
  const Vector3d middle_ab = 0.5 * (a + b), middle_bc = 0.5 * (b + c), middle_ca = 0.5 * (c + a);
  return {
      {TriangleFeature::face, centre + 0.0007 * n},
      {TriangleFeature::edge_ab, middle_ab + 0.0004 * n + 0.0003 * (middle_ab - c).normalized()},
      {TriangleFeature::edge_bc, middle_bc - 0.0004 * n + 0.0003 * (middle_bc - a).normalized()},
      {TriangleFeature::edge_ca, middle_ca + 0.0002 * n + 0.0005 * (middle_ca - b).normalized()},
      {TriangleFeature::vertex_a, a + 0.0003 * n - 0.0004 * (centre - a).normalized()},
      {TriangleFeature::vertex_b, b - 0.0005 * n - 0.0002 * (centre - b).normalized()},
      {TriangleFeature::vertex_c, c + 0.0001 * n - 0.0006 * (centre - c).normalized()},
  };
}

constexpr double stiffness = 250.0, offset = 0.001;

TEST(PointTriangle, DerivativesMatchFiniteDifferencesOnEveryFeature) {
  // The feature cases' depths (0.3 to 0.9 mm) lie inside and beyond 0.6 mm.
  for (const double band : {0.0, 0.6 * offset}) {
    for (const FeatureCase& f : feature_cases()) {
      const Vector12 x = stacked(f.point, a, b, c);
      ASSERT_EQ(closest_point_on_triangle(f.point, a, b, c).feature, f.feature);
      const Result<12> r = point_triangle_penalty(stiffness, offset, x, Want::hessian, true, band);
      ASSERT_GT(r.energy, 0.0);
      const auto energy = [band](const Vector12& y) {
        return point_triangle_penalty(stiffness, offset, y, Want::energy, false, band).energy;
      };
      const auto gradient = [band](const Vector12& y) {
        return point_triangle_penalty(stiffness, offset, y, Want::gradient, false, band).gradient;
      };
      EXPECT_LT(relative_error(numeric_gradient<12>(energy, x, 1e-9), r.gradient), 1e-6)
          << "feature " << int(f.feature) << ", band " << band;
      EXPECT_LT(relative_error(numeric_jacobian<12, 12>(gradient, x, 1e-9), r.hessian), 1e-5)
          << "feature " << int(f.feature) << ", band " << band;
    }
  }
}

// The push on the point is f(g) = k g^2 / b (2 - g / b) inside the band b,
// k g beyond it; at the layer's edge the Hessian vanishes (the plain
// quadratic's jumps to k there).
TEST(PointTriangle, OnsetBandSetsTheForceInSmoothly) {
  const double band = 0.5 * offset;
  const Vector3d n = (b - a).cross(c - a).normalized();
  const Vector3d centre = (a + b + c) / 3.0;
  for (const double depth : {0.1 * band, 0.5 * band, 0.99 * band, 1.5 * band}) {
    const Vector12 x = stacked(centre + (offset - depth) * n, a, b, c);
    const Result<12> r = point_triangle_penalty(stiffness, offset, x, Want::gradient, false, band);
    const double s = depth / band;
    const double expected = depth < band ? stiffness * depth * s * (2.0 - s) : stiffness * depth;
    EXPECT_NEAR(r.gradient.head<3>().dot(n), -expected, 1e-12 * stiffness * offset)
        << "depth " << depth;
  }
  const Vector12 entering = stacked(centre + (offset - 1e-7 * band) * n, a, b, c);
  const double smooth =
      point_triangle_penalty(stiffness, offset, entering, Want::hessian, true, band).hessian.norm();
  const double plain =
      point_triangle_penalty(stiffness, offset, entering, Want::hessian, true).hessian.norm();
  EXPECT_GT(plain, stiffness);
  EXPECT_LT(smooth, 1e-5 * stiffness);
}

TEST(PointTriangle, ForcesBalanceAndPushThePointAway) {
  for (const FeatureCase& f : feature_cases()) {
    const Vector12 x = stacked(f.point, a, b, c);
    const Result<12> r = point_triangle_penalty(stiffness, offset, x, Want::gradient);
    const ClosestPoint q = closest_point_on_triangle(f.point, a, b, c);
    const Vector3d foot = q.barycentric[0] * a + q.barycentric[1] * b + q.barycentric[2] * c;
    // -gradient on p: k (delta - d) along p - q.
    const Vector3d push = -r.gradient.head<3>();
    EXPECT_NEAR(push.norm(), stiffness * (offset - q.distance), 1e-12);
    EXPECT_GT(push.dot(f.point - foot), 0.0);
    Vector3d total = Vector3d::Zero();
    for (int i = 0; i < 4; ++i)
      total += r.gradient.segment<3>(3 * i);
    EXPECT_LT(total.norm(), 1e-12 * push.norm());
  }
}

TEST(PointTriangle, NothingBeyondTheOffsetAndTheProjectionIsSemiDefinite) {
  const Vector3d n = (b - a).cross(c - a).normalized();
  const Vector3d centre = (a + b + c) / 3.0;
  const Result<12> far = point_triangle_penalty(
      stiffness, offset, stacked(centre + 0.0011 * n, a, b, c), Want::hessian);
  EXPECT_EQ(far.energy, 0.0);
  EXPECT_EQ(far.gradient.norm(), 0.0);
  EXPECT_EQ(far.hessian.norm(), 0.0);
  for (const FeatureCase& f : feature_cases()) {
    const Result<12> r =
        point_triangle_penalty(stiffness, offset, stacked(f.point, a, b, c), Want::hessian);
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 12, 12>> eigen(r.hessian);
    EXPECT_GE(eigen.eigenvalues().minCoeff(), -1e-9 * eigen.eigenvalues().maxCoeff());
  }
}

} // namespace
} // namespace sartor::element
