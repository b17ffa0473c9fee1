#pragma once
// `sartor drape PATTERN --start-from DRAPE_DIR` (docs/drape.md#starting-from-another-drape):
// the garment starts where an earlier drape of another version of the
// pattern (a dart added, lines moved, another edge length) left the cloth,
// by the thesis' geometric transfer (ch. 4, eqs. 4.1-4.2): every vertex is
// found, by its pattern coordinates, in the old drape's triangles of the
// panel with the same id, and placed at the barycentric combination of
// their draped corners; a vertex beyond the old panel (a longer hem) takes
// the nearest triangle's affine extension. Then the points inside the body
// are lifted out, and the drape runs from there.

#include "app/cloth_case.hpp"
#include "garment/pattern.hpp"
#include "mesh/triangle_mesh.hpp"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace sartor {

struct StartFromReport {
  std::string directory;
  long vertices = 0;
  long extrapolated = 0;          // vertices beyond the old panel's triangles
  double farthest_beyond_m = 0.0; // the farthest of them from the old panel (pattern), m
  double lifted_depth_m = 0.0;    // the deepest start below the offset surface, lifted out
  nlohmann::json json() const;
};

// Places `mesh` (the new garment: `panel_of_triangle` indexes
// `pattern.panels`) where the drape in `directory` left its panels. Throws
// InputError naming the directory for a folder without a drape (no
// summary.json, final.obj or readable pattern_file) and for a panel the old
// drape does not have.
StartFromReport start_from_drape(const std::string& directory, const garment::Pattern& pattern,
                                 const std::vector<int>& panel_of_triangle,
                                 const ContactCase& contact, TriangleMesh* mesh);

} // namespace sartor
