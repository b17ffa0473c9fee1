#pragma once
// A cloth mesh as the serial front end hands it over: triangles with an
// initial 3D placement and material (u, v) coordinates, u along the warp and
// v along the weft, in metres of undeformed fabric. Material coordinates are
// stored per triangle corner, as OBJ texture coordinates are, so a closed
// tube can carry the seam where u jumps by its circumference.

#include <Eigen/Core>

#include <array>
#include <cmath>
#include <string>
#include <vector>

namespace sartor {

// A mesh edge (vertices a, b) whose bending rest angle is not flat: a crease
// (docs/pleats.md). The angle is the hinge's dihedral rest angle as
// element/bending.hpp defines it (> 0: a ridge seen from the side the
// triangles' counter-clockwise normals face).
struct CreaseEdge {
  int a = 0, b = 0;
  double rest_angle = 0.0; // rad, in (-pi, pi)
  // The hinge's bending stiffness over the fabric's: above 1 a pressed
  // (set) crease, as an interfaced lapel's or a pressed pleat's.
  double stiffness_factor = 1.0;
};

struct TriangleMesh {
  std::vector<Eigen::Vector3d> positions;                  // per vertex, m
  std::vector<std::array<int, 3>> triangles;               // vertex indices
  std::vector<std::array<Eigen::Vector2d, 3>> material_uv; // per triangle corner, m
  std::vector<int> material_ids;                           // per triangle; empty: all 0
  std::vector<CreaseEdge> creases;                         // interior edges; empty: none

  std::size_t vertex_count() const { return positions.size(); }
  std::size_t triangle_count() const { return triangles.size(); }
};

// Throws InputError naming the triangle when an index is out of range, a
// triangle repeats a vertex, a coordinate is not finite, or a triangle has no
// material area (|det [du dv]| below 1e-14 of its squared size). Also throws
// when material_uv does not have one entry per triangle, material_ids is
// neither empty nor one per triangle, or a position is not finite (naming the
// vertex). `context` (a file name, a generator) starts every message.
void validate(const TriangleMesh& mesh, const std::string& context);

// An interior edge shared by two triangles, in the order the bending kernels
// use: the first triangle is (v0, v1, v2), the second (v1, v0, v3), the edge
// is v0-v1 and v2, v3 are the opposite vertices. The first triangle runs
// v0 -> v1 in its own winding; the second normally runs v1 -> v0 (it runs
// v0 -> v1 too only where the mesh is not consistently oriented).
// corners[k][i] is the corner (0..2) of triangles[k] that holds the hinge's
// i-th vertex of that triangle, so that
//   mesh.material_uv[triangles[k]][corners[k][i]]
// is triangle k's own rest coordinate of vertices[0, 1, 2] (k = 0) resp.
// vertices[1, 0, 3] (k = 1); across a seam the two triangles' uv differ.
struct Hinge {
  std::array<int, 4> vertices;               // v0, v1, v2, v3
  std::array<int, 2> triangles;              // first < second
  std::array<std::array<int, 3>, 2> corners; // see above
};

// Every edge with exactly two triangles, ordered by first triangle then by
// the edge's place in it. Throws InputError for an edge with three or more
// triangles (naming the edge and the triangles) and for two triangles on the
// same three vertices.
std::vector<Hinge> interior_edges(const TriangleMesh& mesh);

// Sorted indices of the vertices on edges that have one triangle. Throws as
// interior_edges does for non-manifold edges.
std::vector<int> boundary_vertices(const TriangleMesh& mesh);
// The area of a triangle from its material (u, v) corners, m^2.
inline double material_area(const std::array<Eigen::Vector2d, 3>& uv) {
  const Eigen::Vector2d a = uv[1] - uv[0], b = uv[2] - uv[0];
  return 0.5 * std::abs(a.x() * b.y() - a.y() * b.x());
}
// The mesh's, summed over its triangles, m^2.
double material_area(const TriangleMesh& mesh);

// Each vertex's material (u, v): that of its corner in the last triangle
// holding it (a vertex on a tube's seam has two; this is one of them).
std::vector<Eigen::Vector2d> vertex_material_uv(const TriangleMesh& mesh);

// Edges of one triangle only, (lower, higher vertex index), sorted.
std::vector<std::array<int, 2>> boundary_edges(const TriangleMesh& mesh);
// Every edge once, (lower, higher vertex index), sorted; any connectivity.
std::vector<std::array<int, 2>> mesh_edges(const TriangleMesh& mesh);

} // namespace sartor
