#pragma once
// Seams: which boundary lines of the panels are sewn together, and the
// penalty springs that sew them (Sensitive Couture §7; the seam lines are what
// the garment front end's seam creation, thesis ch. 3, produces).
//
// A seam joins two seam lines, each an ordered polyline of mesh vertices along
// panel boundaries; in a T-seam line b runs inside a panel instead (an outer
// layer's edge sewn onto an interior line, thesis §3.3.4: a patch pocket).
// The lines are paired start to start (start to end when `reverse`) and
// matched by their normalised arc length, measured in material (u, v)
// coordinates so that the panels' rest lengths decide, not their initial
// placement:
//  * lines with as many vertices at the same normalised positions (within
//    1e-6) are sewn vertex to vertex;
//  * otherwise every vertex of each line emits a vertex-to-edge spring to the
//    point of the other line at the same normalised arc length (lines of
//    different lengths are eased in proportionally, as a tailor gathers).
// Springs have zero rest length, so a closed seam joins the lines exactly
// up to the penalty's small residual gap.
//
// Stiffness: the seam is a line spring of stiffness kappa per unit length of
// seam, N/m^2, lumped to the vertices by their tributary lengths (half of
// each adjacent segment). Automatic kappa = penalty * E / h, E the membrane's
// largest initial modulus (N/m) and h the seam's mean segment length (m): the
// seam is `penalty` times stiffer than a strip of membrane one element wide,
// so its residual gap is about strain * h / penalty. A seam's `certainty`
// scales its kappa.

#include "mesh/triangle_mesh.hpp"

#include <array>
#include <string>
#include <utility>
#include <vector>

namespace sartor {

struct Seam {
  std::string name;
  std::vector<int> a; // seam line: mesh vertices in order along a panel boundary
  std::vector<int> b;
  bool reverse = false;   // pair a's start with b's end
  double certainty = 1.0; // in (0, 1]: multiplies the seam's stiffness
  bool t_seam = false;    // line b runs on edges inside a panel, not on its boundary
};

// A zero-rest-length spring: vertex-to-vertex (vertices[0] to vertices[1]) or
// vertex-to-edge (vertices[0] to (1 - s) x_vertices[1] + s x_vertices[2]).
struct SeamSpring {
  std::array<int, 3> vertices{{-1, -1, -1}};
  bool to_edge = false;
  double s = 0.0;         // edge parameter (vertex-to-edge only)
  double stiffness = 0.0; // N/m
  double length = 0.0;    // the length of seam it sews (its tributary), m
  int seam = 0;           // index in the seam list
  int vertex_count() const { return to_edge ? 3 : 2; }
};

struct SeamStiffness {
  double modulus = 0.0; // the membrane's largest initial modulus, N/m
  double penalty = 100.0;
  double per_length = 0.0; // kappa, N/m^2; > 0 overrides the automatic choice
};

// Reads a seam file (docs/formats.md, "Seam files") and checks it against the
// mesh (check_seams). Errors name the file and the seam (index and name).
std::vector<Seam> read_seams(const std::string& path, const TriangleMesh& mesh);

// Writes seams in the format read_seams reads (atomically).
void write_seams(const std::string& path, const std::vector<Seam>& seams);

// Throws InputError ("CONTEXT: seam I ('NAME'): ...") when a line has fewer
// than two vertices, names a vertex outside the mesh or twice, or two
// consecutive vertices are not the ends of a boundary edge (an edge of
// exactly one triangle; of two for line b of a T-seam); or certainty is not
// in (0, 1].
void check_seams(const TriangleMesh& mesh, const std::vector<Seam>& seams,
                 const std::string& context);

// Cumulative material arc length along a seam line (0 at its first vertex), m:
// each segment measured in the uv of the triangle that owns the edge.
std::vector<double> material_arc_length(const TriangleMesh& mesh, const std::vector<int>& line);

// Whether the seam is sewn vertex to vertex (see above).
bool seam_is_matched(const TriangleMesh& mesh, const Seam& seam);

// The springs that sew the seams (checked first).
std::vector<SeamSpring> seam_springs(const TriangleMesh& mesh, const std::vector<Seam>& seams,
                                     const SeamStiffness& stiffness);

// A change of the material coordinates, per triangle corner (as
// TriangleMesh::material_uv), m.
using MaterialChange = std::vector<std::array<Eigen::Vector2d, 3>>;
// The change of a spring's stiffness (N/m) and edge parameter.
struct SeamSpringChange {
  double stiffness = 0.0;
  double s = 0.0;
};
// The change of every spring of seam_springs (in its order) when the
// material coordinates move by `change`: exact, by forward-mode automatic
// differentiation (common/autodiff.hpp) through the same construction
// (tributary and total arc lengths, the automatic kappa, the normalised arc
// lengths that place vertex-to-edge springs). Which springs there are, and
// between which vertices, is held.
std::vector<SeamSpringChange> seam_spring_changes(const TriangleMesh& mesh,
                                                  const std::vector<Seam>& seams,
                                                  const SeamStiffness& stiffness,
                                                  const MaterialChange& change);

// The vertex pairs of matched seams, (a[i], b[i or reversed]); throws
// InputError naming the first seam that is not matched or is a T-seam (its
// merged edges would join three triangles). Pairs of a vertex
// with itself (a dart's tip) are left out.
std::vector<std::pair<int, int>> matched_vertex_pairs(const TriangleMesh& mesh,
                                                      const std::vector<Seam>& seams);

// The distance between a spring's emitting vertex and its anchor, m.
double seam_spring_gap(const SeamSpring& spring, const std::vector<Eigen::Vector3d>& positions);

// The largest distance between a spring's vertex and its anchor on the other
// line, over all springs, for the given positions (mesh numbering), m.
double largest_seam_gap(const std::vector<SeamSpring>& springs,
                        const std::vector<Eigen::Vector3d>& positions);

} // namespace sartor
