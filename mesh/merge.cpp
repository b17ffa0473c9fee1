#include "mesh/merge.hpp"

#include "common/error.hpp"

#include <numeric>

namespace sartor {

namespace {

int find_root(std::vector<int>& parent, int v) {
  while (parent[std::size_t(v)] != v) {
    parent[std::size_t(v)] = parent[std::size_t(parent[std::size_t(v)])];
    v = parent[std::size_t(v)];
  }
  return v;
}

} // namespace

MergedMesh merge_vertices(const TriangleMesh& mesh, const std::vector<std::pair<int, int>>& pairs) {
  const std::size_t n = mesh.vertex_count();
  std::vector<int> parent(n);
  std::iota(parent.begin(), parent.end(), 0);
  for (const auto& [p, q] : pairs) {
    for (int v : {p, q}) {
      if (v < 0 || std::size_t(v) >= n) {
        throw InputError("merge: vertex " + std::to_string(v) + " is not in the mesh (0.." +
                         std::to_string(n - 1) + ")");
      }
    }
    const int rp = find_root(parent, p), rq = find_root(parent, q);
    // The smaller index is the root, so groups are numbered by their first vertex.
    if (rp != rq) parent[std::size_t(std::max(rp, rq))] = std::min(rp, rq);
  }

  MergedMesh merged;
  merged.vertex_map.assign(n, -1);
  std::vector<int> group_size;
  for (std::size_t v = 0; v < n; ++v) {
    const auto root = std::size_t(find_root(parent, int(v)));
    if (merged.vertex_map[root] < 0) {
      merged.vertex_map[root] = int(merged.mesh.positions.size());
      merged.mesh.positions.push_back(Eigen::Vector3d::Zero());
      group_size.push_back(0);
    }
    const auto target = std::size_t(merged.vertex_map[root]);
    merged.vertex_map[v] = int(target);
    merged.mesh.positions[target] += mesh.positions[v];
    ++group_size[target];
  }
  for (std::size_t v = 0; v < merged.mesh.positions.size(); ++v)
    merged.mesh.positions[v] /= double(group_size[v]);

  merged.mesh.material_uv = mesh.material_uv;
  merged.mesh.material_ids = mesh.material_ids;
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    std::array<int, 3> corners{};
    for (std::size_t c = 0; c < 3; ++c)
      corners[c] = merged.vertex_map[std::size_t(mesh.triangles[t][c])];
    if (corners[0] == corners[1] || corners[1] == corners[2] || corners[2] == corners[0]) {
      throw InputError("merge: triangle " + std::to_string(t) +
                       " would collapse (two of its corners are merged into one vertex)");
    }
    merged.mesh.triangles.push_back(corners);
  }
  for (const CreaseEdge& crease : mesh.creases)
    merged.mesh.creases.push_back({merged.vertex_map[std::size_t(crease.a)],
                                   merged.vertex_map[std::size_t(crease.b)], crease.rest_angle,
                                   crease.stiffness_factor});
  validate(merged.mesh, "merged mesh");
  interior_edges(merged.mesh); // throws for a merge that makes an edge non-manifold
  return merged;
}

} // namespace sartor
