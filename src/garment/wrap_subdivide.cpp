// One level of adaptive sqrt(3) subdivision of the cloth edges that cut into
// the body (garment/wrap.hpp: AdaptiveSubdivision).

#include "garment/wrap.hpp"

#include <algorithm>
#include <array>
#include <vector>

namespace sartor::garment {

namespace {

// A split edge merges back once its test passes with this much to spare, so
// that an edge at the threshold does not split and merge step after step.
constexpr double merge_margin = 1.1;

// The paper's test from one end: the body is approximated by the sphere of
// radius L = |AB| touching it at A's nearest body point (`near_a`); the
// edge cuts into the body when it passes through that sphere (tested
// exactly here). Returns the edge's least distance from the sphere's
// centre over L (< 1: it cuts).
double sphere_clearance(const BodyPoint& near_a, const Eigen::Vector3d& a,
                        const Eigen::Vector3d& b) {
  const double length = (b - a).norm();
  const Eigen::Vector3d centre = near_a.closest - length * near_a.normal;
  const double t = std::clamp((centre - a).dot(b - a) / (length * length), 0.0, 1.0);
  return (a + t * (b - a) - centre).norm() / length;
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

// Appends to `refined` the six triangles of the hinge's two base triangles
// split at their centres (vertices `centres`): t1 = (a, b, c) and
// t2 = (b, a, d) each fan to their centre, and a-b is flipped to join them.
void append_split(const TriangleMesh& base, const Hinge& hinge, std::array<int, 2> centres,
                  TriangleMesh& refined) {
  const auto first = corners_from(base, hinge.triangles[0], hinge.vertices[0]);
  const auto second = corners_from(base, hinge.triangles[1], hinge.vertices[1]);
  std::array<Eigen::Vector2d, 2> centre_uv{Eigen::Vector2d::Zero(), Eigen::Vector2d::Zero()};
  for (std::size_t c = 0; c < 3; ++c) {
    centre_uv[0] += first[c].second / 3.0;
    centre_uv[1] += second[c].second / 3.0;
  }
  const int material = base.material_ids[std::size_t(hinge.triangles[0])];
  const auto add = [&](std::array<int, 3> v, std::array<Eigen::Vector2d, 3> w) {
    refined.triangles.push_back(v);
    refined.material_uv.push_back(w);
    refined.material_ids.push_back(material);
  };
  const auto& [va, ua] = first[0];
  const auto& [vb, ub] = first[1];
  const auto& [vc, uc] = first[2];
  const auto& [vd, ud] = second[2];
  add({vb, vc, centres[0]}, {ub, uc, centre_uv[0]});
  add({vc, va, centres[0]}, {uc, ua, centre_uv[0]});
  add({va, vd, centres[1]}, {ua, ud, centre_uv[1]});
  add({vd, vb, centres[1]}, {ud, ub, centre_uv[1]});
  add({centres[0], va, centres[1]}, {centre_uv[0], ua, centre_uv[1]});
  add({centres[1], vb, centres[0]}, {centre_uv[1], ub, centre_uv[0]});
}

} // namespace

AdaptiveSubdivision::AdaptiveSubdivision(const TriangleMesh& base) : base_(base) {
  if (base_.material_ids.empty()) base_.material_ids.assign(base_.triangle_count(), 0);
  base_edges_ = rest_edges(base_);
  const auto is_crease = [&](const Hinge& hinge) {
    return std::any_of(base_.creases.begin(), base_.creases.end(), [&](const CreaseEdge& c) {
      return std::minmax(c.a, c.b) == std::minmax(hinge.vertices[0], hinge.vertices[1]);
    });
  };
  for (const Hinge& hinge : interior_edges(base_))
    if (same_rest_frame(base_, hinge) && !is_crease(hinge)) hinges_.push_back(hinge);
}

bool AdaptiveSubdivision::update(ClothOnBody& cloth) {
  const std::vector<Eigen::Vector3d>& x = cloth.positions();
  const contact::Shape& body = cloth.body();
  const std::size_t n = base_.vertex_count();
  // Each base vertex's nearest body point once (a vertex has about six edges).
  std::vector<BodyPoint> near(n);
  for (std::size_t v = 0; v < n; ++v)
    near[v] = nearest_body_point(body, x[v]);
  const auto clearance = [&](const Hinge& hinge) {
    const std::size_t a = std::size_t(hinge.vertices[0]), b = std::size_t(hinge.vertices[1]);
    return std::min(sphere_clearance(near[a], x[a], x[b]), sphere_clearance(near[b], x[b], x[a]));
  };
  // Split edges that stay (with their centres), then edges newly split.
  std::vector<int> split;
  std::vector<Eigen::Vector3d> centres;
  std::vector<bool> used(base_.triangle_count(), false);
  for (std::size_t k = 0; k < split_.size(); ++k) {
    const Hinge& hinge = hinges_[std::size_t(split_[k])];
    if (clearance(hinge) > merge_margin) {
      ++merges_;
      continue;
    }
    split.push_back(split_[k]);
    centres.push_back(x[n + 2 * k]);
    centres.push_back(x[n + 2 * k + 1]);
    used[std::size_t(hinge.triangles[0])] = used[std::size_t(hinge.triangles[1])] = true;
  }
  const bool merged = split.size() < split_.size();
  for (std::size_t h = 0; h < hinges_.size(); ++h) {
    const Hinge& hinge = hinges_[h];
    if (used[std::size_t(hinge.triangles[0])] || used[std::size_t(hinge.triangles[1])] ||
        clearance(hinge) >= 1.0)
      continue;
    used[std::size_t(hinge.triangles[0])] = used[std::size_t(hinge.triangles[1])] = true;
    split.push_back(int(h));
    for (int t : hinge.triangles) {
      Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
      for (int v : base_.triangles[std::size_t(t)])
        centroid += x[std::size_t(v)] / 3.0;
      centres.push_back(keep_above(body, centroid, cloth.parameters().offset));
    }
    ++splits_;
  }
  if (!merged && split.size() == split_.size()) return false;
  TriangleMesh refined;
  refined.creases = base_.creases; // never split
  refined.positions.assign(x.begin(), x.begin() + std::ptrdiff_t(n));
  refined.positions.insert(refined.positions.end(), centres.begin(), centres.end());
  for (std::size_t k = 0; k < split.size(); ++k)
    append_split(base_, hinges_[std::size_t(split[k])], {int(n + 2 * k), int(n + 2 * k + 1)},
                 refined);
  for (std::size_t t = 0; t < base_.triangle_count(); ++t) {
    if (used[t]) continue;
    refined.triangles.push_back(base_.triangles[t]);
    refined.material_uv.push_back(base_.material_uv[t]);
    refined.material_ids.push_back(base_.material_ids[t]);
  }
  split_ = std::move(split);
  cloth.replace_mesh(std::move(refined));
  return true;
}

void relax_adaptively(ClothOnBody& cloth, AdaptiveSubdivision& subdivision, int steps) {
  for (int step = 0; step < steps; ++step) {
    cloth.relax(1);
    subdivision.update(cloth);
  }
}

} // namespace sartor::garment
