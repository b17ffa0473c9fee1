#pragma once
// Meshes made from a few numbers, for tests, convergence studies and simple
// cases. Every generator checks its arguments (InputError naming the
// parameter) and returns a mesh that passes validate(). Triangles are wound
// counter-clockwise in (u, v), so every material area is positive, and the
// 3D normals point to +z (flat meshes) or outward (band, cap).

#include "mesh/triangle_mesh.hpp"

namespace sartor::mesh {

enum class RectanglePattern {
  alternating, // diagonals alternate like a chess board; symmetric about both
               // centre lines when nx and ny are even
  right,       // every diagonal from the cell's (x0, y0) to its (x1, y1) corner
  perturbed,   // alternating, with every interior vertex moved by a fixed-seed
               // random offset of up to 25 % of the spacing in each direction
               // (inside the ellipse of semi-axes width/nx/4, height/ny/4, so no
               // triangle folds), in 3D position and uv alike: unstructured
               // triangles for patch tests, still at rest
};

// Parses "alternating", "right" or "perturbed"; InputError otherwise.
RectanglePattern rectangle_pattern(const std::string& name);

// width x height in the z = 0 plane, x along u (warp), a corner at the
// origin, nx by ny cells of two triangles; uv = (x, y).
// (nx + 1)(ny + 1) vertices, 2 nx ny triangles.
TriangleMesh rectangle(double width, double height, int nx, int ny,
                       RectanglePattern pattern = RectanglePattern::alternating);

// A disk centred at the origin in z = 0: a centre vertex and `rings` rings of
// vertices exactly on the circles of radius radius * k / rings, ring k with
// 6 k of them, neighbouring rings joined by triangles of nearly equal size;
// uv = (x, y). 1 + 3 rings (rings + 1) vertices, 6 rings^2 triangles.
TriangleMesh disk(double radius, int rings);

// How the band's material u follows its circumference.
enum class BandLength {
  arc,   // u = radius * angle: the band's rest circumference is 2 pi radius,
         // so the polygonal placement starts with a small hoop compression
         // (chord / arc - 1 = sin(pi/n) / (pi/n) - 1, n = segments)
  chord, // u steps by the chord 2 radius sin(pi / n): the placement is
         // exactly at rest (every triangle is isometric to its uv triangle)
};

// A closed tube around the z axis from z = 0 to z = height: `segments`
// vertices around (the first at angle 0 on +x), rows + 1 rows of them, every
// vertex once (the seam at angle 0 shares its vertices). v = z, u increases
// with the angle from 0 to the full circumference; the triangles of the last
// column, which close the tube, give their seam corners u = circumference, so
// u jumps at the seam from one side to the other.
// segments (rows + 1) vertices, 2 segments rows triangles.
TriangleMesh cylinder_band(double radius, double height, int segments, int rows,
                           BandLength length = BandLength::arc);

// The disk pattern of radius sphere_radius * cap_angle (uv, as disk()) laid on
// the sphere of that radius centred at the origin, around +z: the point at
// distance r from the disk centre goes to polar angle r / sphere_radius, so
// radial lines keep their length (geodesic distance), circles do not.
// 0 < cap_angle < pi (rad).
TriangleMesh sphere_cap(double sphere_radius, double cap_angle, int rings);

// An annular sector in z = 0 around the origin: inner_radius <= r <=
// outer_radius, start_angle <= angle <= end_angle (rad, 0 < end - start <=
// 4 pi). It is the rectangle mesh of `rings` (across the radii) by
// `segments` (around) cells of `pattern` on the parameter square, refined
// `refinements` times there and then mapped to polar coordinates, so every
// vertex of every refinement lies exactly on its circle and radial line (a
// refined polygon would converge to the polygon). The first and last radial
// edges are never joined, even for a full turn: a slit; a span over 2 pi
// overlaps itself in the plane. uv = (x, y) of the flat sector. With a
// nonzero `lift` the placement (not the rest shape) rises along a helix:
// vertices at angles <= 0 stay in z = 0, the others at z = lift * angle /
// end_angle (end_angle > 0), so that the two edges of a slit can be told
// apart by position (a start for Newton; the solution does not depend on it).
// With the perturbed pattern, a grid line at angle 0 (a clamp beyond a slit)
// stays straight: its vertices move only along it.
// (rings 2^k + 1)(segments 2^k + 1) vertices, 2 rings segments 4^k triangles.
TriangleMesh annulus(double inner_radius, double outer_radius, int rings, int segments,
                     double start_angle, double end_angle,
                     RectanglePattern pattern = RectanglePattern::alternating, int refinements = 0,
                     double lift = 0.0);

// Uniform refinement: each triangle into four through its edge midpoints,
// midpoints shared by the triangles of an edge and placed at the average of
// the edge's ends; each triangle's uv midpoints come from its own corners (so
// seams survive), material ids are kept. The corner child of corner c of
// triangle t is triangle 4 t + c, the middle child 4 t + 3; old vertices keep
// their indices.
TriangleMesh refine(const TriangleMesh& mesh);

} // namespace sartor::mesh
