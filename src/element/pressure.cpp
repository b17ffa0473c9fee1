#include "element/pressure.hpp"

#include <Eigen/Geometry>

namespace sartor::element {

namespace {

// [v]x: cross(v) w = v x w.
Eigen::Matrix3d cross(const Eigen::Vector3d& v) {
  Eigen::Matrix3d m;
  m << 0.0, -v.z(), v.y(), v.z(), 0.0, -v.x(), -v.y(), v.x(), 0.0;
  return m;
}

} // namespace

// Each vertex carries p n / 3 with n = e1 x e2 / 2, e1 = x1 - x0, e2 = x2 - x0;
// dn = (de1 x e2 + e1 x de2)/2 = (-[e2]x de1 + [e1]x de2)/2.
PressureLoad follower_pressure(double pressure, const Eigen::Matrix<double, 9, 1>& x) {
  const Eigen::Vector3d x0 = x.segment<3>(0);
  const Eigen::Vector3d e1 = x.segment<3>(3) - x0;
  const Eigen::Vector3d e2 = x.segment<3>(6) - x0;
  const Eigen::Vector3d vertex_force = pressure / 6.0 * e1.cross(e2);
  const double scale = pressure / 6.0;
  const Eigen::Matrix3d d_dx1 = -scale * cross(e2);
  const Eigen::Matrix3d d_dx2 = scale * cross(e1);
  const Eigen::Matrix3d d_dx0 = -(d_dx1 + d_dx2);

  PressureLoad load;
  for (int i = 0; i < 3; ++i) {
    load.force.segment<3>(3 * i) = vertex_force;
    load.jacobian.block<3, 3>(3 * i, 0) = d_dx0;
    load.jacobian.block<3, 3>(3 * i, 3) = d_dx1;
    load.jacobian.block<3, 3>(3 * i, 6) = d_dx2;
  }
  return load;
}

double spanned_volume(const Eigen::Matrix<double, 9, 1>& x, const Eigen::Vector3d& centre) {
  const Eigen::Vector3d a = x.segment<3>(0) - centre;
  const Eigen::Vector3d b = x.segment<3>(3) - centre;
  const Eigen::Vector3d c = x.segment<3>(6) - centre;
  return a.dot(b.cross(c)) / 6.0;
}

} // namespace sartor::element
