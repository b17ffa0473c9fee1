#include "element/rest_derivative.hpp"

#include "common/autodiff.hpp"
#include "element/seam.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>

namespace sartor::element {

namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;

// A material point with coordinates of either scalar.
template <class Scalar>
struct Point {
  Scalar u, v;
};

template <class Scalar>
Point<Scalar> minus(const Point<Scalar>& a, const Point<Scalar>& b) {
  return {a.u - b.u, a.v - b.v};
}

template <class Scalar>
Scalar cross2(const Point<Scalar>& a, const Point<Scalar>& b) {
  return a.u * b.v - a.v * b.u;
}

template <class Scalar>
Scalar length(const Point<Scalar>& a) {
  using std::sqrt;
  return sqrt(a.u * a.u + a.v * a.v);
}

// Cotangent of the corner at p of the triangle (p, q, r), as hinge_rest's.
template <class Scalar>
Scalar cotangent(const Point<Scalar>& p, const Point<Scalar>& q, const Point<Scalar>& r) {
  using std::abs;
  const Point<Scalar> a = minus(q, p), b = minus(r, p);
  return (a.u * b.u + a.v * b.v) / abs(cross2(a, b));
}

// hinge_rest's weight |e|^2 / (A1 + A2) and cotangent vector K (its
// quadratic matrix is K K^T / (A1 + A2)), from the corners of
// first = (x0, x1, x2) and second = (x1, x0, x3).
template <class Scalar>
struct HingeGeometry {
  Scalar weight;
  std::array<Scalar, 4> k;
  Scalar area_sum;
};

template <class Scalar>
HingeGeometry<Scalar> hinge_geometry(const std::array<Point<Scalar>, 3>& first,
                                     const std::array<Point<Scalar>, 3>& second) {
  using std::abs;
  const Scalar area_sum =
      0.5 * abs(cross2(minus(first[1], first[0]), minus(first[2], first[0]))) +
      0.5 * abs(cross2(minus(second[1], second[0]), minus(second[2], second[0])));
  const Scalar edge =
      0.5 * (length(minus(first[1], first[0])) + length(minus(second[1], second[0])));
  const Scalar cot00 = cotangent(first[0], first[1], first[2]);
  const Scalar cot01 = cotangent(first[1], first[2], first[0]);
  const Scalar cot11 = cotangent(second[0], second[1], second[2]);
  const Scalar cot10 = cotangent(second[1], second[2], second[0]);
  return {edge * edge / area_sum,
          {cot01 + cot11, cot00 + cot10, -(cot00 + cot01), -(cot10 + cot11)},
          area_sum};
}

// The corners carrying their change.
std::array<Point<AutoDiff>, 3> moving(const std::array<Eigen::Vector2d, 3>& uv,
                                      const std::array<Eigen::Vector2d, 3>& delta) {
  std::array<Point<AutoDiff>, 3> points;
  for (std::size_t i = 0; i < 3; ++i)
    points[i] = {seeded(uv[i].x(), delta[i].x()), seeded(uv[i].y(), delta[i].y())};
  return points;
}

} // namespace

HingeRest hinge_rest_derivative(const std::array<Eigen::Vector2d, 3>& first,
                                const std::array<Eigen::Vector2d, 3>& second,
                                const std::array<Eigen::Vector2d, 3>& delta_first,
                                const std::array<Eigen::Vector2d, 3>& delta_second) {
  const HingeGeometry<AutoDiff> g =
      hinge_geometry(moving(first, delta_first), moving(second, delta_second));
  HingeRest delta;
  delta.weight = derivative_of(g.weight);
  delta.rest_angle = 0.0;
  // d(K K^T / A) = (dK K^T + K dK^T) / A - K K^T dA / A^2.
  const double area = g.area_sum.value(), d_area = derivative_of(g.area_sum);
  for (int i = 0; i < 4; ++i) {
    const double ki = g.k[std::size_t(i)].value(), dki = derivative_of(g.k[std::size_t(i)]);
    for (int j = 0; j < 4; ++j) {
      const double kj = g.k[std::size_t(j)].value(), dkj = derivative_of(g.k[std::size_t(j)]);
      const double d_entry = (dki * kj + ki * dkj) / area - ki * kj * d_area / (area * area);
      delta.quadratic.block<3, 3>(3 * i, 3 * j) = d_entry * Matrix3d::Identity();
    }
  }
  return delta;
}

Vector12 bending_rest_derivative(BendingModel model, double stiffness, const HingeRest& rest,
                                 const HingeRest& delta, const Vector12& x) {
  switch (model.index()) {
  case BendingModel::discrete_shell.index(): {
    // The force k w (theta - theta_rest) grad theta is linear in the weight w > 0.
    const Result<12> force = bending(model, stiffness, rest, x, Want::gradient);
    return (delta.weight / rest.weight) * force.gradient;
  }
  case BendingModel::quadratic.index(): {
    const Vector12 y = x - x.segment<3>(0).replicate<4, 1>();
    return stiffness * delta.quadratic * y;
  }
  default:
    break;
  }
  return bending(model, stiffness, rest, x, Want::gradient).gradient; // throws: not a hinge model
}

Vector36 patch_bending_rest_derivative(const PatchRest& rest, const PatchRestChange& delta,
                                       const Vector36& x) {
  // grad E = A B^T M(s): B the strain rows' derivatives, s = voigt (H^T n) -
  // k_rest, H = sum_i (x_i - x0) w_i^T. A change dw moves H by dH, the strain
  // by voigt (dH^T n) and B by the same terms with dw in place of w.
  Vector36 derivative = Vector36::Zero();
  const Vector3d x0 = x.segment<3>(0);
  const Vector3d e1 = x.segment<3>(3) - x0;
  const Vector3d e2 = x.segment<3>(6) - x0;
  const Vector3d m = e1.cross(e2);
  const double norm = m.norm();
  // A collapsed triangle contributes nothing (patch_bending's test).
  const double longest = std::max({e1.squaredNorm(), e2.squaredNorm(), (e2 - e1).squaredNorm()});
  if (!(norm > 1e-12 * longest)) return derivative;
  const Vector3d n = m / norm;
  const Vector3d voigt(1.0, 1.0, 2.0);
  Matrix3d h = Matrix3d::Zero(), dh = Matrix3d::Zero();
  for (int i = 1; i < 12; ++i) {
    h += (x.segment<3>(3 * i) - x0) * rest.weights.col(i).transpose();
    dh += (x.segment<3>(3 * i) - x0) * delta.weights.col(i).transpose();
  }
  const Vector3d strain = voigt.cwiseProduct(h.transpose() * n) - rest.rest_curvature;
  const Vector3d d_strain = voigt.cwiseProduct(dh.transpose() * n);
  const PatchResponse response = patch_response(rest, strain);
  const Vector3d d_moment = response.tangent * d_strain;

  Eigen::Matrix<double, 3, 9> dm;
  const auto cross = [](const Vector3d& v) {
    Matrix3d c;
    c << 0.0, -v.z(), v.y(), v.z(), 0.0, -v.x(), -v.y(), v.x(), 0.0;
    return c;
  };
  dm.block<3, 3>(0, 0) = cross(e2) - cross(e1);
  dm.block<3, 3>(0, 3) = -cross(e2);
  dm.block<3, 3>(0, 6) = cross(e1);
  const Eigen::Matrix<double, 3, 9> dn = (Matrix3d::Identity() - n * n.transpose()) * dm / norm;
  // B and its change dB (3 x 36).
  Eigen::Matrix<double, 3, 36> b, db;
  for (int i = 0; i < 12; ++i) {
    b.block<3, 3>(0, 3 * i) = voigt.cwiseProduct(rest.weights.col(i)) * n.transpose();
    db.block<3, 3>(0, 3 * i) = voigt.cwiseProduct(delta.weights.col(i)) * n.transpose();
  }
  b.block<3, 9>(0, 0) += voigt.asDiagonal() * h.transpose() * dn;
  db.block<3, 9>(0, 0) += voigt.asDiagonal() * dh.transpose() * dn;
  derivative = delta.area * b.transpose() * response.moment +
               rest.area * (db.transpose() * response.moment + b.transpose() * d_moment);
  return derivative;
}

Eigen::Matrix<double, 6, 1>
seam_vertex_vertex_rest_derivative(double delta_stiffness, const Eigen::Matrix<double, 6, 1>& x) {
  // The force k (g, -g), g = x_a - x_b, is linear in k.
  return seam_vertex_vertex(delta_stiffness, x, Want::gradient).gradient;
}

Eigen::Matrix<double, 9, 1> seam_vertex_edge_rest_derivative(double stiffness, double s,
                                                             double delta_stiffness, double delta_s,
                                                             const Eigen::Matrix<double, 9, 1>& x) {
  // Force k w_i g with weights w = (1, -(1 - s), -s) and gap g = sum w_i x_i:
  // dw = (0, ds, -ds), dg = ds (x_b - x_c).
  const Vector3d weights(1.0, -(1.0 - s), -s);
  const Vector3d d_weights(0.0, delta_s, -delta_s);
  const Vector3d gap =
      x.segment<3>(0) + weights(1) * x.segment<3>(3) + weights(2) * x.segment<3>(6);
  const Vector3d d_gap = delta_s * (x.segment<3>(3) - x.segment<3>(6));
  Eigen::Matrix<double, 9, 1> derivative;
  for (int i = 0; i < 3; ++i) {
    derivative.segment<3>(3 * i) =
        delta_stiffness * weights(i) * gap + stiffness * (d_weights(i) * gap + weights(i) * d_gap);
  }
  return derivative;
}

} // namespace sartor::element
