#include "garment/garment_mesh.hpp"

#include "common/error.hpp"
#include "common/output.hpp"
#include "mesh/obj.hpp"

#include <cstdio>
#include <cstdlib>
#include <functional>
#include <numeric>
#include <sstream>

namespace sartor::garment {

GarmentMesh build_garment_mesh(const Construction& construction, const PanelMeshOptions& options) {
  const Pattern& pattern = *construction.pattern;
  // Lines joined by seams (chains too: a Y-seam contour) share a piece count.
  const int n = int(construction.lines.size());
  std::vector<int> parent(static_cast<std::size_t>(n));
  std::iota(parent.begin(), parent.end(), 0);
  const std::function<int(int)> root = [&](int k) {
    return parent[std::size_t(k)] == k ? k : parent[std::size_t(k)] = root(parent[std::size_t(k)]);
  };
  for (const auto& seam : construction.seams)
    if (!construction.lines[std::size_t(seam.line_a)].interior &&
        !construction.lines[std::size_t(seam.line_b)].interior)
      parent[std::size_t(root(seam.line_a))] = root(seam.line_b);
  std::vector<int> pieces(static_cast<std::size_t>(n), 0);
  for (int k = 0; k < n; ++k) {
    int& p = pieces[std::size_t(root(k))];
    p = std::max(p, pieces_for(construction.lines[std::size_t(k)].length, options.edge_length));
  }
  PanelMeshOptions forced = options;
  for (const auto& seam : construction.seams)
    for (int line : {seam.line_a, seam.line_b})
      if (!construction.lines[std::size_t(line)].interior)
        forced.pieces[construction.lines[std::size_t(line)].id] = pieces[std::size_t(root(line))];

  GarmentMesh garment;
  for (std::size_t p = 0; p < pattern.panels.size(); ++p) {
    const PanelMesh panel = mesh_panel(pattern.panels[p], forced);
    const int offset = int(garment.mesh.vertex_count());
    garment.first_vertex.push_back(offset);
    garment.triangle_count.push_back(int(panel.mesh.triangle_count()));
    for (const auto& x : panel.mesh.positions)
      garment.mesh.positions.push_back(construction.place(int(p), x.head<2>()));
    for (std::size_t t = 0; t < panel.mesh.triangle_count(); ++t) {
      const auto& tri = panel.mesh.triangles[t];
      garment.mesh.triangles.push_back({tri[0] + offset, tri[1] + offset, tri[2] + offset});
      garment.mesh.material_uv.push_back(panel.mesh.material_uv[t]);
      garment.mesh.material_ids.push_back(int(p));
    }
    for (const auto& line : panel.lines) {
      std::vector<int> vertices;
      for (int v : line.vertices)
        vertices.push_back(v + offset);
      garment.line_vertices[line.id] = vertices;
    }
  }
  validate(garment.mesh, pattern.source + ": constructed garment");
  for (const FoundSeam& found : construction.seams) {
    const LineGeometry& a = construction.lines[std::size_t(found.line_a)];
    const LineGeometry& b = construction.lines[std::size_t(found.line_b)];
    const LineGeometry& outer = a.interior ? b : a;
    const LineGeometry& onto = a.interior ? a : b;
    Seam seam;
    seam.name = a.id + "+" + b.id;
    seam.a = garment.line_vertices.at(outer.id);
    seam.b = garment.line_vertices.at(onto.id);
    seam.reverse = found.reverse; // the same pairing whichever line comes first
    seam.certainty = found.certainty;
    seam.t_seam = onto.interior;
    garment.seams.push_back(seam);
  }
  check_seams(garment.mesh, garment.seams, pattern.source + ": constructed seams");
  return garment;
}

void write_garment_obj(const std::string& path, const GarmentMesh& garment,
                       const Pattern& pattern) {
  std::vector<std::string> groups;
  for (std::size_t p = 0; p < pattern.panels.size(); ++p)
    groups.insert(groups.end(), std::size_t(garment.triangle_count[p]), pattern.panels[p].id);
  write_obj(path, garment.mesh, groups,
            (pattern.name.empty() ? pattern.source : pattern.name) +
                ": constructed by sartor construct (TAGCON)");
}

} // namespace sartor::garment
