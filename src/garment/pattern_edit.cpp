#include "garment/pattern_edit.hpp"

#include "common/error.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <optional>
#include <sstream>
#include <string>

namespace sartor::garment {

namespace {

double cross2(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

// Points closer than this to an edge (relative to its length) are on it.
constexpr double on_edge = 1e-12;

void check_outline(const std::vector<Eigen::Vector2d>& outline) {
  const std::size_t n = outline.size();
  if (n < 3) {
    throw InputError("pattern edit: an outline of " + std::to_string(n) +
                     " points; mean value coordinates need at least three");
  }
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t j = (i + 1) % n;
    if (!((outline[j] - outline[i]).norm() > 0.0)) {
      throw InputError("pattern edit: outline points " + std::to_string(i) + " and " +
                       std::to_string(j) + " coincide");
    }
  }
}

// For a point on an edge of the outline (corners included): the linear
// interpolation along that edge; nothing for any other point.
std::optional<std::vector<double>> edge_interpolation(const std::vector<Eigen::Vector2d>& outline,
                                                      const Eigen::Vector2d& point) {
  const std::size_t n = outline.size();
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t j = (i + 1) % n;
    const Eigen::Vector2d edge = outline[j] - outline[i];
    const Eigen::Vector2d from_i = outline[i] - point;
    const Eigen::Vector2d from_j = outline[j] - point;
    const double length = edge.norm();
    const double t = -from_i.dot(edge) / (length * length);
    if (std::abs(cross2(from_i, from_j)) <= on_edge * length * length && t >= 0.0 && t <= 1.0) {
      std::vector<double> lambda(n, 0.0);
      lambda[i] = 1.0 - t;
      lambda[j] += t;
      return lambda;
    }
  }
  return std::nullopt;
}

// Even-odd rule: a ray from the point towards +x crosses the outline an odd
// number of times when the point is inside.
bool inside(const std::vector<Eigen::Vector2d>& outline, const Eigen::Vector2d& point) {
  bool odd = false;
  for (std::size_t i = 0; i < outline.size(); ++i) {
    const Eigen::Vector2d& a = outline[i];
    const Eigen::Vector2d& b = outline[(i + 1) % outline.size()];
    if ((a.y() > point.y()) == (b.y() > point.y())) continue;
    const double crossing_x = a.x() + (point.y() - a.y()) * (b.x() - a.x()) / (b.y() - a.y());
    if (point.x() < crossing_x) odd = !odd;
  }
  return odd;
}

std::string coordinates_text(const Eigen::Vector2d& point) {
  std::ostringstream text;
  text << "(" << point.x() << ", " << point.y() << ")";
  return text.str();
}

// A gap between consecutive directions from the point to outline points,
// counter-clockwise: no outline point lies inside it, so the rays through it
// all first meet the same edge.
struct Gap {
  std::size_t from, to; // the outline points at its ends
  double width;         // radians
  Eigen::Vector2d bisector;
  std::size_t first_edge = 0; // by its first point; only where first_distance is finite
  double first_distance = std::numeric_limits<double>::infinity(); // along the bisector
};

// The gaps between the directions `direction` (radians, in [-pi, pi]) of the
// outline points, in counter-clockwise order; `gap_from[i]` is the index of
// the gap that starts at outline point i.
std::vector<Gap> gaps_between(const std::vector<double>& direction,
                              std::vector<std::size_t>& gap_from) {
  const std::size_t n = direction.size();
  std::vector<std::size_t> by_direction(n);
  std::iota(by_direction.begin(), by_direction.end(), std::size_t(0));
  std::sort(by_direction.begin(), by_direction.end(),
            [&](std::size_t a, std::size_t b) { return direction[a] < direction[b]; });
  std::vector<Gap> gaps(n);
  gap_from.resize(n);
  for (std::size_t k = 0; k < n; ++k) {
    Gap& gap = gaps[k];
    gap.from = by_direction[k];
    gap.to = by_direction[(k + 1) % n];
    gap.width = direction[gap.to] - direction[gap.from] + (k + 1 == n ? 2.0 * M_PI : 0.0);
    const double bisector = direction[gap.from] + 0.5 * gap.width;
    gap.bisector = Eigen::Vector2d(std::cos(bisector), std::sin(bisector));
    gap_from[gap.from] = k;
  }
  return gaps;
}

// Finds each gap's first edge along its bisector. An edge can only be met in
// the gaps its two points' directions enclose (the shorter way round, as an
// edge not through the point spans less than half a turn), so each edge is
// tried there only: about one gap per edge where the outline is seen whole.
void find_first_edges(const std::vector<Eigen::Vector2d>& d, const std::vector<double>& direction,
                      const std::vector<std::size_t>& gap_from, std::vector<Gap>& gaps) {
  const std::size_t n = d.size();
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t j = (i + 1) % n;
    double span = direction[j] - direction[i];
    if (span > M_PI) span -= 2.0 * M_PI;
    if (span <= -M_PI) span += 2.0 * M_PI;
    if (span == 0.0) continue; // the edge points at the point: seen edge-on
    const Eigen::Vector2d edge = d[j] - d[i];
    const double twice_area = cross2(d[i], d[j]);
    const std::size_t end = gap_from[span > 0.0 ? j : i];
    for (std::size_t k = gap_from[span > 0.0 ? i : j]; k != end; k = (k + 1) % n) {
      // distance * bisector = d_i + t edge; crossing with the edge drops t.
      const double distance = twice_area / cross2(gaps[k].bisector, edge);
      if (distance > 0.0 && distance < gaps[k].first_distance) {
        gaps[k].first_distance = distance;
        gaps[k].first_edge = i;
      }
    }
  }
}

// Where on edge i (from d[i] to d[i+1]) the line through the origin along
// `ray` meets it, as the parameter t of (1 - t) d[i] + t d[i+1].
double edge_parameter(const std::vector<Eigen::Vector2d>& d, std::size_t i,
                      const Eigen::Vector2d& ray) {
  const double side_i = cross2(ray, d[i]);
  const double side_j = cross2(ray, d[(i + 1) % d.size()]);
  // Parallel only when the ray's gap has vanishing width; any t then does.
  if (side_i == side_j) return 0.0;
  return std::clamp(side_i / (side_i - side_j), 0.0, 1.0);
}

// Adds to `lambda` the mean value weights of the piece of edge i seen between
// the rays `from` and `to` (angle `angle` apart, counter-clockwise): the
// piece from Q_from to Q_to gives tan(angle/2) / |Q| to each end Q, which
// passes it to the edge's two points linearly. A window edge of the
// visibility polygon (along a ray) spans no angle and adds nothing.
void add_visible_piece(const std::vector<Eigen::Vector2d>& d, std::size_t i,
                       const Eigen::Vector2d& from, const Eigen::Vector2d& to, double angle,
                       std::vector<double>& lambda) {
  const std::size_t j = (i + 1) % d.size();
  const double half_tangent = std::tan(0.5 * angle);
  for (const Eigen::Vector2d& ray : {from, to}) {
    const double t = edge_parameter(d, i, ray);
    const double weight = half_tangent / (d[i] + t * (d[j] - d[i])).norm();
    lambda[i] += (1.0 - t) * weight;
    lambda[j] += t * weight;
  }
}

} // namespace

std::vector<double> mean_value_coordinates(const std::vector<Eigen::Vector2d>& outline,
                                           const Eigen::Vector2d& point) {
  check_outline(outline);
  if (std::optional<std::vector<double>> on_outline = edge_interpolation(outline, point))
    return *on_outline;
  const std::size_t n = outline.size();
  std::vector<Eigen::Vector2d> d(n);
  std::vector<double> r(n);
  for (std::size_t i = 0; i < n; ++i) {
    d[i] = outline[i] - point;
    r[i] = d[i].norm();
  }
  // w_i = (tan(a_{i-1}/2) + tan(a_i/2)) / r_i, a_i the signed angle at the
  // point from d_i to d_{i+1}; tan(a/2) = (d_i x d_j) / (r_i r_j + d_i . d_j).
  std::vector<double> half_tangent(n);
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t j = (i + 1) % n;
    half_tangent[i] = cross2(d[i], d[j]) / (r[i] * r[j] + d[i].dot(d[j]));
  }
  std::vector<double> lambda(n);
  double total = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    lambda[i] = (half_tangent[(i + n - 1) % n] + half_tangent[i]) / r[i];
    total += lambda[i];
  }
  for (double& l : lambda)
    l /= total;
  return lambda;
}

// The outline points' directions from the point cut the full turn into gaps;
// the first edges met in the gaps, clipped to them, are the visible outline:
// the visibility polygon's edges but its windows. Their mean value weights
// are the coordinates: the integral over the turn of (the first hit's
// interpolation) / (its distance), continuous in the point. Where two
// directions nearly coincide the gap between them, whichever edge round-off
// picks there, weighs nearly nothing.
std::vector<double> positive_mean_value_coordinates(const std::vector<Eigen::Vector2d>& outline,
                                                    const Eigen::Vector2d& point) {
  check_outline(outline);
  if (std::optional<std::vector<double>> on_outline = edge_interpolation(outline, point))
    return *on_outline;
  if (!inside(outline, point)) {
    throw InputError("pattern edit: point " + coordinates_text(point) +
                     " is outside the panel's outline");
  }
  const std::size_t n = outline.size();
  std::vector<Eigen::Vector2d> d(n);
  std::vector<double> direction(n);
  for (std::size_t i = 0; i < n; ++i) {
    d[i] = outline[i] - point;
    direction[i] = std::atan2(d[i].y(), d[i].x());
  }
  std::vector<std::size_t> gap_from;
  std::vector<Gap> gaps = gaps_between(direction, gap_from);
  find_first_edges(d, direction, gap_from, gaps);
  std::vector<double> lambda(n, 0.0);
  for (const Gap& gap : gaps) {
    // No edge is found only where round-off leaves a gap of vanishing width.
    if (gap.width > 0.0 && std::isfinite(gap.first_distance))
      add_visible_piece(d, gap.first_edge, d[gap.from], d[gap.to], gap.width, lambda);
  }
  const double total = std::accumulate(lambda.begin(), lambda.end(), 0.0);
  for (double& l : lambda)
    l /= total;
  return lambda;
}

std::vector<double> interior_coordinates(InteriorCoordinates coordinates,
                                         const std::vector<Eigen::Vector2d>& outline,
                                         const Eigen::Vector2d& point) {
  switch (coordinates) {
  case InteriorCoordinates::mean_value:
    return mean_value_coordinates(outline, point);
  case InteriorCoordinates::positive_mean_value:
    return positive_mean_value_coordinates(outline, point);
  }
  throw InputError("pattern edit: unknown kind of interior coordinates");
}

std::vector<double> nearest_outline_coordinates(const std::vector<Eigen::Vector2d>& outline,
                                                const Eigen::Vector2d& point) {
  check_outline(outline);
  const std::size_t n = outline.size();
  std::size_t nearest = 0;
  double nearest_t = 0.0, nearest_distance = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector2d edge = outline[(i + 1) % n] - outline[i];
    const double t = std::clamp((point - outline[i]).dot(edge) / edge.squaredNorm(), 0.0, 1.0);
    const double distance = (outline[i] + t * edge - point).norm();
    if (distance < nearest_distance) {
      nearest = i;
      nearest_t = t;
      nearest_distance = distance;
    }
  }
  std::vector<double> lambda(n, 0.0);
  lambda[nearest] = 1.0 - nearest_t;
  lambda[(nearest + 1) % n] += nearest_t;
  return lambda;
}

std::vector<double> panel_coordinates(InteriorCoordinates coordinates,
                                      const std::vector<Eigen::Vector2d>& outline,
                                      const Eigen::Vector2d& point) {
  if (edge_interpolation(outline, point) || inside(outline, point))
    return interior_coordinates(coordinates, outline, point);
  return nearest_outline_coordinates(outline, point);
}

std::vector<Eigen::Vector2d> outline_edit(const std::vector<Eigen::Vector2d>& outline,
                                          const std::vector<Eigen::Vector2d>& delta,
                                          const std::vector<Eigen::Vector2d>& points,
                                          InteriorCoordinates coordinates) {
  if (delta.size() != outline.size()) {
    throw InputError("pattern edit: " + std::to_string(delta.size()) + " changes for " +
                     std::to_string(outline.size()) + " outline points");
  }
  std::vector<Eigen::Vector2d> change(points.size(), Eigen::Vector2d::Zero());
  for (std::size_t p = 0; p < points.size(); ++p) {
    const std::vector<double> lambda = interior_coordinates(coordinates, outline, points[p]);
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
