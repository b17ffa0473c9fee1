// Wrapping by marks: root edges and growth (garment/wrap.hpp).

#include "garment/wrap.hpp"

#include "common/error.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <utility>

namespace sartor::garment {

namespace {

double cross2(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

// Cumulative arc length of a polyline, 0 at its first point.
template <typename Point>
std::vector<double> arc_lengths(const std::vector<Point>& points) {
  std::vector<double> lengths{0.0};
  for (std::size_t i = 1; i < points.size(); ++i)
    lengths.push_back(lengths.back() + (points[i] - points[i - 1]).norm());
  return lengths;
}

// The point at `fraction` of a 3D polyline's arc length and its unit tangent.
std::pair<Eigen::Vector3d, Eigen::Vector3d> at_fraction(const std::vector<Eigen::Vector3d>& points,
                                                        const std::vector<double>& lengths,
                                                        double fraction) {
  const double target = std::clamp(fraction, 0.0, 1.0) * lengths.back();
  std::size_t segment = 0;
  while (segment + 2 < points.size() && lengths[segment + 1] < target)
    ++segment;
  const double piece = lengths[segment + 1] - lengths[segment];
  const double t = piece > 0.0 ? (target - lengths[segment]) / piece : 0.0;
  const Eigen::Vector3d direction = points[segment + 1] - points[segment];
  return {points[segment] + t * direction, direction.normalized()};
}

// Walks `distance` on the body surface from body point `start` in tangent
// direction `direction`, in short steps each put back on the surface and
// each turning the direction into the new tangent plane.
Eigen::Vector3d walk_on_body(const contact::Shape& body, Eigen::Vector3d start,
                             Eigen::Vector3d direction, double distance) {
  const int steps = std::max(1, int(std::ceil(distance / 0.005)));
  const double step = distance / steps;
  for (int i = 0; i < steps; ++i) {
    const BodyPoint near = nearest_body_point(body, start + step * direction);
    const Eigen::Vector3d tangent = direction - direction.dot(near.normal) * near.normal;
    if (tangent.norm() > 1e-9) direction = tangent.normalized();
    start = near.closest;
  }
  return start;
}

struct Adjacency {
  std::vector<std::vector<int>> triangles_of_vertex;
  std::map<std::pair<int, int>, std::vector<int>> triangles_of_edge;
};

Adjacency adjacency(const TriangleMesh& mesh) {
  Adjacency adjacent;
  adjacent.triangles_of_vertex.resize(mesh.vertex_count());
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    for (int c = 0; c < 3; ++c) {
      const int a = mesh.triangles[t][std::size_t(c)],
                b = mesh.triangles[t][std::size_t(c + 1) % 3];
      adjacent.triangles_of_vertex[std::size_t(a)].push_back(int(t));
      adjacent.triangles_of_edge[{std::min(a, b), std::max(a, b)}].push_back(int(t));
    }
  }
  return adjacent;
}

// The root edges of one mark pair: each edge of the mark's panel that the
// mark crosses, once, with the positions its ends are walked to.
void paste_root_edges(const TriangleMesh& mesh, const MarkPair& pair, int pair_index,
                      const Pattern& pattern, const contact::Shape& body,
                      std::vector<Eigen::Vector3d>& sum, std::vector<int>& count,
                      std::vector<MarkCrossing>& crossings) {
  const GrainLine& grain = pattern.panels[std::size_t(pair.cloth.panel)].grain;
  std::vector<Eigen::Vector2d> mark;
  for (const Eigen::Vector2d& p : pair.cloth.points)
    mark.push_back(grain.material_uv(p));
  const std::vector<double> mark_lengths = arc_lengths(mark);
  const std::vector<double> body_lengths = arc_lengths(pair.body);
  std::set<std::pair<int, int>> seen;
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    if (mesh.material_ids[t] != pair.cloth.panel) continue;
    for (std::size_t c = 0; c < 3; ++c) {
      const int a = mesh.triangles[t][c], b = mesh.triangles[t][(c + 1) % 3];
      const Eigen::Vector2d &ua = mesh.material_uv[t][c], &ub = mesh.material_uv[t][(c + 1) % 3];
      for (std::size_t j = 0; j + 1 < mark.size(); ++j) {
        const Eigen::Vector2d edge = ub - ua, segment = mark[j + 1] - mark[j];
        const double denominator = cross2(edge, segment);
        if (std::abs(denominator) < 1e-14 * edge.norm() * segment.norm()) continue;
        const double along_edge = cross2(mark[j] - ua, segment) / denominator;
        const double along_mark = cross2(mark[j] - ua, edge) / denominator;
        if (along_edge < 0.0 || along_edge > 1.0 || along_mark < 0.0 || along_mark > 1.0) continue;
        if (!seen.insert({std::min(a, b), std::max(a, b)}).second) break;
        const Eigen::Vector2d crossing = ua + along_edge * edge;
        const double fraction =
            (mark_lengths[j] + along_mark * segment.norm()) / mark_lengths.back();
        const auto [target, body_tangent] = at_fraction(pair.body, body_lengths, fraction);
        crossings.push_back({pair_index, a, b, along_edge, target});
        const BodyPoint surface = nearest_body_point(body, target);
        Eigen::Vector3d tangent = body_tangent - body_tangent.dot(surface.normal) * surface.normal;
        tangent.normalize();
        const Eigen::Vector2d mark_tangent = segment.normalized();
        for (const auto& [vertex, uv] : {std::make_pair(a, ua), std::make_pair(b, ub)}) {
          const Eigen::Vector2d offset = uv - crossing;
          const double angle = std::atan2(cross2(mark_tangent, offset), mark_tangent.dot(offset));
          // Turned about the outward normal: the panel's front faces out.
          const Eigen::Vector3d direction =
              std::cos(angle) * tangent + std::sin(angle) * surface.normal.cross(tangent);
          sum[std::size_t(vertex)] += walk_on_body(body, surface.closest, direction, offset.norm());
          ++count[std::size_t(vertex)];
        }
        break;
      }
    }
  }
}

// The position of ready vertex `v` of triangle `t` from parent triangle
// `parent` across the edge of t's other two vertices (or, with parent < 0,
// from the body's tangent plane there).
Eigen::Vector3d place_from_parent(const TriangleMesh& mesh, const std::vector<Eigen::Vector3d>& x,
                                  int t, int v, int parent, const contact::Shape& body) {
  const auto& corners = mesh.triangles[std::size_t(t)];
  std::size_t cv = 0;
  while (corners[cv] != v)
    ++cv;
  const std::size_t ca = (cv + 1) % 3, cb = (cv + 2) % 3;
  const int a = corners[ca], b = corners[cb];
  const auto& uv = mesh.material_uv[std::size_t(t)];
  const Eigen::Vector2d edge = uv[cb] - uv[ca], to_v = uv[cv] - uv[ca];
  const double foot = to_v.dot(edge) / edge.squaredNorm();
  const double altitude = cross2(edge, to_v) / edge.norm(); // > 0: v left of a -> b
  const Eigen::Vector3d &xa = x[std::size_t(a)], &xb = x[std::size_t(b)];
  const Eigen::Vector3d shared = xb - xa, base = xa + foot * shared;
  if (parent >= 0) {
    int third = 0;
    for (int corner : mesh.triangles[std::size_t(parent)])
      if (corner != a && corner != b) third = corner;
    const Eigen::Vector3d to_third = x[std::size_t(third)] - xa;
    const Eigen::Vector3d across = to_third - to_third.dot(shared) / shared.squaredNorm() * shared;
    if (across.norm() > 1e-9 * shared.norm())
      return base - std::abs(altitude) * across.normalized();
  }
  // The front (counter-clockwise (u, v)) faces away from the body.
  const Eigen::Vector3d normal = nearest_body_point(body, base).normal;
  return base + altitude * normal.cross(shared).normalized();
}

// Mesh distance (along rest lengths) from the root vertices.
std::vector<double> distance_from(const RestEdges& edges, const std::vector<int>& roots) {
  std::vector<double> distance(edges.neighbours.size(), std::numeric_limits<double>::infinity());
  std::set<std::pair<double, int>> queue;
  for (int root : roots) {
    distance[std::size_t(root)] = 0.0;
    queue.insert({0.0, root});
  }
  while (!queue.empty()) {
    const auto [d, v] = *queue.begin();
    queue.erase(queue.begin());
    for (const auto& [n, length] : edges.neighbours[std::size_t(v)]) {
      if (d + length >= distance[std::size_t(n)]) continue;
      queue.erase({distance[std::size_t(n)], n});
      distance[std::size_t(n)] = d + length;
      queue.insert({d + length, n});
    }
  }
  return distance;
}

class Growth {
public:
  Growth(ClothOnBody& cloth, std::vector<double> priority, int relax_steps)
      : cloth_(cloth), mesh_(cloth.mesh()), adjacent_(adjacency(cloth.mesh())),
        priority_(std::move(priority)), relax_steps_(relax_steps),
        queued_(mesh_.vertex_count(), false) {}

  // Maps every vertex reachable from the mapped ones; returns them in order.
  std::vector<int> grow() {
    for (std::size_t v = 0; v < mesh_.vertex_count(); ++v)
      if (cloth_.active[v]) enqueue_neighbours(int(v));
    std::vector<int> order;
    while (!ready_.empty()) {
      const int v = ready_.begin()->second;
      ready_.erase(ready_.begin());
      cloth_.positions()[std::size_t(v)] = place(v);
      cloth_.active[std::size_t(v)] = true;
      cloth_.relax(relax_steps_);
      order.push_back(v);
      enqueue_neighbours(v);
    }
    return order;
  }

private:
  bool mapped(int v) const { return cloth_.active[std::size_t(v)]; }
  bool triangle_mapped(int t) const {
    const auto& c = mesh_.triangles[std::size_t(t)];
    return mapped(c[0]) && mapped(c[1]) && mapped(c[2]);
  }

  void enqueue_neighbours(int v) {
    for (int t : adjacent_.triangles_of_vertex[std::size_t(v)]) {
      int unmapped = -1, unmapped_count = 0;
      for (int corner : mesh_.triangles[std::size_t(t)])
        if (!mapped(corner)) ++unmapped_count, unmapped = corner;
      if (unmapped_count != 1 || queued_[std::size_t(unmapped)]) continue;
      queued_[std::size_t(unmapped)] = true;
      ready_.insert({priority_[std::size_t(unmapped)], unmapped});
    }
  }

  // The mean of the positions from every parent triangle of v.
  Eigen::Vector3d place(int v) const {
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    int count = 0;
    for (int t : adjacent_.triangles_of_vertex[std::size_t(v)]) {
      std::vector<int> others;
      for (int corner : mesh_.triangles[std::size_t(t)])
        if (corner != v && mapped(corner)) others.push_back(corner);
      if (others.size() != 2) continue;
      const auto& sharing = adjacent_.triangles_of_edge.at(
          {std::min(others[0], others[1]), std::max(others[0], others[1])});
      bool from_parent = false;
      for (int parent : sharing) {
        if (parent == t || !triangle_mapped(parent)) continue;
        sum += place_from_parent(mesh_, cloth_.positions(), t, v, parent, cloth_.body());
        ++count;
        from_parent = true;
      }
      if (!from_parent) {
        sum += place_from_parent(mesh_, cloth_.positions(), t, v, -1, cloth_.body());
        ++count;
      }
    }
    return keep_above(cloth_.body(), sum / count, cloth_.parameters().offset);
  }

  ClothOnBody& cloth_;
  const TriangleMesh& mesh_;
  Adjacency adjacent_;
  std::vector<double> priority_;
  int relax_steps_;
  std::vector<bool> queued_;
  std::set<std::pair<double, int>> ready_;
};

} // namespace

std::vector<Eigen::Vector3d> body_surface_path(const contact::Shape& body,
                                               const std::vector<Eigen::Vector3d>& points,
                                               double spacing) {
  std::vector<Eigen::Vector3d> path{nearest_body_point(body, points.front()).closest};
  for (std::size_t i = 1; i < points.size(); ++i) {
    const int pieces = std::max(1, int(std::ceil((points[i] - points[i - 1]).norm() / spacing)));
    for (int k = 1; k <= pieces; ++k) {
      const Eigen::Vector3d p = points[i - 1] + double(k) / pieces * (points[i] - points[i - 1]);
      path.push_back(nearest_body_point(body, p).closest);
    }
  }
  return path;
}

MarkMismatch mark_mismatch(const std::vector<MarkCrossing>& crossings,
                           const std::vector<Eigen::Vector3d>& positions,
                           const contact::Shape& body) {
  MarkMismatch mismatch;
  double squares = 0.0;
  for (const MarkCrossing& crossing : crossings) {
    const Eigen::Vector3d on_cloth =
        (1.0 - crossing.along_edge) * positions[std::size_t(crossing.a)] +
        crossing.along_edge * positions[std::size_t(crossing.b)];
    const double error = (nearest_body_point(body, on_cloth).closest - crossing.target).norm();
    mismatch.max = std::max(mismatch.max, error);
    squares += error * error;
    ++mismatch.crossings;
  }
  if (mismatch.crossings > 0) mismatch.rms = std::sqrt(squares / mismatch.crossings);
  return mismatch;
}

namespace {

// The unmapped vertices' panels, named in the error.
void check_all_mapped(const ClothOnBody& cloth, const Pattern& pattern) {
  const TriangleMesh& mesh = cloth.mesh();
  std::set<std::string> unreached;
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t)
    for (int corner : mesh.triangles[t])
      if (!cloth.active[std::size_t(corner)])
        unreached.insert(pattern.panels[std::size_t(mesh.material_ids[t])].id);
  if (unreached.empty()) return;
  std::string names;
  for (const std::string& id : unreached)
    names += (names.empty() ? "'" : ", '") + id + "'";
  throw InputError("wrap: panel(s) " + names +
                   " not reached from any mark: give each piece of the sewn garment a mark");
}

// Rewrapping: vertices at least as far from the new root vertices as the
// nearest pin (mesh distance) keep their place and are held; the others
// are mapped again.
int keep_beyond_pins(ClothOnBody& cloth, const Rewrap& rewrap,
                     const std::vector<double>& distance) {
  if (rewrap.positions.size() != cloth.positions().size())
    throw InputError("rewrap: the placed garment has " + std::to_string(rewrap.positions.size()) +
                     " vertices, the sewn pattern " + std::to_string(cloth.positions().size()) +
                     ": mesh it with the same pattern, seams and --edge-length");
  double limit = std::numeric_limits<double>::infinity();
  for (int pin : rewrap.pins) {
    if (pin < 0 || std::size_t(pin) >= distance.size())
      throw InputError("rewrap: pin " + std::to_string(pin) + " is not in the garment");
    limit = std::min(limit, distance[std::size_t(pin)]);
  }
  int kept = 0;
  for (std::size_t v = 0; v < distance.size(); ++v) {
    if (cloth.active[v] || distance[v] < limit) continue;
    cloth.active[v] = cloth.fixed[v] = true;
    cloth.positions()[v] = rewrap.positions[v];
    ++kept;
  }
  return kept;
}

} // namespace

WrapResult wrap(const TriangleMesh& sewn, const Pattern& pattern,
                const std::vector<MarkPair>& pairs, const contact::Shape& body,
                const WrapOptions& options, const Rewrap* rewrap) {
  ClothOnBody cloth(sewn, body, options.relax);
  cloth.bones = options.bones;
  const std::size_t n = sewn.vertex_count();
  std::vector<Eigen::Vector3d> sum(n, Eigen::Vector3d::Zero());
  std::vector<int> count(n, 0);
  WrapResult result;
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    if (pairs[k].body.size() < 2 || arc_lengths(pairs[k].body).back() <= 0.0)
      throw InputError(pairs[k].cloth.where + ": mark '" + pairs[k].id +
                       "': its body mark has no length on the body's surface");
    const std::size_t before = result.crossings.size();
    paste_root_edges(sewn, pairs[k], int(k), pattern, body, sum, count, result.crossings);
    if (result.crossings.size() == before)
      throw InputError(pairs[k].cloth.where + ": mark '" + pairs[k].id +
                       "' crosses no edge of the mesh of panel '" +
                       pattern.panels[std::size_t(pairs[k].cloth.panel)].id + "'");
  }
  std::vector<int> roots;
  for (std::size_t v = 0; v < n; ++v) {
    cloth.active[v] = count[v] > 0;
    if (count[v] == 0) continue;
    cloth.positions()[v] = keep_above(body, sum[v] / count[v], options.relax.offset);
    roots.push_back(int(v));
  }
  result.root_vertices = int(roots.size());
  result.growth_order = roots;
  std::vector<double> distance = distance_from(cloth.edges(), roots);
  if (rewrap) result.kept_vertices = keep_beyond_pins(cloth, *rewrap, distance);
  Growth growth(cloth, std::move(distance), options.growth_relax_steps);
  for (int v : growth.grow())
    result.growth_order.push_back(v);
  check_all_mapped(cloth, pattern);
  if (options.subdivide) {
    AdaptiveSubdivision subdivision(cloth.mesh());
    relax_adaptively(cloth, subdivision, options.final_relax_steps);
    result.split_edges = subdivision.split_edges();
    result.splits = subdivision.splits();
    result.merges = subdivision.merges();
  } else {
    cloth.relax(options.final_relax_steps);
  }
  result.mesh = cloth.mesh();
  result.bone_holds = cloth.bone_holds();
  result.mismatch = mark_mismatch(result.crossings, result.mesh.positions, body);
  result.edge_ratios = edge_length_ratios(rest_edges(result.mesh), result.mesh.positions);
  result.min_distance = min_body_distance(body, result.mesh.positions);
  return result;
}

} // namespace sartor::garment
