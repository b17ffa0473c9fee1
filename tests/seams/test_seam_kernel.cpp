// The seam springs: derivatives against finite differences, the energy of a
// known gap, and invariance under rigid motions.

#include "element/seam.hpp"

#include "../element/finite_difference.hpp"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include <random>

namespace sartor::element {
namespace {

using Vector6 = Eigen::Matrix<double, 6, 1>;
using Vector9 = Eigen::Matrix<double, 9, 1>;

template <int N>
Eigen::Matrix<double, N, 1> random_positions(unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> coordinate(-0.3, 0.3);
  Eigen::Matrix<double, N, 1> x;
  for (int i = 0; i < N; ++i)
    x(i) = coordinate(random);
  return x;
}

TEST(SeamKernel, VertexToVertexDerivativesMatchFiniteDifferences) {
  const double k = 2.5e4;
  for (unsigned seed = 1; seed <= 5; ++seed) {
    const Vector6 x = random_positions<6>(seed);
    const auto result = seam_vertex_vertex(k, x);
    const auto energy = [&](const Vector6& y) {
      return seam_vertex_vertex(k, y, Want::energy).energy;
    };
    const auto gradient = [&](const Vector6& y) {
      return Vector6(seam_vertex_vertex(k, y, Want::gradient).gradient);
    };
    EXPECT_LT(
        testing::relative_error(result.gradient, testing::numeric_gradient<6>(energy, x, 1e-6)),
        1e-8);
    EXPECT_LT(
        testing::relative_error(result.hessian, testing::numeric_jacobian<6, 6>(gradient, x, 1e-6)),
        1e-8);
    EXPECT_NEAR(result.energy, 0.5 * k * (x.segment<3>(0) - x.segment<3>(3)).squaredNorm(),
                1e-12 * result.energy);
  }
}

TEST(SeamKernel, VertexToEdgeDerivativesMatchFiniteDifferences) {
  const double k = 800.0;
  for (const double s : {0.0, 0.3, 0.5, 1.0}) {
    const Vector9 x = random_positions<9>(7);
    const auto result = seam_vertex_edge(k, s, x);
    const auto energy = [&](const Vector9& y) {
      return seam_vertex_edge(k, s, y, Want::energy).energy;
    };
    const auto gradient = [&](const Vector9& y) {
      return Vector9(seam_vertex_edge(k, s, y, Want::gradient).gradient);
    };
    EXPECT_LT(
        testing::relative_error(result.gradient, testing::numeric_gradient<9>(energy, x, 1e-6)),
        1e-8)
        << "s = " << s;
    EXPECT_LT(
        testing::relative_error(result.hessian, testing::numeric_jacobian<9, 9>(gradient, x, 1e-6)),
        1e-8)
        << "s = " << s;
    // The Hessian is positive semi-definite: Newton sees a convex spring.
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 9, 9>> eigen(result.hessian);
    EXPECT_GT(eigen.eigenvalues().minCoeff(), -1e-9 * k);
  }
}

TEST(SeamKernel, VertexToEdgeAnchorsAtTheEdgeParameter) {
  // a sits 2 cm above the point at s = 0.25 of the edge b-c: E = k (0.02)^2 / 2,
  // the force on a points down to the edge, and the reactions on b and c
  // split as (1 - s, s).
  Vector9 x;
  x << 0.25, 0.0, 0.02, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0;
  const double k = 1000.0;
  const auto result = seam_vertex_edge(k, 0.25, x);
  EXPECT_NEAR(result.energy, 0.5 * k * 0.02 * 0.02, 1e-15);
  EXPECT_LT((result.gradient.segment<3>(0) - Eigen::Vector3d(0.0, 0.0, k * 0.02)).norm(), 1e-12);
  EXPECT_LT((result.gradient.segment<3>(3) + 0.75 * result.gradient.segment<3>(0)).norm(), 1e-12);
  EXPECT_LT((result.gradient.segment<3>(6) + 0.25 * result.gradient.segment<3>(0)).norm(), 1e-12);
}

TEST(SeamKernel, RigidMotionsLeaveTheEnergyAndNetForceUnchanged) {
  const Vector9 x = random_positions<9>(3);
  const Eigen::Matrix3d rotation =
      Eigen::AngleAxisd(0.7, Eigen::Vector3d(1.0, 2.0, -0.5).normalized()).toRotationMatrix();
  Vector9 moved;
  for (int i = 0; i < 3; ++i)
    moved.segment<3>(3 * i) = rotation * x.segment<3>(3 * i) + Eigen::Vector3d(0.1, -0.4, 2.0);
  const auto before = seam_vertex_edge(300.0, 0.6, x);
  const auto after = seam_vertex_edge(300.0, 0.6, moved);
  EXPECT_NEAR(after.energy, before.energy, 1e-12 * before.energy);
  const Eigen::Vector3d net =
      after.gradient.segment<3>(0) + after.gradient.segment<3>(3) + after.gradient.segment<3>(6);
  EXPECT_LT(net.norm(), 1e-12 * after.gradient.norm());
}

} // namespace
} // namespace sartor::element
