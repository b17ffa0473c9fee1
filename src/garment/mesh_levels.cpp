#include "garment/mesh_levels.hpp"

#include "common/csv.hpp"
#include "common/error.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <numeric>

namespace sartor::garment {

namespace {

// Barycentric coordinates of p in the triangle (a, b, c); extrapolated
// outside it. The triangle has material area (validate() checks it).
std::array<double, 3> barycentric(const Eigen::Vector2d& p, const Eigen::Vector2d& a,
                                  const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  Eigen::Matrix2d edges;
  edges << b - a, c - a;
  const Eigen::Vector2d st = edges.partialPivLu().solve(p - a);
  return {1.0 - st.x() - st.y(), st.x(), st.y()};
}

double segment_distance(const Eigen::Vector2d& p, const Eigen::Vector2d& a,
                        const Eigen::Vector2d& b) {
  const Eigen::Vector2d ab = b - a;
  const double s = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
  return (p - a - s * ab).norm();
}

// The coarse triangles of one panel in rest coordinates, bucketed in a
// uniform grid of about one triangle per cell for point location.
class PanelGrid {
public:
  PanelGrid(const TriangleMesh& mesh, std::vector<int> triangles)
      : mesh_(mesh), triangles_(std::move(triangles)) {
    for (int t : triangles_)
      for (const Eigen::Vector2d& uv : mesh_.material_uv[std::size_t(t)])
        box_.extend(uv);
    cells_ = std::max(1, int(std::ceil(std::sqrt(double(triangles_.size())))));
    buckets_.resize(std::size_t(cells_ * cells_));
    for (int t : triangles_) {
      Eigen::AlignedBox2d bounds;
      for (const Eigen::Vector2d& uv : mesh_.material_uv[std::size_t(t)])
        bounds.extend(uv);
      const auto low = cell(bounds.min()), high = cell(bounds.max());
      for (int i = low[0]; i <= high[0]; ++i)
        for (int j = low[1]; j <= high[1]; ++j)
          buckets_[std::size_t(i * cells_ + j)].push_back(t);
    }
  }

  bool empty() const { return triangles_.empty(); }

  // The triangle of the panel holding p, or else the nearest one.
  CoarseLocation locate(const Eigen::Vector2d& p) const {
    const auto at = cell(p);
    CoarseLocation best;
    double best_inside = -std::numeric_limits<double>::infinity();
    for (int t : buckets_[std::size_t(at[0] * cells_ + at[1])]) {
      const auto w = weights(t, p);
      const double inside = std::min({w[0], w[1], w[2]});
      if (inside > best_inside) {
        best_inside = inside;
        best.triangle = t;
        best.weights = w;
      }
    }
    // Inside up to round-off: on an edge or a vertex either side gives the
    // same interpolant.
    if (best_inside >= -1e-10) return best;
    return nearest(p);
  }

private:
  std::array<int, 2> cell(const Eigen::Vector2d& p) const {
    const Eigen::Vector2d size = box_.sizes().cwiseMax(1e-300);
    std::array<int, 2> index{};
    for (int d = 0; d < 2; ++d) {
      const double x = (p[d] - box_.min()[d]) / size[d] * cells_;
      index[std::size_t(d)] = std::clamp(int(std::floor(x)), 0, cells_ - 1);
    }
    return index;
  }

  std::array<double, 3> weights(int t, const Eigen::Vector2d& p) const {
    const auto& uv = mesh_.material_uv[std::size_t(t)];
    return barycentric(p, uv[0], uv[1], uv[2]);
  }

  // p lies outside the panel's triangulation (a fine vertex on a curved
  // outline): the nearest triangle's extrapolated coordinates.
  CoarseLocation nearest(const Eigen::Vector2d& p) const {
    CoarseLocation best;
    best.outside = std::numeric_limits<double>::infinity();
    for (int t : triangles_) {
      const auto& uv = mesh_.material_uv[std::size_t(t)];
      const double distance =
          std::min({segment_distance(p, uv[0], uv[1]), segment_distance(p, uv[1], uv[2]),
                    segment_distance(p, uv[2], uv[0])});
      if (distance < best.outside) {
        best.outside = distance;
        best.triangle = t;
      }
    }
    best.weights = weights(best.triangle, p);
    return best;
  }

  const TriangleMesh& mesh_;
  std::vector<int> triangles_;
  Eigen::AlignedBox2d box_;
  int cells_ = 1;
  std::vector<std::vector<int>> buckets_;
};

std::vector<std::vector<int>> triangles_by_panel(const TriangleMesh& mesh) {
  std::vector<std::vector<int>> panels;
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    const int panel = mesh.material_ids.empty() ? 0 : mesh.material_ids[t];
    if (panel < 0) throw InputError("triangle " + std::to_string(t) + ": negative panel id");
    if (std::size_t(panel) >= panels.size()) panels.resize(std::size_t(panel) + 1);
    panels[std::size_t(panel)].push_back(int(t));
  }
  return panels;
}

double mesh_size(const TriangleMesh& mesh) {
  Eigen::AlignedBox2d box;
  for (const auto& uv : mesh.material_uv)
    for (const Eigen::Vector2d& corner : uv)
      box.extend(corner);
  return box.isEmpty() ? 0.0 : box.diagonal().norm();
}

} // namespace

VertexRest vertex_rest_coordinates(const TriangleMesh& mesh) {
  VertexRest rest;
  rest.panel.assign(mesh.vertex_count(), -1);
  rest.uv.assign(mesh.vertex_count(), Eigen::Vector2d::Zero());
  // Corners of one vertex in one flat panel have the same rest coordinates;
  // a tolerance far above round-off tells a mesh that is not so.
  const double tolerance = 1e-9 * mesh_size(mesh);
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    const int panel = mesh.material_ids.empty() ? 0 : mesh.material_ids[t];
    for (std::size_t c = 0; c < 3; ++c) {
      const std::size_t v = std::size_t(mesh.triangles[t][c]);
      const Eigen::Vector2d& uv = mesh.material_uv[t][c];
      if (rest.panel[v] < 0) {
        rest.panel[v] = panel;
        rest.uv[v] = uv;
      } else if (rest.panel[v] != panel || (rest.uv[v] - uv).norm() > tolerance) {
        throw InputError("vertex " + std::to_string(v) + " of triangle " + std::to_string(t) +
                         " lies in two panels, or at two rest positions: a level of a garment "
                         "has separate panels, each flat");
      }
    }
  }
  for (std::size_t v = 0; v < rest.panel.size(); ++v)
    if (rest.panel[v] < 0) throw InputError("vertex " + std::to_string(v) + " is in no triangle");
  return rest;
}

Prolongation::Prolongation(const TriangleMesh& coarse, const TriangleMesh& fine)
    : coarse_triangles_(coarse.triangles) {
  vertex_rest_coordinates(coarse); // checks the coarse panels are flat and apart
  const VertexRest rest = vertex_rest_coordinates(fine);
  std::vector<PanelGrid> grids;
  for (std::vector<int>& triangles : triangles_by_panel(coarse))
    grids.emplace_back(coarse, std::move(triangles));
  const auto grid = [&](int panel) -> const PanelGrid& {
    if (std::size_t(panel) >= grids.size() || grids[std::size_t(panel)].empty()) {
      throw InputError("panel " + std::to_string(panel) +
                       " of the finer level has no triangles in the coarser level");
    }
    return grids[std::size_t(panel)];
  };
  vertices_.reserve(fine.vertex_count());
  for (std::size_t v = 0; v < fine.vertex_count(); ++v)
    vertices_.push_back(grid(rest.panel[v]).locate(rest.uv[v]));
  centroids_.reserve(fine.triangle_count());
  for (std::size_t t = 0; t < fine.triangle_count(); ++t) {
    const auto& uv = fine.material_uv[t];
    const int panel = fine.material_ids.empty() ? 0 : fine.material_ids[t];
    centroids_.push_back(grid(panel).locate((uv[0] + uv[1] + uv[2]) / 3.0));
  }
}

double Prolongation::largest_outside_distance() const {
  double largest = 0.0;
  for (const CoarseLocation& at : vertices_)
    largest = std::max(largest, at.outside);
  return largest;
}

std::vector<double> level_edge_lengths(const Construction& construction,
                                       const PanelMeshOptions& mesh_options,
                                       const LevelOptions& options) {
  const double target = options.target_edge_length;
  if (!(target > 0)) throw InputError("option --edge-length: must be > 0");
  if (options.levels != 0 && options.coarsest_edge_length > 0) {
    throw InputError("options --levels and --coarsest-edge: give one of them, not both");
  }
  if (options.levels < 0) throw InputError("option --levels: must be at least 1");
  int count = options.levels;
  std::vector<double> lengths;
  if (options.coarsest_edge_length > 0) {
    const double ratio = options.coarsest_edge_length / target;
    if (ratio < 1.0) {
      throw InputError("option --coarsest-edge: " + format_number(options.coarsest_edge_length) +
                       " m is shorter than the target --edge-length " + format_number(target) +
                       " m");
    }
    // Levels in equal ratios of at most 2 (a ratio within 1e-9 of a power
    // of 2 is that power: 0.16 to 0.04 is three levels, not four).
    count = 1 + int(std::ceil(std::log2(ratio) - 1e-9));
    for (int k = 0; k < count; ++k)
      lengths.push_back(target * std::pow(ratio, double(count - 1 - k) / double(count - 1)));
    if (count == 1) lengths = {target};
    return lengths;
  }
  if (count == 0) {
    // Automatic: coarsen by 2 while the garment keeps enough triangles per panel.
    const double panels = double(std::max<std::size_t>(1, construction.pattern->panels.size()));
    count = 1;
    while (count < options.max_levels) {
      PanelMeshOptions coarser = mesh_options;
      coarser.edge_length = target * std::pow(2.0, count);
      if (coarser.edge_length > options.coarsest_limit * (1 + 1e-9)) break;
      const double triangles =
          double(build_garment_mesh(construction, coarser).mesh.triangle_count());
      if (triangles / panels < options.min_triangles_per_panel) break;
      ++count;
    }
  }
  for (int k = count - 1; k >= 0; --k)
    lengths.push_back(target * std::pow(2.0, k));
  return lengths;
}

GarmentMesh keep_panels(const GarmentMesh& garment, const std::vector<bool>& kept) {
  const TriangleMesh& mesh = garment.mesh;
  const VertexRest rest = vertex_rest_coordinates(mesh);
  const auto keeps = [&](int panel) {
    return std::size_t(panel) < kept.size() && kept[std::size_t(panel)];
  };
  GarmentMesh result;
  std::vector<int> new_index(mesh.vertex_count(), -1);
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
    if (!keeps(rest.panel[v])) continue;
    new_index[v] = int(result.mesh.positions.size());
    result.mesh.positions.push_back(mesh.positions[v]);
  }
  for (std::size_t p = 0; p < garment.first_vertex.size(); ++p) {
    if (!keeps(int(p))) continue;
    result.first_vertex.push_back(new_index[std::size_t(garment.first_vertex[p])]);
    result.triangle_count.push_back(garment.triangle_count[p]);
  }
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    if (!keeps(mesh.material_ids[t])) continue;
    std::array<int, 3> triangle{};
    for (std::size_t c = 0; c < 3; ++c)
      triangle[c] = new_index[std::size_t(mesh.triangles[t][c])];
    result.mesh.triangles.push_back(triangle);
    result.mesh.material_uv.push_back(mesh.material_uv[t]);
    result.mesh.material_ids.push_back(mesh.material_ids[t]);
  }
  const auto renumber = [&](std::vector<int> line) {
    for (int& v : line) {
      v = new_index[std::size_t(v)];
      if (v < 0) throw InputError("keep_panels: a seam joins a panel that is left out");
    }
    return line;
  };
  for (const auto& [id, line] : garment.line_vertices)
    if (new_index[std::size_t(line.front())] >= 0) result.line_vertices[id] = renumber(line);
  for (Seam seam : garment.seams) {
    seam.a = renumber(seam.a);
    seam.b = renumber(seam.b);
    result.seams.push_back(seam);
  }
  return result;
}

SeamClosure close_seams(const TriangleMesh& mesh, const std::vector<Seam>& seams,
                        std::vector<Eigen::Vector3d>* positions) {
  // Only where the springs pull matters here, not how hard.
  const std::vector<SeamSpring> springs = seam_springs(mesh, seams, SeamStiffness{1.0});
  std::vector<Eigen::Vector3d>& x = *positions;
  SeamClosure closure;
  closure.gap_before = largest_seam_gap(springs, x);
  // Vertices sewn to an edge: halfway to their partner points, all from the
  // positions before any moved.
  const std::vector<Eigen::Vector3d> before = x;
  std::map<int, std::pair<Eigen::Vector3d, int>> moves;
  for (const SeamSpring& spring : springs) {
    if (!spring.to_edge) continue;
    const int v = spring.vertices[0];
    const Eigen::Vector3d anchor = (1.0 - spring.s) * before[std::size_t(spring.vertices[1])] +
                                   spring.s * before[std::size_t(spring.vertices[2])];
    auto [entry, added] = moves.try_emplace(v, Eigen::Vector3d::Zero(), 0);
    entry->second.first += 0.5 * (before[std::size_t(v)] + anchor);
    ++entry->second.second;
  }
  for (const auto& [v, move] : moves)
    x[std::size_t(v)] = move.first / double(move.second);
  // Vertices sewn vertex to vertex, joined into groups across seams.
  std::vector<int> parent(x.size());
  std::iota(parent.begin(), parent.end(), 0);
  const std::function<int(int)> root = [&](int v) {
    return parent[std::size_t(v)] == v ? v : parent[std::size_t(v)] = root(parent[std::size_t(v)]);
  };
  for (const SeamSpring& spring : springs)
    if (!spring.to_edge) parent[std::size_t(root(spring.vertices[0]))] = root(spring.vertices[1]);
  std::vector<Eigen::Vector3d> sum(x.size(), Eigen::Vector3d::Zero());
  std::vector<int> members(x.size(), 0);
  for (std::size_t v = 0; v < x.size(); ++v) {
    sum[std::size_t(root(int(v)))] += x[v];
    ++members[std::size_t(root(int(v)))];
  }
  for (std::size_t v = 0; v < x.size(); ++v) {
    const std::size_t group = std::size_t(root(int(v)));
    if (members[group] > 1) x[v] = sum[group] / double(members[group]);
  }
  closure.gap_after = largest_seam_gap(springs, x);
  return closure;
}

} // namespace sartor::garment
