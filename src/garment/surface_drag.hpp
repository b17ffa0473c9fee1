#pragma once
// Surface dragging and pushpins (Igarashi & Hughes, "Clothing
// Manipulation", UIST 2002): a grabbed cloth vertex is moved along the body
// surface and the motion is propagated over the cloth through a dependency
// graph, attenuated near pushpins; relaxation (garment/wrap_relax.hpp)
// follows every step.
//  * The graph: from the grabbed vertex (the root), vertices are taken in
//    order of their distance along rest edge lengths (Dijkstra); a vertex's
//    parents are its neighbours taken before it.
//  * Propagation: each vertex's motion is the mean over its parents of the
//    parent's motion carried from the parent's local frame to the vertex's:
//    z the body normal at the vertex, x the parent-to-child edge direction
//    with its z part removed, y = z cross x.
//  * Pushpins: with a, b the mesh distances of a vertex to the grabbed and
//    the pinned vertex and c that between them, the vertex moves by
//    (c - a + b) / 2c of its motion, clamped to [0, 1] (1 where a - b <= -c,
//    0 where a - b >= c); the least over the pins. Pinned vertices and the
//    grabbed one are held during relaxation.
//  * Every step also pulls vertices within `pull_band` of the body halfway
//    to their `offset` above it (the paper's stabilisation).

#include "garment/wrap_relax.hpp"

#include <Eigen/Core>

#include <string>
#include <vector>

namespace sartor::garment {

struct DependencyGraph {
  int root = 0;
  std::vector<int> order;                // processing order, root first (reachable vertices)
  std::vector<std::vector<int>> parents; // per vertex
  std::vector<double> distance;          // from the root along rest lengths, m (inf: unreached)
};
DependencyGraph dependency_graph(const RestEdges& edges, int root);

// The paper's ratio for mesh distances a (to the grabbed vertex), b (to the
// pin) and c (grabbed to pin, > 0).
double attenuation_ratio(double a, double b, double c);

// Per vertex, the least ratio over `pins` (1 everywhere without pins).
std::vector<double> attenuation(const RestEdges& edges, int grabbed, const std::vector<int>& pins);

struct DragOptions {
  int relax_steps = 3;      // after every drag step
  double pull_band = 0.036; // m: vertices nearer the body are pulled halfway to the offset
};

class SurfaceDrag {
public:
  // Builds the graph and the attenuation over `graph_edges` (the cloth's
  // edges when null; the base mesh's when the cloth is subdivided
  // adaptively, so that the graph's vertices keep their numbers while
  // edges split and merge); holds the grabbed vertex and the pins fixed in
  // `cloth` (released by release()). Throws InputError for a vertex outside
  // the graph or a pin on the grabbed vertex.
  SurfaceDrag(ClothOnBody& cloth, int grabbed, std::vector<int> pins, const DragOptions& options,
              const RestEdges* graph_edges = nullptr);

  // One drag step: `displacement` is projected onto the body's tangent plane
  // at the grabbed vertex, propagated, attenuated and applied; then the
  // cloth near the body is pulled to it and relaxed.
  void step(const Eigen::Vector3d& displacement);
  void release();

  const DependencyGraph& graph() const { return graph_; }
  const std::vector<double>& ratios() const { return ratios_; }

private:
  void propagate(const Eigen::Vector3d& root_motion);

  ClothOnBody& cloth_;
  int grabbed_;
  std::vector<int> pins_;
  DragOptions options_;
  DependencyGraph graph_;
  std::vector<double> ratios_;
  std::vector<Eigen::Vector3d> motion_;
};

// A drag script (docs/wrapping.md): the body and the drags.
struct ScriptedDrag {
  int vertex = 0;
  std::vector<Eigen::Vector3d> steps; // displacements, m
  std::vector<int> pins;
};
struct DragScript {
  std::string body; // a body specification (contact/body_spec.hpp)
  DragOptions options;
  std::vector<ScriptedDrag> drags;
};

// Reads a drag script for a garment with `positions` (vertices may be given
// as a point: the nearest vertex). Throws InputError naming the file and entry.
DragScript read_drag_script(const std::string& path, const std::vector<Eigen::Vector3d>& positions);

} // namespace sartor::garment
