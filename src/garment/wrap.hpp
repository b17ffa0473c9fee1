#pragma once
// Wrapping (Igarashi & Hughes, "Clothing Manipulation", UIST 2002): the
// panels of a pattern, sewn into one mesh, are put on a body so that marks
// painted on the panels land on corresponding marks painted on the body.
//  1. Root edges: every mesh edge that crosses a cloth mark. Where it
//     crosses, at a fraction of the mark's arc length, the body mark's point
//     at the same fraction is found (proportional correspondence); each end
//     of the edge is reached by walking on the body surface from there, at
//     the edge's angle to the mark's tangent, as far as the end is from the
//     crossing in the panel. An end of several root edges goes to the mean
//     of its walks, then `offset` above the body point nearest to it.
//  2. Growth: the vertices of triangles with two mapped vertices are ready;
//     the one nearest the marks (mesh distance along rest lengths) is mapped
//     next, from each parent triangle (a mapped triangle across the edge it
//     shares with the triangle of the ready vertex): in the parent's plane,
//     at the proportional foot on the shared edge and the rest altitude, on
//     the far side from the parent. The positions from several parents are
//     averaged. One relaxation step (garment/wrap_relax.hpp) of the mapped
//     part follows each vertex; the whole garment is relaxed at the end.
// The body's signed distance gives the nearest body point of any point
// exactly, so the paper's tracked nearest points (and their migration
// between neighbours) are not needed.

#include "contact/shape.hpp"
#include "garment/pattern.hpp"
#include "garment/wrap_relax.hpp"
#include "mesh/triangle_mesh.hpp"

#include <Eigen/Core>

#include <string>
#include <vector>

namespace sartor::garment {

// A polyline painted on a panel, in panel coordinates (m).
struct ClothMark {
  std::string id;
  int panel = 0; // index into Pattern::panels
  std::vector<Eigen::Vector2d> points;
  std::string where; // file and JSON path, for messages
};

// A cloth mark and the body mark it goes to (points on the body surface).
struct MarkPair {
  std::string id;
  ClothMark cloth;
  std::vector<Eigen::Vector3d> body;
};

// Two lines of the pattern sewn into one (line a's start to line b's start,
// or to its end when `reverse`).
struct SewnLines {
  std::string a, b;
  bool reverse = false;
  std::string where;
};

// A pushpin for rewrapping: a vertex index, or the vertex nearest a point.
struct PinRef {
  int vertex = -1; // < 0: by `point`
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  std::string where;
};

struct WrapMarks {
  std::string body; // a body specification (contact/body_spec.hpp)
  std::vector<SewnLines> seams;
  std::vector<MarkPair> pairs; // body points as given, not yet on the surface
  std::vector<PinRef> pins;    // for rewrapping
};

// The vertex of `positions` a pin names; throws InputError for an index
// outside them.
int pinned_vertex(const PinRef& pin, const std::vector<Eigen::Vector3d>& positions);

// Reads a pattern file that may carry "marks" (docs/wrapping.md): the rest
// goes to the pattern reader. Throws InputError naming the file and entry.
Pattern read_pattern_with_marks(const std::string& path, std::vector<ClothMark>& marks);

// Reads a marks file (docs/wrapping.md). Cloth marks are given in place or
// by the id of one of `pattern_marks`. Throws InputError naming the file and
// the entry (unknown panel, line or mark id, fewer than two points, ...).
WrapMarks read_marks(const std::string& path, const Pattern& pattern,
                     const std::vector<ClothMark>& pattern_marks);

// The panels meshed (mesh/panel_mesher.hpp, `edge_length`, `min_angle_deg`)
// and sewn into one mesh: the lines of each seam (and of the pattern's
// stitches) are given the same number of pieces and their vertices merged.
// material_ids = panel index; positions are the panel coordinates (z = 0).
TriangleMesh sew_panels(const Pattern& pattern, const std::vector<SewnLines>& seams,
                        double edge_length, double min_angle_deg);

// The polyline through `points` with every segment split into pieces no
// longer than `spacing` and every point moved to the nearest body point: a
// path on the body surface.
std::vector<Eigen::Vector3d> body_surface_path(const contact::Shape& body,
                                               const std::vector<Eigen::Vector3d>& points,
                                               double spacing);

struct WrapOptions {
  RelaxParameters relax;
  int growth_relax_steps = 1; // after each mapped vertex
  int final_relax_steps = 100;
  bool subdivide = false;  // adaptive subdivision during the final relaxation
  std::vector<Bone> bones; // no relaxation step sweeps a cloth edge across one (wrap_relax.hpp)
};

// Where a root edge crosses a cloth mark, and where that point belongs.
struct MarkCrossing {
  int pair = 0;
  int a = 0, b = 0;        // the edge's vertices
  double along_edge = 0.0; // the crossing at (1 - t) a + t b
  Eigen::Vector3d target;  // the body mark's point at the same fraction
};

struct MarkMismatch {
  int crossings = 0;
  double max = 0.0, rms = 0.0; // m: body point under the cloth's mark point to its target
};

struct WrapResult {
  TriangleMesh mesh; // the wrapped garment
  std::vector<MarkCrossing> crossings;
  int root_vertices = 0;
  int kept_vertices = 0;         // rewrap: vertices beyond the pins, kept in place
  int split_edges = 0;           // at the end (WrapOptions::subdivide)
  long splits = 0, merges = 0;   // during the final relaxation
  long bone_holds = 0;           // vertex moves held back at the bones
  std::vector<int> growth_order; // the vertices in the order they were mapped (roots first)
  MarkMismatch mismatch;
  EdgeRatios edge_ratios;
  double min_distance = 0.0; // smallest signed distance of a vertex to the body, m
};

// Rewrapping a garment already on the body (the paper's, with pushpins):
// the vertices at least as far (mesh distance from the new marks' root
// vertices) as the nearest pin keep `positions` and are held; the rest are
// pasted and grown again. Without pins, everything is wrapped anew.
struct Rewrap {
  std::vector<Eigen::Vector3d> positions; // the sewn mesh's vertices, placed
  std::vector<int> pins;
};

// Wraps the sewn mesh (sew_panels) onto the body by the mark pairs, whose
// body points lie on the body's surface (body_surface_path); or rewraps it.
// Throws InputError when a mark crosses no edge, some panel is not reached
// from any mark (naming them), or a rewrap's garment does not match.
WrapResult wrap(const TriangleMesh& sewn, const Pattern& pattern,
                const std::vector<MarkPair>& pairs, const contact::Shape& body,
                const WrapOptions& options, const Rewrap* rewrap = nullptr);

// One level of adaptive sqrt(3) subdivision (Kobbelt; the paper's) kept
// over a base mesh while the cloth relaxes. A base edge AB cuts into the
// body when it passes through the sphere of radius |AB| that touches the
// body at A's (or B's) nearest body point from inside (the body's least
// radius of concern). A cutting edge's two triangles get a vertex at their
// centroids (`offset` above the body at least) and the edge is flipped to
// join them: six triangles for two. A split edge is merged back (the two
// base triangles return) once it clears the sphere by 10 % of |AB|: the
// margin keeps an edge at the threshold from splitting and merging in turn.
// Edges on seams (two rest frames), creases, and edges next to a triangle
// already split are left. The base vertices stay the refined meshes' first
// ones; the centres follow, two per split edge.
class AdaptiveSubdivision {
public:
  explicit AdaptiveSubdivision(const TriangleMesh& base);
  // Splits and merges by `cloth`'s positions (its mesh the base or the last
  // refinement of this object) and gives `cloth` the new refined mesh when
  // the split edges change. Returns whether they did.
  bool update(ClothOnBody& cloth);
  // The base mesh's edges: a drag's dependency graph follows them, so that
  // its vertices keep their numbers while edges split and merge.
  const RestEdges& base_edges() const { return base_edges_; }
  int split_edges() const { return int(split_.size()); } // now
  long splits() const { return splits_; }                // so far
  long merges() const { return merges_; }

private:
  TriangleMesh base_;
  RestEdges base_edges_;
  std::vector<Hinge> hinges_; // those that may be split
  std::vector<int> split_;    // into hinges_, in the order of their centres
  long splits_ = 0, merges_ = 0;
};

// `steps` relaxation steps, each followed by subdivision.update(cloth).
void relax_adaptively(ClothOnBody& cloth, AdaptiveSubdivision& subdivision, int steps);

// The mark mismatch of positions: for every crossing, the distance from the
// body point nearest the cloth's mark point to the body mark's point.
MarkMismatch mark_mismatch(const std::vector<MarkCrossing>& crossings,
                           const std::vector<Eigen::Vector3d>& positions,
                           const contact::Shape& body);

} // namespace sartor::garment
