#include "element/bending.hpp"

#include "common/error.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace sartor::element {

namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;
using Matrix12 = Eigen::Matrix<double, 12, 12>;
using Jacobian = Eigen::Matrix<double, 3, 12>; // of a 3-vector with respect to x
using Row = Eigen::Matrix<double, 1, 12>;      // of a scalar with respect to x

// Triangles flatter than this (twice the area relative to the longest edge
// squared) have no normal: rejected at rest, skipped when current.
constexpr double degenerate_ratio = 1e-12;

// [v]x: cross(v) w = v x w.
Matrix3d cross(const Vector3d& v) {
  Matrix3d m;
  m << 0.0, -v.z(), v.y(), v.z(), 0.0, -v.x(), -v.y(), v.x(), 0.0;
  return m;
}

// d(x_to - x_from)/dx.
Jacobian difference(int to, int from) {
  Jacobian d = Jacobian::Zero();
  d.block<3, 3>(0, 3 * to) = Matrix3d::Identity();
  d.block<3, 3>(0, 3 * from) = -Matrix3d::Identity();
  return d;
}

// The dihedral angle of the hinge with its gradient and Hessian.
struct Dihedral {
  bool degenerate = false;
  double angle = 0.0;
  Vector12 gradient = Vector12::Zero();
  Matrix12 hessian = Matrix12::Zero();
};

// With e = x1 - x0, f2 = x2 - x0, f3 = x3 - x0, n1 = e x f2, n2 = f3 x e:
// an opposite vertex moves its triangle about the edge, d theta/dx2 =
// -|e| n1/|n1|^2 (one over its height), d theta/dx3 = -|e| n2/|n2|^2; the
// edge vertices take the reactions in proportion to where the opposite
// vertices project on the edge, t_k = f_k.e/|e|^2:
// d theta/dx0 = -(1 - t2) g2 - (1 - t3) g3, d theta/dx1 = -t2 g2 - t3 g3
// (invariance under translations and rotations). The Hessian is the exact
// derivative of these expressions by the chain rule.
Dihedral dihedral(const Vector12& x, Want want) {
  const Vector3d x0 = x.segment<3>(0);
  const Vector3d e = x.segment<3>(3) - x0;
  const Vector3d f2 = x.segment<3>(6) - x0;
  const Vector3d f3 = x.segment<3>(9) - x0;
  const Vector3d n1 = e.cross(f2);
  const Vector3d n2 = f3.cross(e);
  const double l2 = e.squaredNorm();
  const double n1sq = n1.squaredNorm();
  const double n2sq = n2.squaredNorm();
  const double longest = std::max({l2, f2.squaredNorm(), f3.squaredNorm()});

  Dihedral d;
  if (!(l2 > 0.0) || !(n1sq > 0.0) || !(n2sq > 0.0) ||
      std::sqrt(std::min(n1sq, n2sq)) <= degenerate_ratio * longest) {
    d.degenerate = true;
    return d;
  }
  const double l = std::sqrt(l2);
  d.angle = std::atan2(n1.cross(n2).dot(e) / l, n1.dot(n2));
  if (want == Want::energy) return d;

  const Vector3d m1 = n1 / n1sq;
  const Vector3d m2 = n2 / n2sq;
  const Vector3d g2 = -l * m1;
  const Vector3d g3 = -l * m2;
  const double t2 = f2.dot(e) / l2;
  const double t3 = f3.dot(e) / l2;
  d.gradient.segment<3>(0) = -(1.0 - t2) * g2 - (1.0 - t3) * g3;
  d.gradient.segment<3>(3) = -t2 * g2 - t3 * g3;
  d.gradient.segment<3>(6) = g2;
  d.gradient.segment<3>(9) = g3;
  if (want == Want::gradient) return d;

  const Jacobian de = difference(1, 0);
  const Jacobian df2 = difference(2, 0);
  const Jacobian df3 = difference(3, 0);
  const Jacobian dn1 = cross(e) * df2 - cross(f2) * de;
  const Jacobian dn2 = cross(f3) * de - cross(e) * df3;
  const Row dl = (e / l).transpose() * de;
  const Matrix3d identity = Matrix3d::Identity();
  // d(n/|n|^2) = (I - 2 n n^T/|n|^2) dn / |n|^2.
  const Jacobian dm1 = (identity - 2.0 * n1 * m1.transpose()) * dn1 / n1sq;
  const Jacobian dm2 = (identity - 2.0 * n2 * m2.transpose()) * dn2 / n2sq;
  const Jacobian dg2 = -m1 * dl - l * dm1;
  const Jacobian dg3 = -m2 * dl - l * dm2;
  const Row dt2 = (e.transpose() * df2 + f2.transpose() * de) / l2 - (2.0 * t2 / l) * dl;
  const Row dt3 = (e.transpose() * df3 + f3.transpose() * de) / l2 - (2.0 * t3 / l) * dl;
  Matrix12 h;
  h.block<3, 12>(0, 0) = g2 * dt2 - (1.0 - t2) * dg2 + g3 * dt3 - (1.0 - t3) * dg3;
  h.block<3, 12>(3, 0) = -g2 * dt2 - t2 * dg2 - g3 * dt3 - t3 * dg3;
  h.block<3, 12>(6, 0) = dg2;
  h.block<3, 12>(9, 0) = dg3;
  d.hessian = 0.5 * (h + h.transpose());
  return d;
}

double cross2(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

// Cotangent of the corner at p of the triangle (p, q, r).
double cotangent(const Eigen::Vector2d& p, const Eigen::Vector2d& q, const Eigen::Vector2d& r) {
  const Eigen::Vector2d a = q - p;
  const Eigen::Vector2d b = r - p;
  return a.dot(b) / std::abs(cross2(a, b));
}

// Material area of a rest triangle; throws InputError when degenerate.
double rest_area(const std::array<Eigen::Vector2d, 3>& uv, const char* which) {
  const double twice_area = std::abs(cross2(uv[1] - uv[0], uv[2] - uv[0]));
  const double longest = std::max({(uv[1] - uv[0]).squaredNorm(), (uv[2] - uv[0]).squaredNorm(),
                                   (uv[2] - uv[1]).squaredNorm()});
  if (!(twice_area > degenerate_ratio * longest) || !std::isfinite(twice_area)) {
    std::ostringstream text;
    text.precision(10);
    text << "bending hinge: degenerate " << which << " triangle in material coordinates ("
         << uv[0].x() << ", " << uv[0].y() << "), (" << uv[1].x() << ", " << uv[1].y() << "), ("
         << uv[2].x() << ", " << uv[2].y() << ") m";
    throw InputError(text.str());
  }
  return 0.5 * twice_area;
}

} // namespace

HingeRest hinge_rest(const std::array<Eigen::Vector2d, 3>& first,
                     const std::array<Eigen::Vector2d, 3>& second, double rest_angle) {
  if (!std::isfinite(rest_angle)) {
    throw InputError("bending hinge: rest angle " + std::to_string(rest_angle) +
                     " rad must be finite");
  }
  const double area_sum = rest_area(first, "first") + rest_area(second, "second");
  const double length = 0.5 * ((first[1] - first[0]).norm() + (second[1] - second[0]).norm());

  // Corners: first = (x0, x1, x2), second = (x1, x0, x3).
  const double cot00 = cotangent(first[0], first[1], first[2]);
  const double cot01 = cotangent(first[1], first[2], first[0]);
  const double cot11 = cotangent(second[0], second[1], second[2]);
  const double cot10 = cotangent(second[1], second[2], second[0]);
  Eigen::Vector4d k;
  k << cot01 + cot11, cot00 + cot10, -(cot00 + cot01), -(cot10 + cot11);

  HingeRest rest;
  rest.weight = length * length / area_sum;
  rest.rest_angle = rest_angle;
  const Eigen::Matrix4d kk = k * k.transpose() / area_sum;
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) {
      rest.quadratic.block<3, 3>(3 * i, 3 * j) = kk(i, j) * Matrix3d::Identity();
    }
  }
  return rest;
}

Result<12> bending(BendingModel model, double stiffness, const HingeRest& rest, const Vector12& x,
                   Want want) {
  Result<12> result;
  result.gradient.setZero();
  result.hessian.setZero();
  switch (model.index()) {
  case BendingModel::discrete_shell.index(): {
    const Dihedral d = dihedral(x, want);
    if (d.degenerate) return result;
    const double scale = stiffness * rest.weight;
    const double excess = d.angle - rest.rest_angle;
    result.energy = 0.5 * scale * excess * excess;
    if (want == Want::energy) return result;
    result.gradient = scale * excess * d.gradient;
    if (want == Want::gradient) return result;
    result.hessian = scale * (d.gradient * d.gradient.transpose() + excess * d.hessian);
    return result;
  }
  case BendingModel::quadratic.index(): {
    // Q annihilates translations: positions relative to x0 give the same
    // values without the round-off of large coordinates.
    const Vector12 y = x - x.segment<3>(0).replicate<4, 1>();
    const Vector12 qy = rest.quadratic * y;
    result.energy = 0.5 * stiffness * y.dot(qy);
    if (want == Want::energy) return result;
    result.gradient = stiffness * qy;
    if (want == Want::gradient) return result;
    result.hessian = stiffness * rest.quadratic;
    return result;
  }
  default:
    throw std::logic_error("bending: only the hinge models have hinges (the patch model: "
                           "element/patch_bending.hpp)");
  }
  return result;
}

} // namespace sartor::element
