#include "garment/prefold.hpp"

#include "common/error.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <deque>
#include <numeric>

namespace sartor::garment {

using Eigen::Vector2d;
using Eigen::Vector3d;

std::vector<MeshedFold> meshed_folds(const Panel& panel, const PanelMesh& meshed,
                                     bool outside_is_normal_side) {
  std::vector<MeshedFold> folds;
  for (const InteriorLine& line : panel.interior) {
    if (!line.crease) continue;
    const auto found = std::find_if(meshed.lines.begin(), meshed.lines.end(),
                                    [&](const MeshedLine& m) { return m.id == line.id; });
    if (found == meshed.lines.end()) continue;
    MeshedFold fold;
    fold.line = line.id;
    fold.start = line.curve.start();
    fold.end = line.curve.end();
    fold.vertices = found->vertices;
    fold.left = line.crease->side == Crease::Side::left;
    // Towards +z or -z, then the sense of the turn that takes the region's
    // side (left: the chord's left normal) there.
    const double towards = line.crease->outside == outside_is_normal_side ? 1.0 : -1.0;
    fold.rotation = towards * (fold.left ? 1.0 : -1.0) * line.crease->angle;
    // A region turned towards the normals' side makes a valley seen from there.
    fold.rest_angle = -towards * line.crease->angle;
    fold.stiffness_factor = line.crease->pressed;
    folds.push_back(fold);
  }
  return folds;
}

std::vector<int> warping_region(const TriangleMesh& flat, const MeshedFold& fold) {
  const Vector2d chord = fold.end - fold.start;
  const double length = chord.norm();
  const Vector2d left_normal = Vector2d(-chord.y(), chord.x()) / length;
  // Vertices off the line lie at least a fraction of an edge from it; those
  // on it (the mesher's) within round-off.
  const double margin = 1e-6 * length;
  const std::size_t n = flat.vertex_count();
  std::vector<bool> on_side(n);
  for (std::size_t v = 0; v < n; ++v) {
    const double offset = (flat.positions[v].head<2>() - fold.start).dot(left_normal);
    on_side[v] = fold.left ? offset > margin : offset < -margin;
  }
  std::vector<std::vector<int>> neighbours(n);
  for (const auto& t : flat.triangles)
    for (std::size_t c = 0; c < 3; ++c) {
      neighbours[std::size_t(t[c])].push_back(t[(c + 1) % 3]);
      neighbours[std::size_t(t[(c + 1) % 3])].push_back(t[c]);
    }
  std::vector<bool> reached(n, false);
  std::deque<int> queue;
  for (int v : fold.vertices)
    for (int w : neighbours[std::size_t(v)])
      if (on_side[std::size_t(w)] && !reached[std::size_t(w)]) {
        reached[std::size_t(w)] = true;
        queue.push_back(w);
      }
  while (!queue.empty()) {
    const int v = queue.front();
    queue.pop_front();
    for (int w : neighbours[std::size_t(v)])
      if (on_side[std::size_t(w)] && !reached[std::size_t(w)]) {
        reached[std::size_t(w)] = true;
        queue.push_back(w);
      }
  }
  std::vector<int> region;
  for (std::size_t v = 0; v < n; ++v)
    if (reached[v]) region.push_back(int(v));
  return region;
}

std::vector<Vector3d> prefold(const TriangleMesh& flat, const std::vector<MeshedFold>& folds) {
  std::vector<Vector3d> x = flat.positions;
  std::vector<std::vector<int>> regions;
  for (const MeshedFold& fold : folds) {
    regions.push_back(warping_region(flat, fold));
    if (regions.back().empty())
      throw InputError("fold line '" + fold.line + "': its warping region (the " +
                       (fold.left ? "left" : "right") + " side) holds no mesh vertex");
  }
  // Smaller regions first: a region nested in a larger one turns with it,
  // about an axis that has not moved yet.
  std::vector<std::size_t> order(folds.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t i, std::size_t j) {
    return regions[i].size() < regions[j].size();
  });
  for (std::size_t i : order) {
    const MeshedFold& fold = folds[i];
    const Vector3d origin(fold.start.x(), fold.start.y(), 0.0);
    const Vector3d axis =
        Vector3d(fold.end.x() - fold.start.x(), fold.end.y() - fold.start.y(), 0).normalized();
    const Eigen::AngleAxisd turn(fold.rotation, axis);
    for (int v : regions[i])
      x[std::size_t(v)] = origin + turn * (x[std::size_t(v)] - origin);
  }
  return x;
}

std::vector<CreaseEdge> crease_edges(const std::vector<MeshedFold>& folds, int first_vertex) {
  std::vector<CreaseEdge> edges;
  for (const MeshedFold& fold : folds)
    for (std::size_t k = 0; k + 1 < fold.vertices.size(); ++k)
      edges.push_back({fold.vertices[k] + first_vertex, fold.vertices[k + 1] + first_vertex,
                       fold.rest_angle, fold.stiffness_factor});
  return edges;
}

} // namespace sartor::garment
