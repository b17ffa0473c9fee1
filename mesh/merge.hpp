#pragma once
// Exact merge of sewn vertices: once a seam has closed, each matched pair of
// vertices becomes one vertex, so the panels share the seam edges (and
// bending hinges cross the seam). Material (u, v) stays per triangle corner,
// so both panels keep their own rest shapes.

#include "mesh/triangle_mesh.hpp"

#include <utility>
#include <vector>

namespace sartor {

struct MergedMesh {
  TriangleMesh mesh;
  std::vector<int> vertex_map; // old vertex -> merged vertex
};

// Merges every pair (and, transitively, chains of pairs: a corner where
// several seams meet becomes one vertex). A merged vertex sits at the mean of
// its group's positions; merged vertices are numbered in the order of their
// first old vertex. Throws InputError when a pair names a vertex outside the
// mesh or the merge collapses a triangle (two of its corners in one group);
// the result passes validate().
MergedMesh merge_vertices(const TriangleMesh& mesh, const std::vector<std::pair<int, int>>& pairs);

} // namespace sartor
