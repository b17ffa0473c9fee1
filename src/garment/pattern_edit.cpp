#include "garment/pattern_edit.hpp"

#include "common/error.hpp"

#include <cmath>
#include <string>

namespace sartor::garment {

namespace {

double cross2(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

// Points closer than this to an edge (relative to its length) are on it.
constexpr double on_edge = 1e-12;

} // namespace

std::vector<double> mean_value_coordinates(const std::vector<Eigen::Vector2d>& outline,
                                           const Eigen::Vector2d& point) {
  const std::size_t n = outline.size();
  if (n < 3) {
    throw InputError("pattern edit: an outline of " + std::to_string(n) +
                     " points; mean value coordinates need at least three");
  }
  std::vector<double> lambda(n, 0.0);
  std::vector<Eigen::Vector2d> d(n);
  std::vector<double> r(n);
  for (std::size_t i = 0; i < n; ++i) {
    d[i] = outline[i] - point;
    r[i] = d[i].norm();
  }
  // On an edge (corners included): linear interpolation along it.
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t j = (i + 1) % n;
    const Eigen::Vector2d edge = outline[j] - outline[i];
    const double length = edge.norm();
    if (!(length > 0.0)) {
      throw InputError("pattern edit: outline points " + std::to_string(i) + " and " +
                       std::to_string(j) + " coincide");
    }
    const double t = -d[i].dot(edge) / (length * length);
    if (std::abs(cross2(d[i], d[j])) <= on_edge * length * length && t >= 0.0 && t <= 1.0) {
      lambda[i] = 1.0 - t;
      lambda[j] += t;
      return lambda;
    }
  }
  // w_i = (tan(a_{i-1}/2) + tan(a_i/2)) / r_i, a_i the signed angle at the
  // point from d_i to d_{i+1}; tan(a/2) = (d_i x d_j) / (r_i r_j + d_i . d_j).
  std::vector<double> half_tangent(n);
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t j = (i + 1) % n;
    half_tangent[i] = cross2(d[i], d[j]) / (r[i] * r[j] + d[i].dot(d[j]));
  }
  double total = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    lambda[i] = (half_tangent[(i + n - 1) % n] + half_tangent[i]) / r[i];
    total += lambda[i];
  }
  for (double& l : lambda)
    l /= total;
  return lambda;
}

std::vector<Eigen::Vector2d> outline_edit(const std::vector<Eigen::Vector2d>& outline,
                                          const std::vector<Eigen::Vector2d>& delta,
                                          const std::vector<Eigen::Vector2d>& points) {
  if (delta.size() != outline.size()) {
    throw InputError("pattern edit: " + std::to_string(delta.size()) + " changes for " +
                     std::to_string(outline.size()) + " outline points");
  }
  std::vector<Eigen::Vector2d> change(points.size(), Eigen::Vector2d::Zero());
  for (std::size_t p = 0; p < points.size(); ++p) {
    const std::vector<double> lambda = mean_value_coordinates(outline, points[p]);
    for (std::size_t i = 0; i < outline.size(); ++i)
      change[p] += lambda[i] * delta[i];
  }
  return change;
}

std::vector<Eigen::Vector2d> symmetric_edit(const std::vector<Eigen::Vector2d>& delta,
                                            const std::vector<int>& mirror,
                                            const Eigen::Vector2d& axis) {
  if (mirror.size() != delta.size()) {
    throw InputError("pattern edit: " + std::to_string(mirror.size()) + " mirror indices for " +
                     std::to_string(delta.size()) + " outline points");
  }
  const Eigen::Vector2d a = axis.normalized();
  // The reflection about the axis: 2 a a^T - I.
  const Eigen::Matrix2d reflection = 2.0 * a * a.transpose() - Eigen::Matrix2d::Identity();
  std::vector<Eigen::Vector2d> edit = delta;
  for (std::size_t i = 0; i < delta.size(); ++i) {
    const int m = mirror[i];
    if (m < 0) continue;
    if (std::size_t(m) >= delta.size()) {
      throw InputError("pattern edit: mirror index " + std::to_string(m) + " of point " +
                       std::to_string(i) + " is not an outline point");
    }
    edit[std::size_t(m)] += reflection * delta[i];
  }
  return edit;
}

} // namespace sartor::garment
