#include "element/point_triangle.hpp"

#include "element/penalty_law.hpp"

#include <Eigen/Geometry>
#include <unsupported/Eigen/AutoDiff>

#include <algorithm>
#include <cmath>

namespace sartor::element {

namespace {

using Eigen::Vector3d;

// The closest point on segment (a, b): its parameter along a -> b, clamped.
double segment_parameter(const Vector3d& p, const Vector3d& a, const Vector3d& b) {
  const Vector3d e = b - a;
  const double length2 = e.squaredNorm();
  if (length2 == 0.0) return 0.0;
  return std::clamp((p - a).dot(e) / length2, 0.0, 1.0);
}

// The nearest of the three edges, for a triangle without a normal.
ClosestPoint nearest_edge(const Vector3d& p, const Vector3d& a, const Vector3d& b,
                          const Vector3d& c) {
  ClosestPoint best;
  best.distance = INFINITY;
  const Vector3d corners[3] = {a, b, c};
  const TriangleFeature edges[3] = {TriangleFeature::edge_ab, TriangleFeature::edge_bc,
                                    TriangleFeature::edge_ca};
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3;
    const double t = segment_parameter(p, corners[i], corners[j]);
    const double d = (p - ((1.0 - t) * corners[i] + t * corners[j])).norm();
    if (d >= best.distance) continue;
    best.distance = d;
    best.feature = edges[i];
    best.barycentric = Vector3d::Zero();
    best.barycentric[i] = 1.0 - t;
    best.barycentric[j] = t;
  }
  return best;
}

ClosestPoint on_vertex(TriangleFeature feature, int corner, const Vector3d& p, const Vector3d& x) {
  ClosestPoint q;
  q.feature = feature;
  q.barycentric[corner] = 1.0;
  q.distance = (p - x).norm();
  return q;
}

ClosestPoint on_edge(TriangleFeature feature, int from, int to, double t, const Vector3d& p,
                     const Vector3d& x_from, const Vector3d& x_to) {
  ClosestPoint q;
  q.feature = feature;
  q.barycentric[from] = 1.0 - t;
  q.barycentric[to] = t;
  q.distance = (p - ((1.0 - t) * x_from + t * x_to)).norm();
  return q;
}

// The feature's closest point and the distance's gradient (1, -b) (x) u,
// over any scalar: on AutoDiff its derivatives are the distance's Hessian.
template <class S>
Eigen::Matrix<S, 12, 1> distance_gradient(const Eigen::Matrix<S, 12, 1>& x,
                                          TriangleFeature feature) {
  using V = Eigen::Matrix<S, 3, 1>;
  const V p = x.template segment<3>(0);
  const V corner[3] = {x.template segment<3>(3), x.template segment<3>(6),
                       x.template segment<3>(9)};
  S b[3] = {S(0.0), S(0.0), S(0.0)};
  const auto edge = [&](int i, int j) {
    const V e = corner[j] - corner[i];
    const S t = (p - corner[i]).dot(e) / e.squaredNorm();
    b[i] = 1.0 - t;
    b[j] = t;
  };
  switch (feature) {
  case TriangleFeature::face: {
    const V e1 = corner[1] - corner[0], e2 = corner[2] - corner[0], r = p - corner[0];
    const S m11 = e1.dot(e1), m12 = e1.dot(e2), m22 = e2.dot(e2);
    const S r1 = r.dot(e1), r2 = r.dot(e2);
    const S det = m11 * m22 - m12 * m12;
    b[1] = (m22 * r1 - m12 * r2) / det;
    b[2] = (m11 * r2 - m12 * r1) / det;
    b[0] = 1.0 - b[1] - b[2];
    break;
  }
  case TriangleFeature::edge_ab:
    edge(0, 1);
    break;
  case TriangleFeature::edge_bc:
    edge(1, 2);
    break;
  case TriangleFeature::edge_ca:
    edge(2, 0);
    break;
  case TriangleFeature::vertex_a:
    b[0] = S(1.0);
    break;
  case TriangleFeature::vertex_b:
    b[1] = S(1.0);
    break;
  case TriangleFeature::vertex_c:
    b[2] = S(1.0);
    break;
  }
  const V r = p - (b[0] * corner[0] + b[1] * corner[1] + b[2] * corner[2]);
  const V u = r / r.norm();
  Eigen::Matrix<S, 12, 1> gradient;
  gradient.template segment<3>(0) = u;
  for (int i = 0; i < 3; ++i)
    gradient.template segment<3>(3 + 3 * i) = -b[i] * u;
  return gradient;
}

Eigen::Matrix<double, 12, 12> distance_hessian(const Vector12& x, TriangleFeature feature) {
  using Dual = Eigen::AutoDiffScalar<Vector12>;
  Eigen::Matrix<Dual, 12, 1> seeded;
  for (int i = 0; i < 12; ++i)
    seeded[i] = Dual(x[i], 12, i);
  const Eigen::Matrix<Dual, 12, 1> gradient = distance_gradient<Dual>(seeded, feature);
  Eigen::Matrix<double, 12, 12> hessian;
  for (int i = 0; i < 12; ++i)
    hessian.row(i) = gradient[i].derivatives().transpose();
  return 0.5 * (hessian + hessian.transpose());
}

} // namespace

ClosestPoint closest_point_on_triangle(const Vector3d& p, const Vector3d& a, const Vector3d& b,
                                       const Vector3d& c) {
  const Vector3d ab = b - a, ac = c - a, ap = p - a;
  if (ab.cross(ac).squaredNorm() == 0.0) return nearest_edge(p, a, b, c);
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0.0 && d2 <= 0.0) return on_vertex(TriangleFeature::vertex_a, 0, p, a);
  const Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0.0 && d4 <= d3) return on_vertex(TriangleFeature::vertex_b, 1, p, b);
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0)
    return on_edge(TriangleFeature::edge_ab, 0, 1, d1 / (d1 - d3), p, a, b);
  const Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0.0 && d5 <= d6) return on_vertex(TriangleFeature::vertex_c, 2, p, c);
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0)
    return on_edge(TriangleFeature::edge_ca, 0, 2, d2 / (d2 - d6), p, a, c);
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0)
    return on_edge(TriangleFeature::edge_bc, 1, 2, (d4 - d3) / ((d4 - d3) + (d5 - d6)), p, b, c);
  const double denominator = 1.0 / (va + vb + vc);
  ClosestPoint q;
  q.feature = TriangleFeature::face;
  q.barycentric = Vector3d(va, vb, vc) * denominator;
  q.distance = (p - (q.barycentric[0] * a + q.barycentric[1] * b + q.barycentric[2] * c)).norm();
  return q;
}

Result<12> point_triangle_penalty(double stiffness, double offset, const Vector12& x, Want want,
                                  bool exact, double band) {
  Result<12> result;
  result.gradient.setZero();
  result.hessian.setZero();
  const ClosestPoint q =
      closest_point_on_triangle(x.segment<3>(0), x.segment<3>(3), x.segment<3>(6), x.segment<3>(9));
  const double depth = offset - q.distance; // > 0 inside the offset layer
  if (depth <= 0.0 || q.distance == 0.0) return result;
  const PenaltyLaw law = penalty_law(stiffness, band, depth);
  result.energy = law.energy;
  if (want == Want::energy) return result;
  const Vector12 slope = distance_gradient<double>(x, q.feature);
  result.gradient = -law.force * slope;
  if (want == Want::gradient) return result;
  result.hessian =
      law.stiffness * slope * slope.transpose() - law.force * distance_hessian(x, q.feature);
  if (!exact) project_to_psd<12>(result.hessian);
  return result;
}

} // namespace sartor::element
