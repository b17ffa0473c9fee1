#pragma once
// Measurements of a TriangleMesh shared by the mesh tests.

#include "mesh/triangle_mesh.hpp"

#include <Eigen/Geometry>

namespace sartor::test {

// Signed area of triangle t in (u, v): positive when wound counter-clockwise.
inline double material_area(const TriangleMesh& mesh, std::size_t t) {
  const auto& uv = mesh.material_uv[t];
  const Eigen::Vector2d d1 = uv[1] - uv[0];
  const Eigen::Vector2d d2 = uv[2] - uv[0];
  return 0.5 * (d1.x() * d2.y() - d1.y() * d2.x());
}

inline double total_material_area(const TriangleMesh& mesh) {
  double sum = 0.0;
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t)
    sum += material_area(mesh, t);
  return sum;
}

inline const Eigen::Vector3d& corner_position(const TriangleMesh& mesh, std::size_t t,
                                              std::size_t c) {
  return mesh.positions[static_cast<std::size_t>(mesh.triangles[t][c])];
}

// Area-weighted normal of triangle t in 3D (length = area).
inline Eigen::Vector3d area_normal(const TriangleMesh& mesh, std::size_t t) {
  const Eigen::Vector3d& a = corner_position(mesh, t, 0);
  return 0.5 * (corner_position(mesh, t, 1) - a).cross(corner_position(mesh, t, 2) - a);
}

inline double surface_area(const TriangleMesh& mesh, std::size_t t) {
  return area_normal(mesh, t).norm();
}

} // namespace sartor::test
