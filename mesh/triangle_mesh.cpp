#include "mesh/triangle_mesh.hpp"

#include "common/csv.hpp"
#include "common/error.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <set>

namespace sartor {

namespace {

std::string where(const std::string& context) {
  return context.empty() ? "" : context + ": ";
}

std::string triangle_name(const TriangleMesh& mesh, std::size_t t) {
  const auto& tri = mesh.triangles[t];
  return "triangle " + std::to_string(t) + " (vertices " + std::to_string(tri[0]) + " " +
         std::to_string(tri[1]) + " " + std::to_string(tri[2]) + ")";
}

std::string point_text(const Eigen::Vector2d& p) {
  return "(" + format_number(p.x()) + ", " + format_number(p.y()) + ")";
}

// Index range and distinct corners: what the edge walk below relies on.
void check_connectivity(const TriangleMesh& mesh, const std::string& context) {
  const auto n = static_cast<std::int64_t>(mesh.vertex_count());
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    const auto& tri = mesh.triangles[t];
    for (int c = 0; c < 3; ++c) {
      if (tri[c] < 0 || tri[c] >= n) {
        throw InputError(where(context) + triangle_name(mesh, t) + ": vertex index " +
                         std::to_string(tri[c]) + " is out of range (the mesh has " +
                         std::to_string(n) + " vertices)");
      }
    }
    if (tri[0] == tri[1] || tri[1] == tri[2] || tri[2] == tri[0]) {
      throw InputError(where(context) + triangle_name(mesh, t) + " repeats a vertex");
    }
  }
}

// One triangle's side: its vertices sorted (lo < hi), the triangle and the
// corner the side starts at in the triangle's winding.
struct Side {
  int lo;
  int hi;
  int triangle;
  int corner;
};

// All sides sorted so that the sides of one edge are adjacent, in triangle
// order. Throws for an edge with more than two triangles.
std::vector<Side> sorted_sides(const TriangleMesh& mesh) {
  check_connectivity(mesh, "mesh");
  std::vector<Side> sides;
  sides.reserve(3 * mesh.triangle_count());
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    const auto& tri = mesh.triangles[t];
    for (int c = 0; c < 3; ++c) {
      const int a = tri[c];
      const int b = tri[(c + 1) % 3];
      sides.push_back({std::min(a, b), std::max(a, b), static_cast<int>(t), c});
    }
  }
  std::sort(sides.begin(), sides.end(), [](const Side& x, const Side& y) {
    if (x.lo != y.lo) return x.lo < y.lo;
    if (x.hi != y.hi) return x.hi < y.hi;
    if (x.triangle != y.triangle) return x.triangle < y.triangle;
    return x.corner < y.corner;
  });
  for (std::size_t i = 0; i + 2 < sides.size(); ++i) {
    if (sides[i].lo != sides[i + 2].lo || sides[i].hi != sides[i + 2].hi) continue;
    std::size_t end = i + 2;
    while (end < sides.size() && sides[end].lo == sides[i].lo && sides[end].hi == sides[i].hi)
      ++end;
    std::string list;
    for (std::size_t k = i; k < end; ++k)
      list += (k == i ? "" : ", ") + std::to_string(sides[k].triangle);
    throw InputError("mesh: edge " + std::to_string(sides[i].lo) + "-" +
                     std::to_string(sides[i].hi) + " is shared by " + std::to_string(end - i) +
                     " triangles (" + list +
                     "); a cloth mesh must be a manifold surface (at most two triangles per edge)");
  }
  return sides;
}

} // namespace

void validate(const TriangleMesh& mesh, const std::string& context) {
  const std::size_t triangles = mesh.triangle_count();
  if (mesh.material_uv.size() != triangles) {
    throw InputError(where(context) + "the mesh has " + std::to_string(triangles) +
                     " triangles but material coordinates for " +
                     std::to_string(mesh.material_uv.size()));
  }
  if (!mesh.material_ids.empty() && mesh.material_ids.size() != triangles) {
    throw InputError(where(context) + "the mesh has " + std::to_string(triangles) +
                     " triangles but " + std::to_string(mesh.material_ids.size()) +
                     " material ids (give one per triangle, or none)");
  }
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
    if (!mesh.positions[v].allFinite()) {
      throw InputError(where(context) + "vertex " + std::to_string(v) +
                       ": the position is not finite");
    }
  }
  check_connectivity(mesh, context);
  for (std::size_t t = 0; t < triangles; ++t) {
    const auto& uv = mesh.material_uv[t];
    for (int c = 0; c < 3; ++c) {
      if (!uv[c].allFinite()) {
        throw InputError(where(context) + triangle_name(mesh, t) + ": the material coordinate of " +
                         "corner " + std::to_string(c) + " is not finite");
      }
    }
    const Eigen::Vector2d d1 = uv[1] - uv[0];
    const Eigen::Vector2d d2 = uv[2] - uv[0];
    const double det = d1.x() * d2.y() - d1.y() * d2.x();
    const double size2 =
        std::max({d1.squaredNorm(), d2.squaredNorm(), (uv[2] - uv[1]).squaredNorm()});
    if (!(std::abs(det) > 1e-14 * size2)) {
      throw InputError(where(context) + triangle_name(mesh, t) +
                       " has no material area: its (u, v) corners " + point_text(uv[0]) + " " +
                       point_text(uv[1]) + " " + point_text(uv[2]) + " are collinear");
    }
  }
}

std::vector<Hinge> interior_edges(const TriangleMesh& mesh) {
  const std::vector<Side> sides = sorted_sides(mesh);
  std::vector<Hinge> hinges;
  for (std::size_t i = 0; i + 1 < sides.size(); ++i) {
    const Side& first = sides[i];
    const Side& second = sides[i + 1];
    if (first.lo != second.lo || first.hi != second.hi) continue;
    ++i;
    const auto& a = mesh.triangles[static_cast<std::size_t>(first.triangle)];
    const auto& b = mesh.triangles[static_cast<std::size_t>(second.triangle)];
    Hinge hinge{};
    hinge.triangles = {first.triangle, second.triangle};
    const int c0 = first.corner;
    hinge.corners[0] = {c0, (c0 + 1) % 3, (c0 + 2) % 3};
    hinge.vertices[0] = a[static_cast<std::size_t>(hinge.corners[0][0])];
    hinge.vertices[1] = a[static_cast<std::size_t>(hinge.corners[0][1])];
    hinge.vertices[2] = a[static_cast<std::size_t>(hinge.corners[0][2])];
    const int c1 = second.corner;
    const int next = (c1 + 1) % 3;
    // Oriented meshes: the second triangle runs v1 -> v0 along the edge.
    const bool opposite = b[static_cast<std::size_t>(c1)] == hinge.vertices[1];
    hinge.corners[1] = {opposite ? c1 : next, opposite ? next : c1, (c1 + 2) % 3};
    hinge.vertices[3] = b[static_cast<std::size_t>(hinge.corners[1][2])];
    if (hinge.vertices[3] == hinge.vertices[2]) {
      throw InputError("mesh: triangles " + std::to_string(first.triangle) + " and " +
                       std::to_string(second.triangle) + " have the same three vertices (" +
                       std::to_string(a[0]) + " " + std::to_string(a[1]) + " " +
                       std::to_string(a[2]) + ")");
    }
    hinges.push_back(hinge);
  }
  std::sort(hinges.begin(), hinges.end(), [](const Hinge& x, const Hinge& y) {
    if (x.triangles[0] != y.triangles[0]) return x.triangles[0] < y.triangles[0];
    return x.corners[0][0] < y.corners[0][0];
  });
  return hinges;
}

std::vector<std::array<int, 2>> boundary_edges(const TriangleMesh& mesh) {
  const std::vector<Side> sides = sorted_sides(mesh);
  std::vector<std::array<int, 2>> edges;
  for (std::size_t i = 0; i < sides.size(); ++i) {
    const bool paired =
        i + 1 < sides.size() && sides[i + 1].lo == sides[i].lo && sides[i + 1].hi == sides[i].hi;
    if (paired) {
      ++i;
      continue;
    }
    edges.push_back({sides[i].lo, sides[i].hi});
  }
  return edges;
}

std::vector<std::array<int, 2>> mesh_edges(const TriangleMesh& mesh) {
  std::set<std::array<int, 2>> edges;
  for (const auto& corners : mesh.triangles) {
    for (std::size_t c = 0; c < 3; ++c) {
      const int a = corners[c], b = corners[(c + 1) % 3];
      edges.insert({std::min(a, b), std::max(a, b)});
    }
  }
  return {edges.begin(), edges.end()};
}

std::vector<int> boundary_vertices(const TriangleMesh& mesh) {
  std::vector<int> vertices;
  for (const auto& edge : boundary_edges(mesh))
    vertices.insert(vertices.end(), edge.begin(), edge.end());
  std::sort(vertices.begin(), vertices.end());
  vertices.erase(std::unique(vertices.begin(), vertices.end()), vertices.end());
  return vertices;
}

double material_area(const TriangleMesh& mesh) {
  double area = 0.0;
  for (const auto& uv : mesh.material_uv)
    area += material_area(uv);
  return area;
}

std::vector<Eigen::Vector2d> vertex_material_uv(const TriangleMesh& mesh) {
  std::vector<Eigen::Vector2d> uv(mesh.vertex_count(), Eigen::Vector2d::Zero());
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t)
    for (std::size_t c = 0; c < 3; ++c)
      uv[std::size_t(mesh.triangles[t][c])] = mesh.material_uv[t][c];
  return uv;
}

} // namespace sartor
