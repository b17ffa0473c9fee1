#pragma once
// The broad phase of cloth self-contact: the (vertex, triangle) pairs of a
// cloth mesh closer than a radius, found through a uniform grid of the
// triangles' boxes, less the pairs of vertices and triangles that are near
// each other in the cloth itself (the same triangle, its neighbours, the
// other side of a seam), whose closeness is the cloth's own shape and is
// the bending's and the seams' to hold.

#include <Eigen/Core>

#include <array>
#include <functional>
#include <utility>
#include <vector>

namespace sartor::contact {

// For each vertex, the sorted vertices within `rings` steps of it along the
// mesh's edges and the `links` (pairs of sewn vertices), or no farther than
// `radius` along them at their rest lengths (`rest_length(triangle, i)`:
// the length of edge i -> i + 1 of that triangle, m; links have none), itself
// included. The radius covers the small triangles of a corner, where a few
// rings reach less far than layers of cloth are apart.
std::vector<std::vector<int>>
nearby_vertices(std::size_t vertex_count, const std::vector<std::array<int, 3>>& triangles,
                const std::function<double(std::size_t, int)>& rest_length,
                const std::vector<std::pair<int, int>>& links, int rings, double radius);

struct VertexTrianglePair {
  int vertex = 0;
  int triangle = 0;
  double distance = 0.0; // from the vertex to the triangle, m

  bool operator<(const VertexTrianglePair& other) const {
    return vertex != other.vertex ? vertex < other.vertex : triangle < other.triangle;
  }
};

// Every pair of a vertex v with assigned[v] and a triangle with none of
// nearby[v] among its corners whose distance is below `radius`, sorted by
// vertex then triangle. The grid's cells are the larger of `radius` and the
// longest edge, so each triangle's box covers a few.
std::vector<VertexTrianglePair> vertex_triangle_pairs(
    const std::vector<Eigen::Vector3d>& positions, const std::vector<std::array<int, 3>>& triangles,
    const std::vector<std::vector<int>>& nearby, const std::vector<bool>& assigned, double radius);

} // namespace sartor::contact
