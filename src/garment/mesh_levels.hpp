#pragma once
// Progressive refinement of a garment (Sensitive Couture §7.1; the cascadic
// multigrid of Bornemann and Deuflhard 1996): the drape is solved on a
// coarse meshing of the panels, carried to a finer meshing of the same
// panels, solved again, and so on to the target edge length.
//
// Levels. TAGCON places the packs and pairs the seam lines on the pattern's
// curves, not on a mesh, so one construction serves every level: each level
// is build_garment_mesh of that construction at its own edge length, and its
// seams pair the same lines, re-discretised.
//
// Prolongation. A vertex of the finer level lies in one panel; it is located
// in the coarser level's triangulation of that panel in rest (u, v)
// coordinates, and takes the coarse triangle's barycentric combination of
// any per-vertex field (3D positions, friction anchors). A fine vertex on a
// curved outline may lie just outside the coarse panel (the coarse outline
// is a coarser polygon through the same curve): it takes the barycentric
// coordinates, extrapolated, of the nearest coarse triangle, so that an
// affine field is still carried exactly. Per-triangle state (creep) takes
// the value of the coarse triangle that holds the fine triangle's centroid.
// Each side of a seam is interpolated in its own panel, so the two sides of a
// closed seam land a little apart: close_seams then puts the paired vertices
// at their mean.

#include "garment/garment_mesh.hpp"
#include "mesh/seams.hpp"
#include "mesh/triangle_mesh.hpp"

#include <Eigen/Core>

#include <array>
#include <vector>

namespace sartor::garment {

struct LevelOptions {
  double target_edge_length = 0.04; // m: the finest level's
  int levels = 0;                   // 0: automatic
  double coarsest_edge_length = 0;  // m; 0: automatic (or from `levels`)
  // Automatic levels: the coarsest is the longest target * 2^k no longer
  // than coarsest_limit whose mesh still has this many triangles per panel
  // on average, and there are at most max_levels levels. The limit: a
  // coarse triangle's chord cuts h^2 / 8R into a convex body, and a drape
  // on 16 cm triangles cut 38 mm into the mannequin's arms, so its 8 cm
  // level, lifted out of them, started with 81 J of potential (2 J at
  // rest) and did not converge.
  double min_triangles_per_panel = 20;
  double coarsest_limit = 0.08; // m
  int max_levels = 4;
};

// The edge lengths of the levels, coarse to fine; the last is the target,
// each is at most twice the next. With `levels` given: target * 2^k,
// k = levels - 1 .. 0. With `coarsest_edge_length` given: the fewest levels
// from it to the target in equal ratios of at most 2. Otherwise automatic
// (LevelOptions). Throws InputError for a level count below 1, a coarsest
// edge shorter than the target, or both given.
std::vector<double> level_edge_lengths(const Construction& construction,
                                       const PanelMeshOptions& mesh_options,
                                       const LevelOptions& options);

// The garment mesh without the panels not `kept` (per pattern panel):
// vertices renumbered in order, seams with them (a seam must join kept
// panels only). material_ids stay the pattern's panel indices.
GarmentMesh keep_panels(const GarmentMesh& garment, const std::vector<bool>& kept);

// Where a fine vertex (or triangle centroid) lies in the coarse mesh.
struct CoarseLocation {
  int triangle = -1;               // in the coarse mesh
  std::array<double, 3> weights{}; // barycentric, sum 1; one negative when outside
  double outside = 0.0;            // distance outside the coarse panel, m (0 inside)
};

// Barycentric prolongation from a coarse to a fine meshing of the same
// panels. Both meshes' material_ids give each triangle's panel (the same
// numbering on both) and material_uv its rest coordinates; every vertex lies
// in one panel. Throws InputError when a fine panel has no coarse triangles,
// or a vertex's triangles disagree on its panel or its rest coordinates.
class Prolongation {
public:
  Prolongation(const TriangleMesh& coarse, const TriangleMesh& fine);

  // A per-vertex field of the coarse mesh on the fine mesh's vertices.
  template <class T>
  std::vector<T> vertex_field(const std::vector<T>& coarse) const;
  // Per-triangle state: the coarse triangle holding each fine centroid's.
  template <class T>
  std::vector<T> triangle_field(const std::vector<T>& coarse) const;

  const std::vector<CoarseLocation>& vertex_locations() const { return vertices_; }
  const std::vector<CoarseLocation>& centroid_locations() const { return centroids_; }
  // The farthest a fine vertex lies outside its coarse panel, m.
  double largest_outside_distance() const;

private:
  std::vector<std::array<int, 3>> coarse_triangles_;
  std::vector<CoarseLocation> vertices_;
  std::vector<CoarseLocation> centroids_;
};

// Per vertex: its panel (material id of its triangles) and its rest (u, v)
// coordinates. Throws InputError as Prolongation does, or for a vertex in
// no triangle.
struct VertexRest {
  std::vector<int> panel;
  std::vector<Eigen::Vector2d> uv;
};
VertexRest vertex_rest_coordinates(const TriangleMesh& mesh);

struct SeamClosure {
  double gap_before = 0.0; // largest seam gap before closing, m
  double gap_after = 0.0;  // after, m
};
// Puts the vertices a seam sews together at their mean: vertices sewn vertex
// to vertex (with those they are sewn to through other seams, a corner
// where three lines meet) at their mean; a vertex sewn to an edge of the
// other line halfway to its partner point there.
SeamClosure close_seams(const TriangleMesh& mesh, const std::vector<Seam>& seams,
                        std::vector<Eigen::Vector3d>* positions);

template <class T>
std::vector<T> Prolongation::vertex_field(const std::vector<T>& coarse) const {
  std::vector<T> fine;
  fine.reserve(vertices_.size());
  for (const CoarseLocation& at : vertices_) {
    const auto& corners = coarse_triangles_[std::size_t(at.triangle)];
    fine.push_back(at.weights[0] * coarse[std::size_t(corners[0])] +
                   at.weights[1] * coarse[std::size_t(corners[1])] +
                   at.weights[2] * coarse[std::size_t(corners[2])]);
  }
  return fine;
}

template <class T>
std::vector<T> Prolongation::triangle_field(const std::vector<T>& coarse) const {
  std::vector<T> fine;
  fine.reserve(centroids_.size());
  for (const CoarseLocation& at : centroids_)
    fine.push_back(coarse[std::size_t(at.triangle)]);
  return fine;
}

} // namespace sartor::garment
