#include "contact/cloth_pairs.hpp"

#include "element/point_triangle.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <queue>
#include <unordered_map>

namespace sartor::contact {

namespace {

using Cell = std::array<std::int64_t, 3>;

std::int64_t cell_key(const Cell& c) {
  // 21 bits a coordinate: cells of 1 mm reach a kilometre either way.
  constexpr std::int64_t bits = 21, half = std::int64_t(1) << (bits - 1);
  constexpr std::int64_t mask = (std::int64_t(1) << bits) - 1;
  return (((c[0] + half) & mask) << (2 * bits)) | (((c[1] + half) & mask) << bits) |
         ((c[2] + half) & mask);
}

Cell cell_of(const Eigen::Vector3d& p, double size) {
  return {std::int64_t(std::floor(p.x() / size)), std::int64_t(std::floor(p.y() / size)),
          std::int64_t(std::floor(p.z() / size))};
}

double longest_edge(const std::vector<Eigen::Vector3d>& positions,
                    const std::vector<std::array<int, 3>>& triangles) {
  double longest = 0.0;
  for (const auto& t : triangles) {
    for (int i = 0; i < 3; ++i) {
      const double length =
          (positions[std::size_t(t[std::size_t(i)])] - positions[std::size_t(t[(i + 1) % 3])])
              .norm();
      longest = std::max(longest, length);
    }
  }
  return longest;
}

// Each cell's triangles: those whose box, grown by `radius`, meets it.
std::unordered_map<std::int64_t, std::vector<int>>
triangle_grid(const std::vector<Eigen::Vector3d>& positions,
              const std::vector<std::array<int, 3>>& triangles, double radius, double size) {
  std::unordered_map<std::int64_t, std::vector<int>> grid;
  for (std::size_t k = 0; k < triangles.size(); ++k) {
    Eigen::Vector3d low = positions[std::size_t(triangles[k][0])], high = low;
    for (int i = 1; i < 3; ++i) {
      low = low.cwiseMin(positions[std::size_t(triangles[k][std::size_t(i)])]);
      high = high.cwiseMax(positions[std::size_t(triangles[k][std::size_t(i)])]);
    }
    const Cell from = cell_of(low.array() - radius, size);
    const Cell to = cell_of(high.array() + radius, size);
    for (std::int64_t i = from[0]; i <= to[0]; ++i) {
      for (std::int64_t j = from[1]; j <= to[1]; ++j) {
        for (std::int64_t l = from[2]; l <= to[2]; ++l)
          grid[cell_key({i, j, l})].push_back(int(k));
      }
    }
  }
  return grid;
}

bool shares_nearby_vertex(const std::array<int, 3>& triangle, const std::vector<int>& nearby) {
  return std::any_of(triangle.begin(), triangle.end(), [&](int corner) {
    return std::binary_search(nearby.begin(), nearby.end(), corner);
  });
}

} // namespace

namespace {

struct Step {
  int to;
  double length; // m, at rest
};
using Graph = std::vector<std::vector<Step>>;

// The vertices within `rings` steps of `from`.
std::vector<int> within_rings(const Graph& graph, int from, int rings) {
  std::vector<int> reached{from}, front{from};
  for (int ring = 0; ring < rings; ++ring) {
    std::vector<int> next;
    for (int u : front) {
      for (const Step& step : graph[std::size_t(u)]) {
        if (std::find(reached.begin(), reached.end(), step.to) != reached.end()) continue;
        reached.push_back(step.to);
        next.push_back(step.to);
      }
    }
    front = std::move(next);
  }
  return reached;
}

// The vertices no farther than `radius` from `from` along the graph
// (Dijkstra's search, stopped at the radius).
std::vector<int> within_length(const Graph& graph, int from, double radius) {
  std::vector<std::pair<int, double>> settled;
  std::priority_queue<std::pair<double, int>, std::vector<std::pair<double, int>>, std::greater<>>
      queue;
  queue.push({0.0, from});
  while (!queue.empty()) {
    const auto [length, u] = queue.top();
    queue.pop();
    const bool done =
        std::any_of(settled.begin(), settled.end(), [&](const auto& s) { return s.first == u; });
    if (done) continue;
    settled.emplace_back(u, length);
    for (const Step& step : graph[std::size_t(u)]) {
      if (length + step.length <= radius) queue.push({length + step.length, step.to});
    }
  }
  std::vector<int> reached;
  for (const auto& s : settled)
    reached.push_back(s.first);
  return reached;
}

} // namespace

std::vector<std::vector<int>>
nearby_vertices(std::size_t vertex_count, const std::vector<std::array<int, 3>>& triangles,
                const std::function<double(std::size_t, int)>& rest_length,
                const std::vector<std::pair<int, int>>& links, int rings, double radius) {
  Graph graph(vertex_count);
  const auto connect = [&](int a, int b, double length) {
    graph[std::size_t(a)].push_back({b, length});
    graph[std::size_t(b)].push_back({a, length});
  };
  for (std::size_t k = 0; k < triangles.size(); ++k) {
    for (int i = 0; i < 3; ++i)
      connect(triangles[k][std::size_t(i)], triangles[k][std::size_t((i + 1) % 3)],
              rest_length(k, i));
  }
  for (const auto& [a, b] : links)
    connect(a, b, 0.0);
  std::vector<std::vector<int>> nearby(vertex_count);
  for (std::size_t v = 0; v < vertex_count; ++v) {
    std::vector<int> mine = within_rings(graph, int(v), rings);
    const std::vector<int> close = within_length(graph, int(v), radius);
    mine.insert(mine.end(), close.begin(), close.end());
    std::sort(mine.begin(), mine.end());
    mine.erase(std::unique(mine.begin(), mine.end()), mine.end());
    nearby[v] = std::move(mine);
  }
  return nearby;
}

std::vector<VertexTrianglePair> vertex_triangle_pairs(
    const std::vector<Eigen::Vector3d>& positions, const std::vector<std::array<int, 3>>& triangles,
    const std::vector<std::vector<int>>& nearby, const std::vector<bool>& assigned, double radius) {
  std::vector<VertexTrianglePair> pairs;
  if (triangles.empty() || !(radius > 0.0)) return pairs;
  const double size = std::max(radius, longest_edge(positions, triangles));
  if (!(size > 0.0) || !std::isfinite(size)) return pairs;
  const auto grid = triangle_grid(positions, triangles, radius, size);
  for (std::size_t v = 0; v < positions.size(); ++v) {
    if (!assigned[v]) continue;
    const auto cell = grid.find(cell_key(cell_of(positions[v], size)));
    if (cell == grid.end()) continue;
    for (int k : cell->second) {
      const auto& t = triangles[std::size_t(k)];
      if (shares_nearby_vertex(t, nearby[v])) continue;
      const double d = element::closest_point_on_triangle(
                           positions[v], positions[std::size_t(t[0])], positions[std::size_t(t[1])],
                           positions[std::size_t(t[2])])
                           .distance;
      if (d < radius) pairs.push_back({int(v), k, d});
    }
  }
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

} // namespace sartor::contact
