// Physical checks of the follower pressure: the load of one triangle and, on
// a closed surface, the work of the pressure on the enclosed volume.

#include "element/pressure.hpp"

#include "finite_difference.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <array>
#include <random>

namespace sartor::element {
namespace {

using Eigen::Vector3d;
using Vector9 = Eigen::Matrix<double, 9, 1>;
using Vector12 = Eigen::Matrix<double, 12, 1>;

TEST(FollowerPressure, EachVertexCarriesAThirdOfPressureTimesAreaNormal) {
  Vector9 x;
  x << 0.0, 0.0, 0.0, 0.2, 0.0, 0.0, 0.0, 0.1, 0.0;
  const PressureLoad load = follower_pressure(300.0, x);
  for (int i = 0; i < 3; ++i) {
    EXPECT_LT((load.force.segment<3>(3 * i) - Vector3d(0.0, 0.0, 300.0 * 0.01 / 3)).norm(), 1e-14);
  }
  // Reversing the corner order reverses the load.
  Vector9 reversed;
  reversed << x.segment<3>(0), x.segment<3>(6), x.segment<3>(3);
  EXPECT_LT(
      (follower_pressure(300.0, reversed).force.segment<3>(0) + load.force.segment<3>(0)).norm(),
      1e-14);
}

// On a closed surface with outward normals the pressure forces are the
// gradient of p V (V the enclosed volume): they add up to zero and their
// assembled Jacobian is the symmetric Hessian of p V.
TEST(FollowerPressure, ClosedSurfaceLoadIsTheGradientOfPressureTimesVolume) {
  std::mt19937 random(9);
  std::uniform_real_distribution<double> jitter(-0.1, 0.1);
  Vector12 x;
  x << 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0;
  for (int i = 0; i < 12; ++i)
    x(i) += jitter(random);
  const std::array<std::array<int, 3>, 4> faces{{{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}}};
  const double pressure = 1500.0;
  const auto assemble = [&](const Vector12& y, Vector12& force,
                            Eigen::Matrix<double, 12, 12>& jacobian) {
    force.setZero();
    jacobian.setZero();
    for (const auto& f : faces) {
      Vector9 corners;
      for (int i = 0; i < 3; ++i)
        corners.segment<3>(3 * i) = y.segment<3>(3 * f[static_cast<std::size_t>(i)]);
      const PressureLoad load = follower_pressure(pressure, corners);
      for (int i = 0; i < 3; ++i) {
        force.segment<3>(3 * f[static_cast<std::size_t>(i)]) += load.force.segment<3>(3 * i);
        for (int j = 0; j < 3; ++j) {
          jacobian.block<3, 3>(3 * f[static_cast<std::size_t>(i)],
                               3 * f[static_cast<std::size_t>(j)]) +=
              load.jacobian.block<3, 3>(3 * i, 3 * j);
        }
      }
    }
  };
  const auto work = [&](const Vector12& y) {
    const Vector3d a = y.segment<3>(3) - y.segment<3>(0);
    const Vector3d b = y.segment<3>(6) - y.segment<3>(0);
    const Vector3d c = y.segment<3>(9) - y.segment<3>(0);
    return pressure * a.cross(b).dot(c) / 6.0;
  };
  Vector12 force;
  Eigen::Matrix<double, 12, 12> jacobian;
  assemble(x, force, jacobian);
  EXPECT_GT(work(x), 0.0);
  const Vector12 expected = testing::numeric_gradient<12>(work, x, 1e-6);
  EXPECT_LT(testing::relative_error(force, expected), 1e-8);
  Vector3d net = Vector3d::Zero();
  for (int i = 0; i < 4; ++i)
    net += force.segment<3>(3 * i);
  EXPECT_LT(net.norm(), 1e-10);
  EXPECT_LT((jacobian - jacobian.transpose()).cwiseAbs().maxCoeff(),
            1e-12 * jacobian.cwiseAbs().maxCoeff());
}

} // namespace
} // namespace sartor::element
