#pragma once
// Pre-folding (thesis §6.2): a panel's creased fold lines split it into a
// warping region and a stationary region; the warping region turns rigidly
// about the line's chord by the crease's angle before the simulation starts,
// so that sharp features (lapels, pleats) begin folded instead of being left
// to a simulation that starts flat. The crease's bending rest angle is the
// same angle. docs/pleats.md.

#include "garment/pattern.hpp"
#include "mesh/panel_mesher.hpp"
#include "mesh/triangle_mesh.hpp"

#include <Eigen/Core>

#include <vector>

namespace sartor::garment {

// One creased fold line of a meshed panel.
struct MeshedFold {
  std::string line;
  Eigen::Vector2d start = Eigen::Vector2d::Zero(), end = Eigen::Vector2d::Zero(); // the chord
  std::vector<int> vertices; // panel mesh vertices on the line, start to end
  bool left = true;          // the warping region is left of start -> end
  // Signed rotation of the warping region about start -> end, rad: > 0 turns
  // the left side towards +z (the side the panel's counter-clockwise
  // triangles face).
  double rotation = 0.0;
  // The crease's dihedral rest angle in the convention of element/bending.hpp
  // (> 0: a ridge seen from the triangles' normal side).
  double rest_angle = 0.0;
  double stiffness_factor = 1.0; // Crease::pressed
};

// The creased fold lines of `panel` as meshed in `meshed` (its lines in
// mesh_panel's order). `outside_is_normal_side`: the panel's
// counter-clockwise triangles face the outside of the garment (away from the
// body), so that a crease "toward outside" turns its region towards +z.
std::vector<MeshedFold> meshed_folds(const Panel& panel, const PanelMesh& meshed,
                                     bool outside_is_normal_side);

// The vertices of the warping region of `fold` on a flat mesh (z = 0): those
// strictly on the fold's side of its chord's line that are connected to the
// fold line through such vertices.
std::vector<int> warping_region(const TriangleMesh& flat, const MeshedFold& fold);

// The pre-folded positions of a flat panel mesh (panel coordinates, z = 0):
// folds are applied in order of growing warping region, each turning its
// region (which may hold smaller regions already turned) rigidly about its
// chord, so that nested folds (pleats) compose. Throws InputError naming the
// line when a fold's warping region is empty.
std::vector<Eigen::Vector3d> prefold(const TriangleMesh& flat,
                                     const std::vector<MeshedFold>& folds);

// The crease edges of `folds` (consecutive vertices of each line, offset by
// `first_vertex`) with their rest angles.
std::vector<CreaseEdge> crease_edges(const std::vector<MeshedFold>& folds, int first_vertex);

} // namespace sartor::garment
