#pragma once
// Rigid bodies as closed triangle meshes: the Wavefront OBJ reader for body
// files, the checks that make a mesh usable as a solid (its inside must be
// well defined, so that a signed distance exists), and the measurements that
// `sartor body` reports. Serial data, replicated on every rank.
//
// Read: `v x y z [w | r g b]` and `f` with corners `a`, `a/b`, `a//c` or
// `a/b/c` (only the vertex index is used), 1-based or negative (relative)
// indices, polygons fan-triangulated from their first corner; `#` comments,
// `\` line continuations; `vt vn vp o g s usemtl mtllib l p` are ignored. Any
// other statement is an error. Vertices that no face uses are kept and
// ignored.
//
// A body must be (each an InputError at FILE:LINE of the offending face, or
// naming the face for meshes built in memory): non-empty; free of bad numbers,
// out-of-range indices and degenerate faces (a repeated vertex, or an area
// below 1e-12 of the squared longest side); 2-manifold (every edge in exactly
// two faces, every vertex's faces one fan); closed (no edge in one face);
// consistently oriented (the two faces of an edge run it in opposite
// directions); oriented outward (positive enclosed volume); and free of
// self-intersections (no two faces cross other than along the edge or at the
// vertex they share; CGAL's exact predicates).

#include <Eigen/Core>

#include <array>
#include <string>
#include <vector>

namespace sartor {

struct BodyMesh {
  std::vector<Eigen::Vector3d> vertices; // m
  std::vector<std::array<int, 3>> faces; // counter-clockwise seen from outside
};

// Reads and checks a body OBJ file (see above).
BodyMesh read_body_obj(const std::string& path);

// The checks above for a mesh built in memory; `context` (a generator's name)
// starts every message.
void check_body_mesh(const BodyMesh& mesh, const std::string& context);

struct BodyMeasures {
  std::size_t used_vertices = 0;
  Eigen::Vector3d lower = Eigen::Vector3d::Zero(); // bounding box of the used vertices, m
  Eigen::Vector3d upper = Eigen::Vector3d::Zero();
  double area = 0.0;   // m^2
  double volume = 0.0; // m^3, > 0 for outward faces
  std::size_t edges = 0;
  std::size_t components = 0;    // connected pieces (by shared edges)
  long euler_characteristic = 0; // V - E + F; 2 per closed sphere-like piece
  double shortest_edge = 0.0;    // m
  double longest_edge = 0.0;     // m
  double smallest_angle_deg = 0.0;
};

// Measures a mesh that passed check_body_mesh.
BodyMeasures measure_body(const BodyMesh& mesh);

// v and f lines (numbers that read back to the same double), written
// atomically; `comment` lines go first, each prefixed with "# ".
void write_body_obj(const std::string& path, const BodyMesh& mesh,
                    const std::vector<std::string>& comment);

} // namespace sartor
