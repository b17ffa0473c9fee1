#include "contact/self_intersections.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>

#include <algorithm>
#include <iterator>
#include <stdexcept>
#include <string>

namespace sartor {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using SurfaceMesh = CGAL::Surface_mesh<Kernel::Point_3>;
using Face = SurfaceMesh::Face_index;

// The faces keep their indices: Surface_mesh numbers faces in the order added.
SurfaceMesh surface_mesh(const BodyMesh& mesh) {
  SurfaceMesh surface;
  std::vector<SurfaceMesh::Vertex_index> vertices;
  vertices.reserve(mesh.vertices.size());
  for (const Eigen::Vector3d& p : mesh.vertices)
    vertices.push_back(surface.add_vertex(Kernel::Point_3(p.x(), p.y(), p.z())));
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    const auto& face = mesh.faces[f];
    const Face added = surface.add_face(vertices[static_cast<std::size_t>(face[0])],
                                        vertices[static_cast<std::size_t>(face[1])],
                                        vertices[static_cast<std::size_t>(face[2])]);
    if (added == SurfaceMesh::null_face() || std::size_t(added.idx()) != f)
      throw std::logic_error("self_intersecting_faces: face " + std::to_string(f) +
                             " does not make an oriented 2-manifold with the faces before it");
  }
  return surface;
}

} // namespace

std::vector<std::pair<std::size_t, std::size_t>> self_intersecting_faces(const BodyMesh& mesh) {
  const SurfaceMesh surface = surface_mesh(mesh);
  std::vector<std::pair<Face, Face>> crossing;
  CGAL::Polygon_mesh_processing::self_intersections(surface, std::back_inserter(crossing));
  std::vector<std::pair<std::size_t, std::size_t>> pairs;
  pairs.reserve(crossing.size());
  for (const auto& [a, b] : crossing)
    pairs.emplace_back(std::min<std::size_t>(a.idx(), b.idx()),
                       std::max<std::size_t>(a.idx(), b.idx()));
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

} // namespace sartor
