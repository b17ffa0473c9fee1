#include "garment/garment_mesh.hpp"

#include "common/error.hpp"
#include "common/output.hpp"
#include "garment/prefold.hpp"
#include "mesh/obj.hpp"

#include <Eigen/Geometry>

#include <cstdio>
#include <cstdlib>
#include <functional>
#include <numeric>
#include <sstream>

namespace sartor::garment {

namespace {

// The wrap's unit normal at a panel point: the image of the panel's +z.
Eigen::Vector3d panel_normal(const Construction& construction, int panel,
                             const Eigen::Vector2d& point) {
  const Pattern& pattern = *construction.pattern;
  const int pack = pattern.pack_of(panel);
  for (const auto& member : pattern.packs[std::size_t(pack)].members) {
    if (member.panel != panel) continue;
    const auto frame = construction.wrap_tangents(pack, member.placement.apply(point));
    return frame[0].cross(frame[1]).normalized();
  }
  return Eigen::Vector3d::UnitZ();
}

// Whether a panel's +z faces away from its cylinder's axis (the outside of
// the garment), judged at the panel's centroid.
bool normal_side_is_outside(const Construction& construction, int panel, const PanelMesh& mesh) {
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();
  for (const auto& x : mesh.mesh.positions)
    centre += x.head<2>();
  centre /= double(mesh.mesh.vertex_count());
  const Pattern& pattern = *construction.pattern;
  const FittedCylinder& c =
      construction
          .cylinders[std::size_t(construction.packs[std::size_t(pattern.pack_of(panel))].cylinder)];
  const Eigen::Vector3d p = construction.place(panel, centre);
  const Eigen::Vector3d radial = (p - c.top) - (p - c.top).dot(c.up) * c.up;
  return panel_normal(construction, panel, centre).dot(radial) > 0.0;
}

// A panel's mesh vertices in 3D: pre-folded in panel coordinates (x, y, z),
// then (x, y) wrapped by TAGCON and z laid along the wrap's normal there.
void place_panel(const Construction& construction, int panel, const PanelMesh& meshed, bool fold,
                 GarmentMesh* garment) {
  const Panel& pattern_panel = construction.pattern->panels[std::size_t(panel)];
  const bool creased = std::any_of(pattern_panel.interior.begin(), pattern_panel.interior.end(),
                                   [](const InteriorLine& line) { return bool(line.crease); });
  std::vector<MeshedFold> folds;
  if (creased)
    folds =
        meshed_folds(pattern_panel, meshed, normal_side_is_outside(construction, panel, meshed));
  const std::vector<Eigen::Vector3d> folded =
      fold && !folds.empty() ? prefold(meshed.mesh, folds) : meshed.mesh.positions;
  for (const auto& x : folded) {
    Eigen::Vector3d p = construction.place(panel, x.head<2>());
    if (x.z() != 0.0) p += x.z() * panel_normal(construction, panel, x.head<2>());
    garment->mesh.positions.push_back(p);
  }
  for (const CreaseEdge& edge : crease_edges(folds, garment->first_vertex.back()))
    garment->mesh.creases.push_back(edge);
}

} // namespace

GarmentMesh build_garment_mesh(const Construction& construction, const PanelMeshOptions& options,
                               bool fold) {
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
  const auto stitch_line = [&](const std::string& id) {
    const int line = construction.line_index(id);
    if (line < 0) throw std::logic_error("a stitch names line '" + id + "', which has no geometry");
    return line;
  };
  for (const Stitch& stitch : pattern.stitches)
    parent[std::size_t(root(stitch_line(stitch.line_a)))] = root(stitch_line(stitch.line_b));
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
  for (const Stitch& stitch : pattern.stitches)
    for (const std::string& id : {stitch.line_a, stitch.line_b})
      forced.pieces[id] = pieces[std::size_t(root(stitch_line(id)))];

  GarmentMesh garment;
  for (std::size_t p = 0; p < pattern.panels.size(); ++p) {
    const PanelMesh panel = mesh_panel(pattern.panels[p], forced);
    const int offset = int(garment.mesh.vertex_count());
    garment.first_vertex.push_back(offset);
    garment.triangle_count.push_back(int(panel.mesh.triangle_count()));
    place_panel(construction, int(p), panel, fold, &garment);
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
  for (const Stitch& stitch : pattern.stitches) {
    Seam seam;
    seam.name = stitch.line_a + "+" + stitch.line_b;
    seam.a = garment.line_vertices.at(stitch.line_a);
    seam.b = garment.line_vertices.at(stitch.line_b);
    seam.reverse = stitch.reverse;
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
