#pragma once
// Triangulates one flat pattern panel: constrained Delaunay refinement
// (CGAL's 2D mesher, Ruppert/Shewchuk style) to a target edge length and a
// minimum angle, interior lines as constrained edges, material (u, v) from
// the grain line, placed flat in z = 0 in panel coordinates.
//
// Seam lines: every line is first split into n pieces of equal arc length
// (n = pieces_for(length, edge_length), or forced per outline line id so that
// two lines to be sewn together get the same n). The mesher may still split
// such a piece (Ruppert splits a constrained edge that a new vertex would
// encroach). When that happens to a line whose n is not forced, the line's n
// is doubled and the panel meshed again (up to max_rounds times); a forced
// line keeps its n, and its vertex list then holds the mesher's extra
// vertices too, flagged by MeshedLine::split_by_mesher. The mesh follows a
// curved line by the chords between those points (a polyline's own corners
// are not kept: give a corner that matters its own line). Interior lines may
// be split by the mesher freely; their vertex lists hold every vertex on them.

#include "garment/pattern.hpp"
#include "mesh/triangle_mesh.hpp"

#include <map>
#include <string>
#include <vector>

namespace sartor {

struct PanelMeshOptions {
  double edge_length = 0.02;         // m: longest triangle edge
  double min_angle_deg = 25;         // smallest triangle angle, at most 33
  std::map<std::string, int> pieces; // line id -> forced number of pieces
  int max_rounds = 4;                // meshings when unforced lines get split
};

struct MeshedLine {
  std::string id;
  bool interior = false;
  int pieces = 0;               // equal arc-length pieces the line was given
  bool forced = false;          // pieces came from PanelMeshOptions::pieces
  bool split_by_mesher = false; // vertices holds more than pieces + 1 vertices
  std::vector<int> vertices;    // mesh vertices from the line's start to its end
};

struct PanelMesh {
  TriangleMesh mesh;             // positions (x, y, 0) in panel coordinates
  std::vector<MeshedLine> lines; // outline lines in (counter-clockwise) order, then interior
  double min_angle_deg = 0;      // over all triangles
  // Over the triangles with no vertex where constrained edges meet at less
  // than the requested angle (there the input itself is sharper).
  double min_angle_regular_deg = 0;
  double area = 0;          // sum of the triangles' areas, m^2
  double boundary_area = 0; // of the polygon through the outline's mesh vertices
  int rounds = 0;           // meshings done
};

// Boundary pieces are at most this fraction of the edge length: then a right
// isosceles triangle on a piece still meets the size bound, and CGAL has no
// cause to split pieces (measured on the sample patterns: with pieces of the
// full edge length every line was split; at 1/sqrt(2) none up to 30 degrees).
constexpr double boundary_piece_fraction = 0.7071067811865476;

// Equal pieces no longer than boundary_piece_fraction * edge_length, at least one.
int pieces_for(double length, double edge_length);

// Throws InputError (naming the panel) for a non-positive edge length, a
// minimum angle outside (0, 33] degrees, or a forced count below what the
// outline needs to stay a polygon.
PanelMesh mesh_panel(const garment::Panel& panel, const PanelMeshOptions& options);

} // namespace sartor
