#pragma once
// The constructed garment as one mesh for the solver: every panel
// triangulated (mesh/panel_mesher), its vertices placed in 3D by TAGCON, the
// panels merged (vertex numbers panel after panel, in pattern order), and
// the seams as the seam list `sartor run --seams-file` reads. Lines that are
// sewn together are given the same number of equal arc-length pieces (the
// largest any of them needs), so their seams sew vertex to vertex.

#include "garment/tagcon.hpp"
#include "mesh/panel_mesher.hpp"
#include "mesh/seams.hpp"
#include "mesh/triangle_mesh.hpp"

#include <map>
#include <string>
#include <vector>

namespace sartor::garment {

struct GarmentMesh {
  TriangleMesh mesh;                                     // material_ids = panel index
  std::vector<int> first_vertex;                         // per panel, into mesh
  std::vector<int> triangle_count;                       // per panel
  std::map<std::string, std::vector<int>> line_vertices; // line id -> mesh vertices, start to end
  // As Construction::seams, in its order (a T-seam's interior line is line
  // b), then the pattern's stitches. mesh.creases holds the creases.
  std::vector<Seam> seams;
};

// `fold`: pre-fold the panels' creased fold lines (docs/pleats.md); without
// it the panels start flat, their creases keeping their rest angles. The
// pattern's stitches (pleats) are seams too, after TAGCON's.
GarmentMesh build_garment_mesh(const Construction& construction, const PanelMeshOptions& options,
                               bool fold = true);

// OBJ with `g PANEL` and `usemtl PANEL` per panel, v = placed positions,
// vt = material (u, v) in m; written atomically. `sartor run --mesh obj`
// reads it (groups and materials are ignored there).
void write_garment_obj(const std::string& path, const GarmentMesh& garment, const Pattern& pattern);

} // namespace sartor::garment
