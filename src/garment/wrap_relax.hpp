#pragma once
// Cloth kept on a body by the relaxation of Igarashi & Hughes, "Clothing
// Manipulation" (UIST 2002; /work/shared/seeds/001): the approximate,
// geometric placement that wrapping (garment/wrap.hpp) and surface dragging
// (garment/surface_drag.hpp) share. It is not mechanics: it moves the cloth
// towards a plausible rest configuration before the drape solver takes over.
//
// One relaxation step moves every active vertex by the sum of
//  * the reference-triangle pull: each triangle's rest shape (from its
//    material (u, v)) is laid, face up, in the plane normal to a temporary
//    normal (the body's normal near the body, the cloth's far from it,
//    blended between), centred on the triangle's centroid and turned to
//    best fit it; each vertex moves towards its copies (mean over its
//    triangles). Stretch, shrinkage and flipped triangles recover together;
//  * flattening: each interior edge moves its two wing vertices towards the
//    plane of the hinge's four vertices and its two edge vertices the
//    opposite way (a dihedral spring towards 180 degrees);
//  * gravity: a constant step down (constant speed);
// except that friction holds a vertex in contact with the body when its
// move heads down the body's surface and is shorter than a threshold. The
// moved vertex is then pushed back out to `offset` above the body.
// Bones (the paper's "collision detection with bones"): only vertices are
// kept out of the body, so a long step can carry a cloth edge through a thin
// limb, and the cloth cannot recover from that. A step that would sweep an
// edge across a bone (a segment inside the limb) is held back: both ends of
// such an edge keep their place, until no moved edge sweeps across one.
//
// "Front" of a panel: the side from which its material (u, v) axes appear
// counter-clockwise (u right, v up). Wrapping puts the front away from the
// body.

#include "contact/body.hpp"
#include "contact/mannequin.hpp"
#include "contact/shape.hpp"
#include "mesh/triangle_mesh.hpp"

#include <Eigen/Core>

#include <array>
#include <vector>

namespace sartor::garment {

// The lengths are in the body's units (metres); the paper's values (its
// bodies are 1 to 2 units tall) are the defaults.
struct RelaxParameters {
  double offset = 0.012;     // vertices are kept this far above the body
  double near_body = 0.012;  // temporary normal = body normal closer than this
  double far_body = 0.08;    // = cloth normal farther than this
  double stretch_rate = 0.5; // fraction of the way to the reference copies per step
  double flatten_rate = 0.1; // fraction of a hinge's out-of-plane offset per step
  // m down per step (constant speed). Small against the reference-triangle
  // pull: a hanging loop of a sleeve stretched without end at 1 mm.
  double gravity_step = 0.0001;
  double friction_limit = 0.002; // m: a shorter downhill move of a vertex in contact is held
  // m: the longest move of a vertex in one step. Only vertices are kept out
  // of the body; a longer step can carry one through a thin limb.
  double max_step = 0.006;
  Eigen::Vector3d down = -Eigen::Vector3d::UnitZ();
};

// A body at rest (time 0) as a Shape in world coordinates.
class BodyAtRest : public contact::Shape {
public:
  explicit BodyAtRest(const contact::Body& body) : body_(body) {}
  contact::SurfaceQuery query(const Eigen::Vector3d& p) const override {
    return body_.query(p, 0.0);
  }
  std::string describe() const override { return body_.describe(); }

private:
  const contact::Body& body_;
};

// The nearest body point and the outward unit normal at it.
struct BodyPoint {
  double distance = 0.0;
  Eigen::Vector3d closest = Eigen::Vector3d::Zero();
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ(); // unit
};
BodyPoint nearest_body_point(const contact::Shape& body, const Eigen::Vector3d& p);

// `p` itself when it is at least `offset` above the body, else the point
// `offset` above its nearest body point.
Eigen::Vector3d keep_above(const contact::Shape& body, const Eigen::Vector3d& p, double offset);

// The mesh's unique edges (a < b) and each one's rest length: the length in
// the material (u, v) of a triangle that has it (across a seam the two
// triangles' lengths are averaged).
struct RestEdges {
  std::vector<std::array<int, 2>> edges;
  std::vector<double> lengths;                                 // m
  std::vector<std::vector<std::pair<int, double>>> neighbours; // per vertex: (vertex, rest length)
};
RestEdges rest_edges(const TriangleMesh& mesh);

// Whether the surface swept by an edge moving from (a0, b0) to (a1, b1)
// (the bilinear patch, as its two triangles a0 b0 b1 and a0 b1 a1) meets the
// segment from `start` to `end`.
bool edge_sweep_meets_segment(const Eigen::Vector3d& a0, const Eigen::Vector3d& b0,
                              const Eigen::Vector3d& a1, const Eigen::Vector3d& b1,
                              const Eigen::Vector3d& start, const Eigen::Vector3d& end);

class ClothOnBody {
public:
  // `mesh`'s positions are the cloth's start; throws InputError when the
  // mesh is not valid or has non-manifold edges.
  ClothOnBody(TriangleMesh mesh, const contact::Shape& body, const RelaxParameters& parameters);

  const TriangleMesh& mesh() const { return mesh_; }
  const RestEdges& edges() const { return edges_; }
  const contact::Shape& body() const { return body_; }
  const RelaxParameters& parameters() const { return parameters_; }
  std::vector<Eigen::Vector3d>& positions() { return mesh_.positions; }
  const std::vector<Eigen::Vector3d>& positions() const { return mesh_.positions; }
  // Vertices that relaxation moves and triangles it uses: all by default;
  // wrapping activates them as it maps them.
  std::vector<bool> active;
  // Vertices relaxation leaves where they are (pushpins, a grabbed vertex).
  std::vector<bool> fixed;
  // Segments inside the body (contact::body_bones, in world coordinates)
  // that no cloth edge may sweep across; none by default.
  std::vector<Bone> bones;

  // `steps` relaxation steps over the active part.
  void relax(int steps);
  // The same cloth on another mesh (a refinement of this one: its first
  // vertices are this mesh's, which keep `active` and `fixed`; the others
  // are active and free). Throws InputError for a mesh that is not valid.
  void replace_mesh(TriangleMesh mesh);
  // Puts back at `before` both ends of every edge between active vertices
  // whose move from `before` to positions() sweeps across a bone, until no
  // moved edge does. Returns the number of vertices put back.
  int hold_back_at_bones(const std::vector<Eigen::Vector3d>& before);
  // Vertices put back so far, by relax() and hold_back_at_bones().
  long bone_holds() const { return bone_holds_; }

private:
  void add_reference_triangle_pull(std::vector<Eigen::Vector3d>& pull, std::vector<int>& count,
                                   const std::vector<BodyPoint>& near) const;
  void add_flattening(std::vector<Eigen::Vector3d>& move) const;
  bool held_by_friction(const Eigen::Vector3d& move, const BodyPoint& near) const;

  TriangleMesh mesh_;
  const contact::Shape& body_;
  RelaxParameters parameters_;
  RestEdges edges_;
  std::vector<Hinge> hinges_;
  long bone_holds_ = 0;
};

// Each edge's current length over its rest length: min, max and mean.
struct EdgeRatios {
  double min = 0.0, max = 0.0, mean = 0.0;
};
EdgeRatios edge_length_ratios(const RestEdges& edges,
                              const std::vector<Eigen::Vector3d>& positions);

// The smallest signed distance of a vertex to the body, m.
double min_body_distance(const contact::Shape& body, const std::vector<Eigen::Vector3d>& positions);

} // namespace sartor::garment
