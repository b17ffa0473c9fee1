#include "mesh/panels.hpp"

#include "common/error.hpp"
#include "mesh/generators.hpp"

#include <cmath>

namespace sartor::mesh {

namespace {

// Appends `panel` to `set` with its positions mapped by `place(u, v)`.
template <class Place>
void append_panel(PanelMesh& set, const TriangleMesh& panel, const Place& place) {
  const int offset = int(set.mesh.vertex_count());
  set.panel_start.push_back(offset);
  for (const Eigen::Vector3d& p : panel.positions)
    set.mesh.positions.push_back(place(p.x(), p.y()));
  for (const auto& t : panel.triangles)
    set.mesh.triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
  set.mesh.material_uv.insert(set.mesh.material_uv.end(), panel.material_uv.begin(),
                              panel.material_uv.end());
}

// Vertices of a rectangle's u = const edge (column i), bottom to top.
std::vector<int> column(int offset, int nx, int ny, int i) {
  std::vector<int> line;
  for (int j = 0; j <= ny; ++j)
    line.push_back(offset + j * (nx + 1) + i);
  return line;
}

} // namespace

PanelMesh tube_panels(double width, double height, int nx, int ny, int nx_front, int ny_front,
                      double gap) {
  if (!(gap >= 0.0) || !std::isfinite(gap)) {
    throw InputError("tube_panels: gap must be a finite distance >= 0 m");
  }
  const TriangleMesh back = rectangle(width, height, nx, ny);
  const TriangleMesh front = rectangle(width, height, nx_front, ny_front);
  const double radius = width / M_PI;
  PanelMesh set;
  append_panel(set, back, [&](double u, double v) {
    const double angle = M_PI * (1.0 + u / width);
    return Eigen::Vector3d(radius * std::cos(angle), radius * std::sin(angle) - 0.5 * gap, v);
  });
  append_panel(set, front, [&](double u, double v) {
    const double angle = M_PI * u / width;
    return Eigen::Vector3d(radius * std::cos(angle), radius * std::sin(angle) + 0.5 * gap, v);
  });
  const int b = set.panel_start[1];
  set.seams.push_back(
      {"right", column(0, nx, ny, nx), column(b, nx_front, ny_front, 0), false, 1.0});
  set.seams.push_back(
      {"left", column(b, nx_front, ny_front, nx_front), column(0, nx, ny, 0), false, 1.0});
  validate(set.mesh, "tube_panels");
  return set;
}

} // namespace sartor::mesh
