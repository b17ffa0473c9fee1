#pragma once
// Multi-panel meshes with their seams, for tests and simple cases.

#include "mesh/seams.hpp"
#include "mesh/triangle_mesh.hpp"

#include <vector>

namespace sartor::mesh {

struct PanelMesh {
  TriangleMesh mesh;
  std::vector<Seam> seams;
  std::vector<int> panel_start; // first vertex of each panel (panels are numbered in turn)
};

// Two width x height rectangles (rectangle(), alternating diagonals), back
// panel nx x ny cells, front panel nx_front x ny_front, u along the width
// (warp), v = z along the height (weft). Each is laid out as a half cylinder of
// radius width / pi about the z axis, so that sewn they make a round tube of
// circumference 2 width: the back panel on y < 0 (u from x = -r to x = +r),
// the front panel on y > 0 (u from x = +r to x = -r), normals outward; then
// pulled apart by `gap` along y (back to -gap/2, front to +gap/2). Two seams,
// both running bottom to top: "right" sews the back panel's u = width edge
// to the front panel's u = 0 edge, "left" the front's u = width edge to the
// back's u = 0 edge. Unequal ny and ny_front give vertex-to-edge seams.
// Back panel vertices first: (nx + 1)(ny + 1) + (nx_front + 1)(ny_front + 1)
// vertices, 2 (nx ny + nx_front ny_front) triangles.
PanelMesh tube_panels(double width, double height, int nx, int ny, int nx_front, int ny_front,
                      double gap);

} // namespace sartor::mesh
