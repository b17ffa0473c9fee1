#pragma once
// The cloth mesh of a case: a generator or an OBJ file, its uniform
// refinement and its placement (waves, rotation, translation). The options
// are read once into a typed MeshCase, each value checked on its own and
// only those the chosen generator uses; the mesh is built from it.

#include "app/cli.hpp"
#include "mesh/generators.hpp"
#include "mesh/panels.hpp"
#include "mesh/triangle_mesh.hpp"

#include <Eigen/Core>

#include <optional>
#include <string>
#include <vector>

namespace sartor {

// The mesh options, declared by this module.
const std::vector<OptionSpec>& mesh_option_specs();

// --mesh-waves N,A,R0 (see apply_placement_waves).
struct PlacementWaves {
  double count = 0.0;        // N, a whole number
  double amplitude = 0.0;    // A, m
  double start_radius = 0.0; // R0, m
  std::string text;          // as given, for messages
};

struct MeshCase {
  std::string kind = "rectangle"; // --mesh
  std::string file;               // --mesh-file (obj)
  // The generator's parameters; those the kind does not use keep their defaults.
  double width = 1.0, height = 1.0, radius = 0.5, inner_radius = 0.25; // m
  int nx = 10, ny = 10, nx_front = 10, ny_front = 10;
  int rings = 8, segments = 32, rows = 8;
  mesh::RectanglePattern pattern = mesh::RectanglePattern::alternating;
  double angle_from = 0.0, angle_to = 360.0; // annulus, degrees
  double lift = 0.0;                         // annulus, m
  double cap_angle = 0.5;                    // sphere cap, rad
  double gap = 0.15;                         // tube_panels, m
  int refine = 0;                            // --mesh-refine
  bool snap_boundary = false;                // disk
  std::optional<PlacementWaves> waves;
  double rotate_x = 0.0; // degrees
  Eigen::Vector3d translate = Eigen::Vector3d::Zero();
};

// Throws InputError naming the option for a malformed value, an unknown
// kind, obj without --mesh-file, or --mesh-snap-boundary off a disk. Without
// `generated` the cloth comes from elsewhere (a drape's garment): only its
// refinement and placement are read, and the kind is empty.
MeshCase read_mesh_case(const Options& options, bool generated = true);

// --mesh tube_panels: its two panels and their seams.
mesh::PanelMesh tube_panels_mesh(const MeshCase& mesh_case);

// The mesh the case describes (or `given`, in place of --mesh), with
// `extra_refinements` more uniform refinements than --mesh-refine asks for;
// `refinements` gets the total. Throws InputError for a mesh past the size
// limit or a bad OBJ file.
TriangleMesh build_mesh(const MeshCase& mesh_case, int extra_refinements, int* refinements,
                        const TriangleMesh* given);

// --mesh-waves N,A,R0: a small out-of-plane imperfection of the placement,
// applied in the mesh's own frame (before --mesh-rotate-x and
// --mesh-translate), about its z axis:
//     z += A ((r - R0) / (R - R0))^2 cos(N theta)   for r > R0,
// R the largest distance of a vertex from the axis. A flat, symmetric start
// (a Cusick specimen) is a saddle that a static or damped solve need never
// leave; N waves seed the N folds (nodes) a real drape forms.
// Throws InputError when the waves start beyond the mesh.
void apply_placement_waves(const PlacementWaves& waves, TriangleMesh& mesh);

} // namespace sartor
