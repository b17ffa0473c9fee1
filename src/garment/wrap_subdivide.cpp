// One level of sqrt(3) subdivision of the cloth edges that cut into the body
// (garment/wrap.hpp: subdivide_cutting_edges).

#include "garment/wrap.hpp"

#include <algorithm>
#include <array>
#include <vector>

namespace sartor::garment {

namespace {

// The paper's test from one end: the body is approximated by the sphere of
// radius L = |AB| touching it at A's nearest body point; the edge cuts into
// the body when it passes through that sphere (tested exactly here).
bool cuts_sphere_below(const contact::Shape& body, const Eigen::Vector3d& a,
                       const Eigen::Vector3d& b) {
  const BodyPoint near = nearest_body_point(body, a);
  const double length = (b - a).norm();
  const Eigen::Vector3d centre = near.closest - length * near.normal;
  const double t = std::clamp((centre - a).dot(b - a) / (length * length), 0.0, 1.0);
  return (a + t * (b - a) - centre).norm() < length;
}

// Whether the hinge's two triangles share the edge's rest coordinates (one
// panel, not a seam): only then may the edge be flipped.
bool same_rest_frame(const TriangleMesh& mesh, const Hinge& hinge) {
  const auto& first = mesh.material_uv[std::size_t(hinge.triangles[0])];
  const auto& second = mesh.material_uv[std::size_t(hinge.triangles[1])];
  const Eigen::Vector2d &a1 = first[std::size_t(hinge.corners[0][0])],
                        &b1 = first[std::size_t(hinge.corners[0][1])],
                        &b2 = second[std::size_t(hinge.corners[1][0])],
                        &a2 = second[std::size_t(hinge.corners[1][1])];
  const double tolerance = 1e-9 * (b1 - a1).norm();
  return mesh.material_ids[std::size_t(hinge.triangles[0])] ==
             mesh.material_ids[std::size_t(hinge.triangles[1])] &&
         (a1 - a2).norm() < tolerance && (b1 - b2).norm() < tolerance;
}

// Triangle t's corners as (vertex, uv), starting at vertex `first`.
std::array<std::pair<int, Eigen::Vector2d>, 3> corners_from(const TriangleMesh& mesh, int t,
                                                            int first) {
  const auto& triangle = mesh.triangles[std::size_t(t)];
  std::size_t start = 0;
  while (triangle[start] != first)
    ++start;
  std::array<std::pair<int, Eigen::Vector2d>, 3> corners;
  for (std::size_t k = 0; k < 3; ++k)
    corners[k] = {triangle[(start + k) % 3], mesh.material_uv[std::size_t(t)][(start + k) % 3]};
  return corners;
}

} // namespace

int subdivide_cutting_edges(TriangleMesh& mesh, const contact::Shape& body, double offset) {
  const std::vector<Hinge> hinges = interior_edges(mesh);
  std::vector<bool> used(mesh.triangle_count(), false);
  std::vector<std::array<int, 3>> triangles;
  std::vector<std::array<Eigen::Vector2d, 3>> uv;
  std::vector<int> ids;
  int split = 0;
  for (const Hinge& hinge : hinges) {
    const int t1 = hinge.triangles[0], t2 = hinge.triangles[1];
    if (used[std::size_t(t1)] || used[std::size_t(t2)] || !same_rest_frame(mesh, hinge)) continue;
    const Eigen::Vector3d &a = mesh.positions[std::size_t(hinge.vertices[0])],
                          &b = mesh.positions[std::size_t(hinge.vertices[1])];
    if (!cuts_sphere_below(body, a, b) && !cuts_sphere_below(body, b, a)) continue;
    used[std::size_t(t1)] = used[std::size_t(t2)] = true;
    ++split;
    // t1 = (a, b, c), t2 = (b, a, d); a new vertex at each one's centroid.
    const auto first = corners_from(mesh, t1, hinge.vertices[0]);
    const auto second = corners_from(mesh, t2, hinge.vertices[1]);
    std::array<int, 2> centre{};
    std::array<Eigen::Vector2d, 2> centre_uv;
    for (std::size_t k = 0; k < 2; ++k) {
      const auto& c = k == 0 ? first : second;
      Eigen::Vector3d position = Eigen::Vector3d::Zero();
      centre_uv[k].setZero();
      for (const auto& [vertex, corner_uv] : c) {
        position += mesh.positions[std::size_t(vertex)] / 3.0;
        centre_uv[k] += corner_uv / 3.0;
      }
      centre[k] = int(mesh.positions.size());
      mesh.positions.push_back(keep_above(body, position, offset));
    }
    const int material = mesh.material_ids[std::size_t(t1)];
    const auto add = [&](std::array<int, 3> v, std::array<Eigen::Vector2d, 3> w) {
      triangles.push_back(v);
      uv.push_back(w);
      ids.push_back(material);
    };
    const auto& [va, ua] = first[0];
    const auto& [vb, ub] = first[1];
    const auto& [vc, uc] = first[2];
    const auto& [vd, ud] = second[2];
    add({vb, vc, centre[0]}, {ub, uc, centre_uv[0]});
    add({vc, va, centre[0]}, {uc, ua, centre_uv[0]});
    add({va, vd, centre[1]}, {ua, ud, centre_uv[1]});
    add({vd, vb, centre[1]}, {ud, ub, centre_uv[1]});
    // The edge a-b flipped to join the two centres.
    add({centre[0], va, centre[1]}, {centre_uv[0], ua, centre_uv[1]});
    add({centre[1], vb, centre[0]}, {centre_uv[1], ub, centre_uv[0]});
  }
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    if (used[t]) continue;
    triangles.push_back(mesh.triangles[t]);
    uv.push_back(mesh.material_uv[t]);
    ids.push_back(mesh.material_ids[t]);
  }
  mesh.triangles = std::move(triangles);
  mesh.material_uv = std::move(uv);
  mesh.material_ids = std::move(ids);
  return split;
}

} // namespace sartor::garment
