#pragma once
// Keeping a cloth mesh fit for its rest shape after a pattern edit moved the
// material coordinates (Sensitive Couture §6, "Fast and slow remeshing"):
// measure the triangles' shape in (u, v), first try Delaunay smoothing (edge
// flips, vertices kept), and when the quality stays poor rebuild the mesh
// and carry the state over by barycentric interpolation in (u, v).

#include "mesh/triangle_mesh.hpp"

#include <Eigen/Core>

#include <array>
#include <vector>

namespace sartor {

// Incircle diameter over longest edge, times sqrt(3) so that an equilateral
// triangle scores 1 (a right isosceles one sqrt(3) (sqrt(2) - 1) = 0.717).
// Corners are (u, v) in counter-clockwise order; a degenerate or clockwise
// (folded) triangle scores 0, since no flip mends either.
double triangle_quality(const std::array<Eigen::Vector2d, 3>& uv);

// The smallest triangle_quality over the mesh's triangles in material
// coordinates; 1 for a mesh without triangles.
double worst_quality(const TriangleMesh& mesh);

struct FlipReport {
  int flips = 0;
  double worst_before = 0, worst_after = 0; // worst_quality
};

// Lawson's edge flips in material coordinates until every flippable interior
// edge is Delaunay: the two angles facing it sum to at most pi + 1e-9 rad
// (the margin keeps co-circular quads, a structured grid's squares, as they
// are). An edge is flippable when its two triangles are counter-clockwise in
// (u, v) and run it in opposite directions, give its ends the same (u, v) (a
// closed tube's seam does not), have the same material id, it is no crease,
// the other diagonal is not an edge already, and the flipped triangles are
// counter-clockwise with material area. A flip rewrites the two triangles in
// their slots, keeping their material id and taking every corner's (u, v)
// from the old corners of that vertex. Positions, boundary edges and creases
// stay as they are. Per-triangle state of the caller moves with
// source_triangles(copy before, mesh after). Throws InputError for a mesh
// that validate() or interior_edges() rejects, and std::logic_error if the
// flips fail to end (Lawson's algorithm ends: a bug).
FlipReport delaunay_smoothing(TriangleMesh& mesh);

// A point of the material domain in a triangle of a mesh.
struct BarycentricLocation {
  int triangle = -1;
  Eigen::Vector3d weights = Eigen::Vector3d::Zero(); // of the triangle's corners, sum 1
};

// For each point (u, v): the triangle of `old_mesh` holding it, with its
// barycentric weights (each >= -1e-12). A point outside every triangle (a
// moved outline) gets the nearest triangle and the weights of the point
// on it closest to the query, so all weights are >= 0. Material ids are
// groups that must not mix (callers pass a panel index per triangle: panels
// overlap in (u, v), each with its own grain coordinates): with
// `point_groups` given (one per point), a point is located only among the
// triangles whose material id (0 when the mesh has none) is its group.
// Empty `point_groups`: every triangle is a candidate. Throws InputError for
// a point that is not finite, a group with no triangles, or a group list of
// the wrong length.
std::vector<BarycentricLocation> locate_in_material(const TriangleMesh& old_mesh,
                                                    const std::vector<Eigen::Vector2d>& points,
                                                    const std::vector<int>& point_groups);

// The 3D positions of `old_mesh` interpolated at the located points, m.
std::vector<Eigen::Vector3d> transfer_positions(const TriangleMesh& old_mesh,
                                                const std::vector<BarycentricLocation>& at);

// For each triangle of `new_mesh`, the triangle of `old_mesh` that holds its
// (u, v) centroid (the nearest one outside), searched in its own group when
// new_mesh has material ids (as locate_in_material), so that per-triangle
// state (creep) can be copied from it.
std::vector<int> source_triangles(const TriangleMesh& old_mesh, const TriangleMesh& new_mesh);

} // namespace sartor
