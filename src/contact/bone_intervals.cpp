#include "contact/bone_intervals.hpp"

#include "common/error.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>

namespace sartor::contact {

namespace {

using Eigen::Vector3d;

// Barycentric distance from a triangle's edge below which a ray's hit is too
// close to call: the parity of crossings would then hang on round-off.
constexpr double edge_band = 1e-7;

enum class Hit { none, crosses, grazes };

// Moller and Trumbore: whether the ray origin + t direction (t > 0) meets the
// triangle, and at which t.
Hit ray_hit(const Vector3d& origin, const Vector3d& direction, const Vector3d& p0,
            const Vector3d& e1, const Vector3d& e2, double* t) {
  const Vector3d h = direction.cross(e2);
  const double determinant = e1.dot(h);
  const double scale = direction.norm() * e1.norm() * e2.norm();
  if (std::abs(determinant) <= edge_band * scale) return Hit::none; // parallel
  const Vector3d from_corner = origin - p0;
  const double u = from_corner.dot(h) / determinant;
  const Vector3d q = from_corner.cross(e1);
  const double v = direction.dot(q) / determinant;
  *t = e2.dot(q) / determinant;
  if (*t <= 0.0 || u < -edge_band || v < -edge_band || u + v > 1.0 + edge_band) return Hit::none;
  if (u < edge_band || v < edge_band || u + v > 1.0 - edge_band) return Hit::grazes;
  return Hit::crosses;
}

std::pair<double, double> segment_parameter_and_distance(const Vector3d& start,
                                                         const Vector3d& axis, const Vector3d& x) {
  const double squared = axis.squaredNorm();
  const double s = squared > 0.0 ? std::clamp((x - start).dot(axis) / squared, 0.0, 1.0) : 0.0;
  return {s, (start + s * axis - x).norm()};
}

} // namespace

BoneIntervals::BoneIntervals(const BodyMesh& mesh, const std::vector<Bone>& bones, double interval)
    : interval_(interval) {
  if (bones.empty()) throw InputError("bone intervals: the body has no bones");
  if (!(interval > 0.0))
    throw InputError("bone intervals: the interval length must be > 0, got " +
                     std::to_string(interval));
  for (const auto& face : mesh.faces) {
    const Vector3d& p0 = mesh.vertices[std::size_t(face[0])];
    triangles_.push_back(
        {p0, mesh.vertices[std::size_t(face[1])] - p0, mesh.vertices[std::size_t(face[2])] - p0});
  }
  for (const Bone& bone : bones) {
    FiledBone filed{bone.start, bone.end - bone.start, (bone.end - bone.start).norm(), {}, {}};
    const std::size_t count =
        std::max<std::size_t>(1, std::size_t(std::ceil(filed.length / interval)));
    filed.intervals.resize(count);
    std::vector<bool> end_inside;
    for (std::size_t k = 0; k <= count; ++k)
      end_inside.push_back(
          inside_by_all_triangles(filed.start + double(k) / double(count) * filed.axis));
    for (std::size_t k = 0; k < count; ++k)
      filed.usable.push_back(end_inside[k] && end_inside[k + 1]);
    bones_.push_back(std::move(filed));
  }
  // Alg. 1, lines 5 to 10: each triangle under the bone nearest its centre.
  for (std::size_t t = 0; t < triangles_.size(); ++t) {
    const Triangle& tri = triangles_[t];
    const Vector3d centre = tri.p0 + (tri.e1 + tri.e2) / 3.0;
    const auto [bone, parameter] = nearest_bone(centre);
    bones_[bone].intervals[std::size_t(interval_of(bones_[bone], parameter))].push_back(int(t));
  }
}

std::pair<std::size_t, double> BoneIntervals::nearest_bone(const Vector3d& x) const {
  std::size_t nearest = 0;
  double best = std::numeric_limits<double>::infinity(), parameter = 0.0;
  for (std::size_t b = 0; b < bones_.size(); ++b) {
    const auto [s, distance] = segment_parameter_and_distance(bones_[b].start, bones_[b].axis, x);
    if (distance < best) { // ties: the first bone, whatever the round-off
      best = distance;
      nearest = b;
      parameter = s;
    }
  }
  return {nearest, parameter};
}

int BoneIntervals::interval_of(const FiledBone& bone, double parameter) const {
  const int count = int(bone.intervals.size());
  return std::clamp(int(parameter * count), 0, count - 1);
}

// Parity of crossings along a few fixed directions against every triangle,
// for checking that the bones lie inside (once, at construction).
bool BoneIntervals::inside_by_all_triangles(const Vector3d& x) const {
  const Vector3d directions[] = {Vector3d(0.5377, 0.8147, 0.2176).normalized(),
                                 Vector3d(-0.3188, 0.1449, -0.9367).normalized(),
                                 Vector3d(0.7254, -0.6631, 0.1842).normalized()};
  for (const Vector3d& direction : directions) {
    int crossings = 0;
    bool grazed = false;
    for (const Triangle& tri : triangles_) {
      double t = 0.0;
      const Hit hit = ray_hit(x, direction, tri.p0, tri.e1, tri.e2, &t);
      grazed = grazed || hit == Hit::grazes;
      crossings += hit == Hit::crosses ? 1 : 0;
    }
    if (!grazed) return crossings % 2 == 1;
  }
  return false; // every direction grazed an edge: not trusted as inside
}

BoneIntervals::Detection BoneIntervals::detect(const Vector3d& x) const {
  Detection detection;
  const auto [b, parameter] = nearest_bone(x);
  detection.bone = b;
  const FiledBone& bone = bones_[b];
  const int k = interval_of(bone, parameter);
  const Vector3d origin = bone.start + parameter * bone.axis;
  const Vector3d ray = x - origin;
  const double reach = ray.norm();
  if (!bone.usable[std::size_t(k)] || reach == 0.0) return detection;
  int crossings_before = 0;
  double last_before = 0.0, first_after = std::numeric_limits<double>::infinity();
  const int last = int(bone.intervals.size()) - 1;
  for (int j = std::max(0, k - 1); j <= std::min(last, k + 1); ++j) {
    for (const int t : bone.intervals[std::size_t(j)]) {
      const Triangle& tri = triangles_[std::size_t(t)];
      double along = 0.0;
      const Hit hit = ray_hit(origin, ray, tri.p0, tri.e1, tri.e2, &along);
      if (hit == Hit::grazes) return detection;
      if (hit == Hit::none) continue;
      if (along < 1.0) {
        ++crossings_before;
        last_before = std::max(last_before, along);
      } else {
        first_after = std::min(first_after, along);
      }
    }
  }
  if (crossings_before == 0 && std::isinf(first_after)) return detection; // no surface seen
  if (crossings_before % 2 == 0) {
    if (std::isinf(first_after)) return detection; // inside, yet no way out: not consistent
    detection.side = Side::inside;
    detection.depth = (first_after - 1.0) * reach;
  } else {
    detection.side = Side::outside;
    detection.depth = -(1.0 - last_before) * reach;
  }
  return detection;
}

std::size_t BoneIntervals::intervals() const {
  std::size_t count = 0;
  for (const FiledBone& bone : bones_)
    count += bone.intervals.size();
  return count;
}

std::size_t BoneIntervals::largest_interval() const {
  std::size_t largest = 0;
  for (const FiledBone& bone : bones_)
    for (const auto& triangles : bone.intervals)
      largest = std::max(largest, triangles.size());
  return largest;
}

std::size_t BoneIntervals::intervals_outside() const {
  std::size_t count = 0;
  for (const FiledBone& bone : bones_)
    count += std::size_t(std::count(bone.usable.begin(), bone.usable.end(), false));
  return count;
}

double mesh_deviation(const BodyMesh& mesh, const Shape& shape) {
  double largest = 0.0;
  const auto sample = [&](const Vector3d& p) {
    largest = std::max(largest, std::abs(shape.partial_query(p, QueryNeeds::distance).distance));
  };
  for (const auto& face : mesh.faces) {
    const Vector3d& a = mesh.vertices[std::size_t(face[0])];
    const Vector3d& b = mesh.vertices[std::size_t(face[1])];
    const Vector3d& c = mesh.vertices[std::size_t(face[2])];
    for (const Vector3d& p : {a, Vector3d(0.5 * (a + b)), Vector3d(0.5 * (b + c)),
                              Vector3d(0.5 * (c + a)), Vector3d((a + b + c) / 3.0)})
      sample(p);
  }
  return largest;
}

} // namespace sartor::contact
