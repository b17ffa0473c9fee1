// The relaxation of Igarashi & Hughes (garment/wrap_relax.hpp).

#include "garment/wrap_relax.hpp"

#include "common/error.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <limits>
#include <map>
#include <utility>

namespace sartor::garment {

namespace {

double cross2(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

// A unit vector perpendicular to unit `n`.
Eigen::Vector3d any_perpendicular(const Eigen::Vector3d& n) {
  const Eigen::Vector3d helper =
      std::abs(n.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  return n.cross(helper).normalized();
}

// Whether the segment s0-s1 meets the triangle p0 p1 p2 (Moller and
// Trumbore). A segment parallel to the triangle's plane is taken not to.
bool segment_meets_triangle(const Eigen::Vector3d& s0, const Eigen::Vector3d& s1,
                            const Eigen::Vector3d& p0, const Eigen::Vector3d& p1,
                            const Eigen::Vector3d& p2) {
  const Eigen::Vector3d direction = s1 - s0, e1 = p1 - p0, e2 = p2 - p0;
  const Eigen::Vector3d h = direction.cross(e2);
  const double determinant = e1.dot(h);
  if (determinant == 0.0) return false;
  const Eigen::Vector3d from_corner = s0 - p0;
  const double u = from_corner.dot(h) / determinant;
  if (u < 0.0 || u > 1.0) return false;
  const Eigen::Vector3d q = from_corner.cross(e1);
  const double v = direction.dot(q) / determinant;
  if (v < 0.0 || u + v > 1.0) return false;
  const double along = e2.dot(q) / determinant;
  return along >= 0.0 && along <= 1.0;
}

struct Box3 {
  Eigen::Vector3d lower, upper;
  bool overlaps(const Box3& other) const {
    return (lower.array() <= other.upper.array()).all() &&
           (other.lower.array() <= upper.array()).all();
  }
};

Box3 box_of(std::initializer_list<Eigen::Vector3d> points) {
  Box3 box{*points.begin(), *points.begin()};
  for (const Eigen::Vector3d& p : points) {
    box.lower = box.lower.cwiseMin(p);
    box.upper = box.upper.cwiseMax(p);
  }
  return box;
}

} // namespace

bool edge_sweep_meets_segment(const Eigen::Vector3d& a0, const Eigen::Vector3d& b0,
                              const Eigen::Vector3d& a1, const Eigen::Vector3d& b1,
                              const Eigen::Vector3d& start, const Eigen::Vector3d& end) {
  return segment_meets_triangle(start, end, a0, b0, b1) ||
         segment_meets_triangle(start, end, a0, b1, a1);
}

BodyPoint nearest_body_point(const contact::Shape& body, const Eigen::Vector3d& p) {
  const contact::SurfaceQuery query = body.query(p);
  BodyPoint point;
  point.distance = query.distance;
  point.closest = query.closest;
  const double length = query.normal.norm();
  if (length > 0.0) {
    point.normal = query.normal / length;
  } else if ((p - query.closest).norm() > 0.0) {
    point.normal = (p - query.closest).normalized() * (query.distance < 0.0 ? -1.0 : 1.0);
  }
  return point;
}

Eigen::Vector3d keep_above(const contact::Shape& body, const Eigen::Vector3d& p, double offset) {
  const BodyPoint near = nearest_body_point(body, p);
  if (near.distance >= offset) return p;
  return near.closest + offset * near.normal;
}

RestEdges rest_edges(const TriangleMesh& mesh) {
  std::map<std::pair<int, int>, std::pair<double, int>> sums;
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    for (int c = 0; c < 3; ++c) {
      const int a = mesh.triangles[t][std::size_t(c)],
                b = mesh.triangles[t][std::size_t(c + 1) % 3];
      const double length =
          (mesh.material_uv[t][std::size_t(c)] - mesh.material_uv[t][std::size_t(c + 1) % 3])
              .norm();
      auto& sum = sums[{std::min(a, b), std::max(a, b)}];
      sum.first += length;
      sum.second += 1;
    }
  }
  RestEdges result;
  result.neighbours.resize(mesh.vertex_count());
  for (const auto& [edge, sum] : sums) {
    const double length = sum.first / sum.second;
    result.edges.push_back({edge.first, edge.second});
    result.lengths.push_back(length);
    result.neighbours[std::size_t(edge.first)].emplace_back(edge.second, length);
    result.neighbours[std::size_t(edge.second)].emplace_back(edge.first, length);
  }
  return result;
}

ClothOnBody::ClothOnBody(TriangleMesh mesh, const contact::Shape& body,
                         const RelaxParameters& parameters)
    : active(mesh.vertex_count(), true), fixed(mesh.vertex_count(), false), mesh_(std::move(mesh)),
      body_(body), parameters_(parameters) {
  validate(mesh_, "cloth on body");
  edges_ = rest_edges(mesh_);
  hinges_ = interior_edges(mesh_);
}

void ClothOnBody::replace_mesh(TriangleMesh mesh) {
  validate(mesh, "cloth on body");
  mesh_ = std::move(mesh);
  edges_ = rest_edges(mesh_);
  hinges_ = interior_edges(mesh_);
  const std::size_t kept = std::min(active.size(), mesh_.vertex_count());
  active.resize(kept);
  fixed.resize(kept);
  active.resize(mesh_.vertex_count(), true);
  fixed.resize(mesh_.vertex_count(), false);
}

void ClothOnBody::add_reference_triangle_pull(std::vector<Eigen::Vector3d>& pull,
                                              std::vector<int>& count,
                                              const std::vector<BodyPoint>& near) const {
  const auto& x = mesh_.positions;
  for (std::size_t t = 0; t < mesh_.triangle_count(); ++t) {
    const auto& corners = mesh_.triangles[t];
    if (!active[std::size_t(corners[0])] || !active[std::size_t(corners[1])] ||
        !active[std::size_t(corners[2])])
      continue;
    const auto& uv = mesh_.material_uv[t];
    std::array<Eigen::Vector3d, 3> p;
    Eigen::Vector3d body_normal = Eigen::Vector3d::Zero();
    double distance = 0.0;
    for (std::size_t c = 0; c < 3; ++c) {
      p[c] = x[std::size_t(corners[c])];
      body_normal += near[std::size_t(corners[c])].normal;
      distance += near[std::size_t(corners[c])].distance / 3.0;
    }
    // The temporary normal: the body's near it, the cloth's front far from it.
    const double orientation = cross2(uv[1] - uv[0], uv[2] - uv[0]) > 0.0 ? 1.0 : -1.0;
    Eigen::Vector3d cloth_normal = orientation * (p[1] - p[0]).cross(p[2] - p[0]);
    if (cloth_normal.norm() > 0.0) cloth_normal.normalize();
    if (body_normal.norm() > 0.0) body_normal.normalize();
    const double blend = std::clamp((distance - parameters_.near_body) /
                                        (parameters_.far_body - parameters_.near_body),
                                    0.0, 1.0);
    Eigen::Vector3d normal = (1.0 - blend) * body_normal + blend * cloth_normal;
    if (normal.norm() < 1e-6) normal = body_normal.norm() > 0.0 ? body_normal : cloth_normal;
    if (normal.norm() < 1e-6) continue;
    normal.normalize();
    // In the plane normal to it, (e1, e2) right-handed about the normal: the
    // rest triangle's (u, v) keep their orientation there, so it lies face up.
    const Eigen::Vector3d e1 = any_perpendicular(normal), e2 = normal.cross(e1);
    std::array<Eigen::Vector2d, 3> current, rest;
    Eigen::Vector2d current_centre = Eigen::Vector2d::Zero(), rest_centre = Eigen::Vector2d::Zero();
    for (std::size_t c = 0; c < 3; ++c) {
      current[c] = {p[c].dot(e1), p[c].dot(e2)};
      rest[c] = uv[c];
      current_centre += current[c] / 3.0;
      rest_centre += rest[c] / 3.0;
    }
    // The turn that best aligns the centred rest corners with the centred
    // current ones (each corner's angle, weighted by the lengths' product).
    double sine = 0.0, cosine = 0.0;
    for (std::size_t c = 0; c < 3; ++c) {
      rest[c] -= rest_centre;
      current[c] -= current_centre;
      sine += cross2(rest[c], current[c]);
      cosine += rest[c].dot(current[c]);
    }
    const double angle = std::atan2(sine, cosine);
    const Eigen::Rotation2Dd turn(angle);
    for (std::size_t c = 0; c < 3; ++c) {
      const Eigen::Vector2d move = turn * rest[c] - current[c];
      pull[std::size_t(corners[c])] += move.x() * e1 + move.y() * e2;
      ++count[std::size_t(corners[c])];
    }
  }
}

void ClothOnBody::add_flattening(std::vector<Eigen::Vector3d>& move) const {
  const auto& x = mesh_.positions;
  std::vector<Eigen::Vector3d> sum(x.size(), Eigen::Vector3d::Zero());
  std::vector<int> count(x.size(), 0);
  for (const Hinge& hinge : hinges_) {
    const auto& v = hinge.vertices;
    if (!active[std::size_t(v[0])] || !active[std::size_t(v[1])] || !active[std::size_t(v[2])] ||
        !active[std::size_t(v[3])])
      continue;
    const Eigen::Vector3d &x0 = x[std::size_t(v[0])], &x1 = x[std::size_t(v[1])],
                          &x2 = x[std::size_t(v[2])], &x3 = x[std::size_t(v[3])];
    const Eigen::Vector3d edge = (x1 - x0).normalized();
    const Eigen::Vector3d wings = 0.5 * (x2 + x3);
    const Eigen::Vector3d foot = x0 + (wings - x0).dot(edge) * edge;
    Eigen::Vector3d normal = (x1 - x0).cross(x2 - x0);
    const Eigen::Vector3d second = (x0 - x1).cross(x3 - x1);
    if (normal.dot(second) > 0.0) normal += second;
    if (normal.norm() == 0.0) continue;
    normal.normalize();
    // Only the part out of the hinge's mean plane: in-plane asymmetry of the
    // two triangles is the reference triangles' business.
    const Eigen::Vector3d lift = (foot - wings).dot(normal) * normal;
    for (int k = 0; k < 4; ++k) {
      sum[std::size_t(v[std::size_t(k)])] += k < 2 ? -lift : lift;
      ++count[std::size_t(v[std::size_t(k)])];
    }
  }
  for (std::size_t i = 0; i < x.size(); ++i)
    if (count[i] > 0) move[i] += parameters_.flatten_rate * sum[i] / count[i];
}

bool ClothOnBody::held_by_friction(const Eigen::Vector3d& move, const BodyPoint& near) const {
  // In contact: within half an offset of where the cloth is kept.
  if (near.distance > 1.5 * parameters_.offset) return false;
  const Eigen::Vector3d tangential = move - move.dot(near.normal) * near.normal;
  return tangential.dot(parameters_.down) > 0.0 && move.norm() < parameters_.friction_limit;
}

int ClothOnBody::hold_back_at_bones(const std::vector<Eigen::Vector3d>& before) {
  if (bones.empty()) return 0;
  auto& x = mesh_.positions;
  std::vector<Box3> bone_boxes;
  for (const Bone& bone : bones)
    bone_boxes.push_back(box_of({bone.start, bone.end}));
  const auto sweeps_a_bone = [&](std::size_t a, std::size_t b) {
    const Box3 sweep = box_of({before[a], before[b], x[a], x[b]});
    for (std::size_t k = 0; k < bones.size(); ++k)
      if (sweep.overlaps(bone_boxes[k]) &&
          edge_sweep_meets_segment(before[a], before[b], x[a], x[b], bones[k].start, bones[k].end))
        return true;
    return false;
  };
  // Each pass puts back at least one vertex for good, so the passes end.
  int held = 0;
  for (bool changed = true; changed;) {
    changed = false;
    for (const auto& [a_index, b_index] : edges_.edges) {
      const std::size_t a = std::size_t(a_index), b = std::size_t(b_index);
      if (!active[a] || !active[b] || (x[a] == before[a] && x[b] == before[b])) continue;
      if (!sweeps_a_bone(a, b)) continue;
      for (std::size_t v : {a, b}) {
        if (x[v] == before[v]) continue;
        x[v] = before[v];
        ++held;
      }
      changed = true;
    }
  }
  bone_holds_ += held;
  return held;
}

void ClothOnBody::relax(int steps) {
  auto& x = mesh_.positions;
  const std::size_t n = x.size();
  for (int step = 0; step < steps; ++step) {
    const std::vector<Eigen::Vector3d> before = bones.empty() ? std::vector<Eigen::Vector3d>{} : x;
    std::vector<BodyPoint> near(n);
    for (std::size_t i = 0; i < n; ++i)
      if (active[i]) near[i] = nearest_body_point(body_, x[i]);
    std::vector<Eigen::Vector3d> pull(n, Eigen::Vector3d::Zero()), move(n, Eigen::Vector3d::Zero());
    std::vector<int> count(n, 0);
    add_reference_triangle_pull(pull, count, near);
    add_flattening(move);
    for (std::size_t i = 0; i < n; ++i) {
      if (!active[i] || fixed[i]) continue;
      if (count[i] > 0) move[i] += parameters_.stretch_rate * pull[i] / count[i];
      move[i] += parameters_.gravity_step * parameters_.down;
      if (held_by_friction(move[i], near[i])) continue;
      // No step past the body's nearest point: only vertices are kept out.
      if (move[i].norm() > parameters_.max_step) move[i] *= parameters_.max_step / move[i].norm();
      x[i] = keep_above(body_, x[i] + move[i], parameters_.offset);
    }
    hold_back_at_bones(before);
  }
}

EdgeRatios edge_length_ratios(const RestEdges& edges,
                              const std::vector<Eigen::Vector3d>& positions) {
  EdgeRatios ratios;
  ratios.min = std::numeric_limits<double>::infinity();
  ratios.max = 0.0;
  for (std::size_t e = 0; e < edges.edges.size(); ++e) {
    const auto& [a, b] = edges.edges[e];
    const double ratio =
        (positions[std::size_t(a)] - positions[std::size_t(b)]).norm() / edges.lengths[e];
    ratios.min = std::min(ratios.min, ratio);
    ratios.max = std::max(ratios.max, ratio);
    ratios.mean += ratio / double(edges.edges.size());
  }
  return ratios;
}

double min_body_distance(const contact::Shape& body,
                         const std::vector<Eigen::Vector3d>& positions) {
  double smallest = std::numeric_limits<double>::infinity();
  for (const Eigen::Vector3d& p : positions)
    smallest = std::min(smallest, body.query(p).distance);
  return smallest;
}

} // namespace sartor::garment
