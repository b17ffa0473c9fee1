#include "mesh/remesh.hpp"

#include "common/error.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <optional>
#include <stdexcept>
#include <unordered_map>
#include <unordered_set>

namespace sartor {

namespace {

constexpr double pi = 3.14159265358979323846;
// A flip needs the angles facing the edge to exceed pi by this much, rad: far
// above atan2's round-off (1e-15), so that no flip hinges on it and the
// co-circular squares of a grid stay as they are.
constexpr double kDelaunayMargin = 1e-9;
// A flipped triangle's det [du dv] must exceed this fraction of its squared
// longest side: 100 times the bound validate() checks, far above round-off.
constexpr double kFlatness = 1e-12;
// An edge's ends whose (u, v) in its two triangles differ by more than this
// fraction of its length lie on a seam: a seam jumps by a circumference,
// round-off by 1e-16.
constexpr double kSameCoordinate = 1e-9;
// Barycentric weights down to this count as inside a triangle.
constexpr double kInside = 1e-12;

double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

// Twice the signed area of (a, b, c): positive when they run counter-clockwise.
double orientation(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  return cross(b - a, c - a);
}

// ---- Delaunay smoothing -------------------------------------------------

using EdgeKey = std::uint64_t;

EdgeKey edge_key(int a, int b) {
  const auto low = static_cast<std::uint32_t>(std::min(a, b));
  const auto high = static_cast<std::uint32_t>(std::max(a, b));
  return EdgeKey{low} << 32 | high;
}

// The triangles of every edge: one, or two (the second -1 when one).
using EdgeTriangles = std::unordered_map<EdgeKey, std::array<int, 2>>;

EdgeTriangles edge_triangles(const TriangleMesh& mesh) {
  EdgeTriangles edges;
  edges.reserve(3 * mesh.triangle_count());
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    const auto& corners = mesh.triangles[t];
    for (std::size_t c = 0; c < 3; ++c) {
      const auto [entry, added] = edges.try_emplace(edge_key(corners[c], corners[(c + 1) % 3]),
                                                    std::array<int, 2>{int(t), -1});
      if (!added) entry->second[1] = int(t);
    }
  }
  return edges;
}

std::unordered_set<EdgeKey> crease_keys(const TriangleMesh& mesh) {
  std::unordered_set<EdgeKey> keys;
  for (const CreaseEdge& crease : mesh.creases)
    keys.insert(edge_key(crease.a, crease.b));
  return keys;
}

// An interior edge v0-v1 with its triangles t0 = (v0, v1, v2) and
// t1 = (v1, v0, v3): v0, v3, v1, v2 run counter-clockwise around the quad
// when both triangles do. uv[i] is vertex v[i]'s (u, v), from t0 for v0, v1,
// v2 and from t1 for v3; second_uv is t1's own (u, v) of v0 and v1.
struct Quad {
  std::array<int, 2> triangles{};
  std::array<int, 4> v{};
  std::array<Eigen::Vector2d, 4> uv;
  std::array<Eigen::Vector2d, 2> second_uv;
};

// The corner of triangle t whose side runs from a to b; -1 if none does.
int corner_running(const TriangleMesh& mesh, int t, int a, int b) {
  const auto& corners = mesh.triangles[std::size_t(t)];
  for (int c = 0; c < 3; ++c)
    if (corners[std::size_t(c)] == a && corners[std::size_t((c + 1) % 3)] == b) return c;
  return -1;
}

// The quad of the edge a-b and its triangles; none when both triangles run
// the edge the same way (a mesh not consistently oriented there).
std::optional<Quad> quad_of(const TriangleMesh& mesh, int a, int b, std::array<int, 2> triangles) {
  const int forward = corner_running(mesh, triangles[0], a, b);
  const int c0 = forward >= 0 ? forward : corner_running(mesh, triangles[0], b, a);
  const auto& first = mesh.triangles[std::size_t(triangles[0])];
  const auto& first_uv = mesh.material_uv[std::size_t(triangles[0])];
  const std::size_t i0 = std::size_t(c0), i1 = (i0 + 1) % 3, i2 = (i0 + 2) % 3;
  const int c1 = corner_running(mesh, triangles[1], first[i1], first[i0]);
  if (c1 < 0) return std::nullopt;
  const auto& second = mesh.triangles[std::size_t(triangles[1])];
  const auto& second_uv = mesh.material_uv[std::size_t(triangles[1])];
  const std::size_t j0 = std::size_t(c1), j1 = (j0 + 1) % 3, j2 = (j0 + 2) % 3;
  Quad quad;
  quad.triangles = triangles;
  quad.v = {first[i0], first[i1], first[i2], second[j2]};
  quad.uv = {first_uv[i0], first_uv[i1], first_uv[i2], second_uv[j2]};
  quad.second_uv = {second_uv[j1], second_uv[j0]};
  return quad;
}

// The two triangles give the edge's ends different (u, v): a closed tube's
// seam, which a flip would tear.
bool on_seam(const Quad& q) {
  const double tolerance = kSameCoordinate * (q.uv[1] - q.uv[0]).norm();
  return (q.second_uv[0] - q.uv[0]).norm() > tolerance ||
         (q.second_uv[1] - q.uv[1]).norm() > tolerance;
}

bool same_material(const TriangleMesh& mesh, const Quad& q) {
  return mesh.material_ids.empty() || mesh.material_ids[std::size_t(q.triangles[0])] ==
                                          mesh.material_ids[std::size_t(q.triangles[1])];
}

// Counter-clockwise with a material area well above round-off.
bool solid_counter_clockwise(const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                             const Eigen::Vector2d& c) {
  const double longest =
      std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()});
  return orientation(a, b, c) > kFlatness * longest;
}

// Both triangles are counter-clockwise in (u, v) (a folded pair calls for a
// new mesh, not a flip) and so are the flipped (v0, v3, v2) and (v3, v1, v2):
// the quad is strictly convex. An edge that fails the Delaunay test has a
// convex quad in exact arithmetic; the check keeps round-off in thin
// triangles from making a flip that validate() would reject.
bool flip_keeps_orientation(const Quad& q) {
  const auto& uv = q.uv;
  return orientation(uv[0], uv[1], uv[2]) > 0.0 && orientation(uv[1], uv[0], uv[3]) > 0.0 &&
         solid_counter_clockwise(uv[0], uv[3], uv[2]) &&
         solid_counter_clockwise(uv[3], uv[1], uv[2]);
}

bool flippable(const TriangleMesh& mesh, const EdgeTriangles& edges,
               const std::unordered_set<EdgeKey>& creases, const Quad& q) {
  return creases.count(edge_key(q.v[0], q.v[1])) == 0 && same_material(mesh, q) && !on_seam(q) &&
         flip_keeps_orientation(q) && edges.count(edge_key(q.v[2], q.v[3])) == 0;
}

// The angle at `apex` facing the side a-b, rad in [0, pi].
double angle_at(const Eigen::Vector2d& apex, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const Eigen::Vector2d to_a = a - apex, to_b = b - apex;
  return std::atan2(std::abs(cross(to_a, to_b)), to_a.dot(to_b));
}

// Lawson's test: v3 lies inside the circumcircle of (v0, v1, v2) exactly when
// the angles facing v0-v1 sum to more than pi; here by more than the margin.
bool violates_delaunay(const Quad& q) {
  const auto& uv = q.uv;
  return angle_at(uv[2], uv[0], uv[1]) + angle_at(uv[3], uv[1], uv[0]) > pi + kDelaunayMargin;
}

void replace_triangle(EdgeTriangles& edges, int a, int b, int from, int to) {
  auto& triangles = edges.at(edge_key(a, b));
  std::replace(triangles.begin(), triangles.end(), from, to);
}

// Replaces t0, t1 by (v0, v3, v2), (v3, v1, v2) in the same slots (material
// ids stay): the edge v0-v1 becomes v2-v3.
void flip(TriangleMesh& mesh, EdgeTriangles& edges, const Quad& q) {
  const auto [t0, t1] = q.triangles;
  const auto [v0, v1, v2, v3] = q.v;
  mesh.triangles[std::size_t(t0)] = {v0, v3, v2};
  mesh.material_uv[std::size_t(t0)] = {q.uv[0], q.uv[3], q.uv[2]};
  mesh.triangles[std::size_t(t1)] = {v3, v1, v2};
  mesh.material_uv[std::size_t(t1)] = {q.uv[3], q.uv[1], q.uv[2]};
  edges.erase(edge_key(v0, v1));
  edges.emplace(edge_key(v2, v3), std::array<int, 2>{t0, t1});
  replace_triangle(edges, v0, v3, t1, t0);
  replace_triangle(edges, v1, v2, t0, t1);
}

// ---- Point location -----------------------------------------------------

Eigen::Vector3d barycentric_weights(const std::array<Eigen::Vector2d, 3>& uv,
                                    const Eigen::Vector2d& p) {
  const double area = orientation(uv[0], uv[1], uv[2]);
  const double w1 = orientation(uv[0], p, uv[2]) / area;
  const double w2 = orientation(uv[0], uv[1], p) / area;
  return {1.0 - w1 - w2, w1, w2};
}

// A triangle for a point: its weights there (or at its point closest to p
// when p is outside) and the distance from p, m.
struct Candidate {
  BarycentricLocation at;
  double distance = std::numeric_limits<double>::infinity();
};

// Outside, the closest point lies on the nearest side.
Candidate candidate(const TriangleMesh& mesh, int t, const Eigen::Vector2d& p) {
  const auto& uv = mesh.material_uv[std::size_t(t)];
  Candidate found{{t, barycentric_weights(uv, p)}, 0.0};
  if (found.at.weights.minCoeff() >= -kInside) return found;
  found.distance = std::numeric_limits<double>::infinity();
  for (Eigen::Index side = 0; side < 3; ++side) {
    const Eigen::Index next = (side + 1) % 3;
    const Eigen::Vector2d& a = uv[std::size_t(side)];
    const Eigen::Vector2d along = uv[std::size_t(next)] - a;
    const double s = std::clamp((p - a).dot(along) / along.squaredNorm(), 0.0, 1.0);
    const double distance = (a + s * along - p).norm();
    if (distance >= found.distance) continue;
    found.distance = distance;
    found.at.weights.setZero();
    found.at.weights[side] = 1.0 - s;
    found.at.weights[next] = s;
  }
  return found;
}

// The triangles of one group bucketed in a uniform grid over their (u, v)
// bounding box, about one triangle per cell. A query searches rings of cells
// around its own until no unvisited cell can hold a nearer triangle.
class TriangleGrid {
public:
  TriangleGrid(const TriangleMesh& mesh, const std::vector<int>& triangles) : mesh_(mesh) {
    size_cells(triangles);
    fill_cells(triangles);
  }

  BarycentricLocation locate(const Eigen::Vector2d& p) const {
    const std::array<int, 2> centre = cell_of(p);
    Candidate best;
    for (int ring = 0;; ++ring) {
      for_each_cell_in_ring(centre, ring, [&](std::size_t cell) {
        for (int e = start_[cell]; e < start_[cell + 1]; ++e) {
          const Candidate found = candidate(mesh_, entries_[std::size_t(e)], p);
          if (found.distance < best.distance) best = found;
        }
      });
      if (best.distance <= distance_beyond(p, centre, ring)) return best.at;
    }
  }

private:
  void size_cells(const std::vector<int>& triangles) {
    Eigen::AlignedBox2d box;
    for (int t : triangles)
      for (const Eigen::Vector2d& uv : mesh_.material_uv[std::size_t(t)])
        box.extend(uv);
    origin_ = box.min();
    const Eigen::Vector2d sizes = box.sizes();
    const double count = double(triangles.size());
    // At most `count` cells along the box, however thin it is.
    cell_size_ = std::max(std::sqrt(sizes.prod() / count), sizes.maxCoeff() / count);
    columns_ = std::max(1, static_cast<int>(std::ceil(sizes.x() / cell_size_)));
    rows_ = std::max(1, static_cast<int>(std::ceil(sizes.y() / cell_size_)));
  }

  // Each triangle in every cell its bounding box meets: counted, then placed.
  void fill_cells(const std::vector<int>& triangles) {
    start_.assign(std::size_t(columns_) * std::size_t(rows_) + 1, 0);
    for (int t : triangles)
      for_each_cell_of(t, [&](std::size_t cell) { ++start_[cell + 1]; });
    for (std::size_t cell = 1; cell < start_.size(); ++cell)
      start_[cell] += start_[cell - 1];
    entries_.resize(std::size_t(start_.back()));
    std::vector<int> filled(start_.begin(), start_.end() - 1);
    for (int t : triangles)
      for_each_cell_of(t, [&](std::size_t cell) { entries_[std::size_t(filled[cell]++)] = t; });
  }

  template <class Visit>
  void for_each_cell_of(int t, Visit visit) const {
    Eigen::AlignedBox2d box;
    for (const Eigen::Vector2d& uv : mesh_.material_uv[std::size_t(t)])
      box.extend(uv);
    const std::array<int, 2> low = cell_of(box.min()), high = cell_of(box.max());
    for (int i = low[0]; i <= high[0]; ++i)
      for (int j = low[1]; j <= high[1]; ++j)
        visit(cell_index(i, j));
  }

  // The cell holding p, or the nearest cell for p outside the grid.
  std::array<int, 2> cell_of(const Eigen::Vector2d& p) const {
    const Eigen::Vector2d scaled = (p - origin_) / cell_size_;
    const auto index = [](double x, int count) {
      return static_cast<int>(std::clamp(std::floor(x), 0.0, double(count - 1)));
    };
    return {index(scaled.x(), columns_), index(scaled.y(), rows_)};
  }

  std::size_t cell_index(int i, int j) const {
    return std::size_t(i) * std::size_t(rows_) + std::size_t(j);
  }

  // The grid's cells at Chebyshev distance `ring` from `centre`.
  template <class Visit>
  void for_each_cell_in_ring(const std::array<int, 2>& centre, int ring, Visit visit) const {
    const auto [ci, cj] = centre;
    if (ring == 0) return visit(cell_index(ci, cj));
    for (int i = std::max(0, ci - ring); i <= std::min(columns_ - 1, ci + ring); ++i)
      for (int j : {cj - ring, cj + ring})
        if (j >= 0 && j < rows_) visit(cell_index(i, j));
    for (int j = std::max(0, cj - ring + 1); j <= std::min(rows_ - 1, cj + ring - 1); ++j)
      for (int i : {ci - ring, ci + ring})
        if (i >= 0 && i < columns_) visit(cell_index(i, j));
  }

  // The distance from p to the cells [i0, i1] x [j0, j1], m.
  double distance_to_cells(const Eigen::Vector2d& p, int i0, int i1, int j0, int j1) const {
    const Eigen::Vector2d low = origin_ + cell_size_ * Eigen::Vector2d(i0, j0);
    const Eigen::Vector2d high = origin_ + cell_size_ * Eigen::Vector2d(i1 + 1, j1 + 1);
    return (p - p.cwiseMax(low).cwiseMin(high)).norm();
  }

  // A lower bound of the distance from p to every cell not yet visited (those
  // outside the rings up to `ring`); infinite when all are visited.
  double distance_beyond(const Eigen::Vector2d& p, const std::array<int, 2>& centre,
                         int ring) const {
    const int last_column = columns_ - 1, last_row = rows_ - 1;
    const int left = centre[0] - ring - 1, right = centre[0] + ring + 1;
    const int below = centre[1] - ring - 1, above = centre[1] + ring + 1;
    double bound = std::numeric_limits<double>::infinity();
    if (left >= 0) bound = std::min(bound, distance_to_cells(p, 0, left, 0, last_row));
    if (right <= last_column)
      bound = std::min(bound, distance_to_cells(p, right, last_column, 0, last_row));
    if (below >= 0) bound = std::min(bound, distance_to_cells(p, 0, last_column, 0, below));
    if (above <= last_row)
      bound = std::min(bound, distance_to_cells(p, 0, last_column, above, last_row));
    return bound;
  }

  const TriangleMesh& mesh_;
  Eigen::Vector2d origin_ = Eigen::Vector2d::Zero();
  double cell_size_ = 1.0;
  int columns_ = 1, rows_ = 1;
  std::vector<int> start_;   // entries of cell c: [start_[c], start_[c + 1])
  std::vector<int> entries_; // triangle indices
};

// Triangles by material id, or all under 0 when not `grouped`.
std::map<int, std::vector<int>> triangles_by_group(const TriangleMesh& mesh, bool grouped) {
  std::map<int, std::vector<int>> groups;
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    const int group = grouped && !mesh.material_ids.empty() ? mesh.material_ids[t] : 0;
    groups[group].push_back(int(t));
  }
  return groups;
}

void check_queries(const std::vector<Eigen::Vector2d>& points,
                   const std::vector<int>& point_groups) {
  if (!point_groups.empty() && point_groups.size() != points.size()) {
    throw InputError("locate_in_material: " + std::to_string(points.size()) + " points but " +
                     std::to_string(point_groups.size()) + " groups (give one per point, or none)");
  }
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!points[i].allFinite())
      throw InputError("locate_in_material: point " + std::to_string(i) + " is not finite");
  }
}

} // namespace

double triangle_quality(const std::array<Eigen::Vector2d, 3>& uv) {
  const Eigen::Vector3d sides((uv[1] - uv[0]).norm(), (uv[2] - uv[1]).norm(),
                              (uv[0] - uv[2]).norm());
  const double area = 0.5 * orientation(uv[0], uv[1], uv[2]);
  if (!(area > 0.0)) return 0.0;
  const double inradius = 2.0 * area / sides.sum();
  return std::sqrt(3.0) * 2.0 * inradius / sides.maxCoeff();
}

double worst_quality(const TriangleMesh& mesh) {
  double worst = 1.0;
  for (const auto& uv : mesh.material_uv)
    worst = std::min(worst, triangle_quality(uv));
  return worst;
}

FlipReport delaunay_smoothing(TriangleMesh& mesh) {
  validate(mesh, "delaunay_smoothing");
  std::vector<std::array<int, 2>> pending;
  for (const Hinge& hinge : interior_edges(mesh))
    pending.push_back({hinge.vertices[0], hinge.vertices[1]});
  EdgeTriangles edges = edge_triangles(mesh);
  const std::unordered_set<EdgeKey> creases = crease_keys(mesh);
  FlipReport report;
  report.worst_before = worst_quality(mesh);
  // Lawson's flips end (each lowers the lifted triangulation); a cap turns a
  // bug into an error instead of a hang.
  const double most_checks = 10.0 * double(mesh.triangle_count()) * double(mesh.triangle_count());
  for (std::uint64_t checks = 1; !pending.empty(); ++checks) {
    if (double(checks) > most_checks)
      throw std::logic_error("delaunay_smoothing: edge flips did not end");
    const auto [a, b] = pending.back();
    pending.pop_back();
    const auto found = edges.find(edge_key(a, b));
    if (found == edges.end() || found->second[1] < 0) continue; // flipped away, or outline
    const std::optional<Quad> quad = quad_of(mesh, a, b, found->second);
    if (!quad || !violates_delaunay(*quad) || !flippable(mesh, edges, creases, *quad)) continue;
    flip(mesh, edges, *quad);
    ++report.flips;
    const auto [v0, v1, v2, v3] = quad->v;
    pending.insert(pending.end(), {{v0, v3}, {v3, v1}, {v1, v2}, {v2, v0}});
  }
  report.worst_after = worst_quality(mesh);
  return report;
}

std::vector<BarycentricLocation> locate_in_material(const TriangleMesh& old_mesh,
                                                    const std::vector<Eigen::Vector2d>& points,
                                                    const std::vector<int>& point_groups) {
  validate(old_mesh, "locate_in_material");
  check_queries(points, point_groups);
  const bool grouped = !point_groups.empty();
  std::map<int, TriangleGrid> grids;
  for (const auto& [group, triangles] : triangles_by_group(old_mesh, grouped))
    grids.try_emplace(group, old_mesh, triangles);
  std::vector<BarycentricLocation> located;
  located.reserve(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    const int group = grouped ? point_groups[i] : 0;
    const auto grid = grids.find(group);
    if (grid == grids.end()) {
      throw InputError("locate_in_material: point " + std::to_string(i) + " is in group " +
                       std::to_string(group) + ", which has no triangles");
    }
    located.push_back(grid->second.locate(points[i]));
  }
  return located;
}

std::vector<Eigen::Vector3d> transfer_positions(const TriangleMesh& old_mesh,
                                                const std::vector<BarycentricLocation>& at) {
  std::vector<Eigen::Vector3d> positions;
  positions.reserve(at.size());
  for (const BarycentricLocation& location : at) {
    const auto& corners = old_mesh.triangles.at(std::size_t(location.triangle));
    Eigen::Vector3d position = Eigen::Vector3d::Zero();
    for (std::size_t c = 0; c < 3; ++c)
      position += location.weights[Eigen::Index(c)] * old_mesh.positions[std::size_t(corners[c])];
    positions.push_back(position);
  }
  return positions;
}

std::vector<int> source_triangles(const TriangleMesh& old_mesh, const TriangleMesh& new_mesh) {
  std::vector<Eigen::Vector2d> centroids;
  centroids.reserve(new_mesh.triangle_count());
  for (const auto& uv : new_mesh.material_uv)
    centroids.push_back((uv[0] + uv[1] + uv[2]) / 3.0);
  std::vector<int> sources;
  sources.reserve(centroids.size());
  for (const BarycentricLocation& at :
       locate_in_material(old_mesh, centroids, new_mesh.material_ids))
    sources.push_back(at.triangle);
  return sources;
}

} // namespace sartor
