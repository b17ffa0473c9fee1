#include "app/start_from.hpp"

#include "app/progressive_drape.hpp"
#include "common/error.hpp"
#include "mesh/obj.hpp"
#include "mesh/remesh.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <filesystem>
#include <map>

namespace sartor {

namespace {

// A vertex farther than this beyond the old panel is reported as extended.
constexpr double counted_beyond = 1e-9; // m

// The old drape: its cloth (final positions, material coordinates) and per
// triangle the index of its panel in `panels`.
struct OldDrape {
  TriangleMesh mesh;
  std::vector<std::string> panels;
};

OldDrape read_old_drape(const std::string& directory) {
  const std::string path = directory + "/final.obj";
  if (!std::filesystem::exists(path)) {
    throw InputError("option --start-from: " + directory +
                     ": no final.obj (not the output folder of a drape)");
  }
  OldDrape old;
  std::vector<std::string> groups;
  old.mesh = read_obj(path, {}, &groups);
  std::map<std::string, int> index;
  old.mesh.material_ids.clear();
  for (const std::string& group : groups) {
    const auto [entry, fresh] = index.emplace(group, int(old.panels.size()));
    if (fresh) old.panels.push_back(group);
    old.mesh.material_ids.push_back(entry->second);
  }
  return old;
}

// Each vertex's panel (a corner's, as vertex_material_uv takes its uv).
std::vector<int> vertex_panels(const TriangleMesh& mesh,
                               const std::vector<int>& panel_of_triangle) {
  std::vector<int> panel(mesh.vertex_count(), -1);
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t)
    for (std::size_t c = 0; c < 3; ++c)
      panel[std::size_t(mesh.triangles[t][c])] = panel_of_triangle.at(t);
  return panel;
}

// The barycentric coordinates of `point` in triangle `uv`, not clamped: an
// affine extension beyond it.
Eigen::Vector3d barycentric(const std::array<Eigen::Vector2d, 3>& uv,
                            const Eigen::Vector2d& point) {
  Eigen::Matrix2d edges;
  edges << uv[1] - uv[0], uv[2] - uv[0];
  const Eigen::Vector2d w = edges.fullPivLu().solve(point - uv[0]);
  return {1.0 - w.x() - w.y(), w.x(), w.y()};
}

} // namespace

nlohmann::json StartFromReport::json() const {
  return {{"directory", directory},
          {"vertices", vertices},
          {"extrapolated_vertices", extrapolated},
          {"farthest_beyond_old_panel_m", farthest_beyond_m},
          {"lifted_depth_m", lifted_depth_m}};
}

StartFromReport start_from_drape(const std::string& directory, const garment::Pattern& pattern,
                                 const std::vector<int>& panel_of_triangle,
                                 const ContactCase& contact, TriangleMesh* mesh) {
  const OldDrape old = read_old_drape(directory);
  const std::vector<Eigen::Vector2d> uv = vertex_material_uv(*mesh);
  const std::vector<int> panel = vertex_panels(*mesh, panel_of_triangle);
  std::vector<int> group(mesh->vertex_count(), 0);
  for (std::size_t v = 0; v < group.size(); ++v) {
    const std::string& id = pattern.panels.at(std::size_t(panel[v])).id;
    const auto found = std::find(old.panels.begin(), old.panels.end(), id);
    if (found == old.panels.end()) {
      throw InputError("option --start-from: " + directory + " has no panel '" + id +
                       "' (its final.obj's groups are the panels it draped)");
    }
    group[v] = int(found - old.panels.begin());
  }
  const std::vector<BarycentricLocation> located = locate_in_material(old.mesh, uv, group);
  StartFromReport report;
  report.directory = directory;
  report.vertices = long(mesh->vertex_count());
  std::vector<Eigen::Vector3d> positions(mesh->vertex_count());
  for (std::size_t v = 0; v < positions.size(); ++v) {
    const auto& corners = old.mesh.triangles[std::size_t(located[v].triangle)];
    const auto& corner_uv = old.mesh.material_uv[std::size_t(located[v].triangle)];
    const Eigen::Vector3d clamped = located[v].weights;
    const Eigen::Vector2d nearest =
        clamped[0] * corner_uv[0] + clamped[1] * corner_uv[1] + clamped[2] * corner_uv[2];
    const double beyond = (nearest - uv[v]).norm();
    if (beyond > counted_beyond) {
      ++report.extrapolated;
      report.farthest_beyond_m = std::max(report.farthest_beyond_m, beyond);
    }
    // Inside the triangle these are its clamped weights; beyond it, the
    // affine extension (the same formula: no branch on round-off).
    const Eigen::Vector3d w = barycentric(corner_uv, uv[v]);
    positions[v] = Eigen::Vector3d::Zero();
    for (std::size_t c = 0; c < 3; ++c)
      positions[v] += w[Eigen::Index(c)] * old.mesh.positions[std::size_t(corners[c])];
  }
  report.lifted_depth_m = lift_out_of_bodies(contact, *mesh, &positions);
  mesh->positions = positions;
  return report;
}

} // namespace sartor
