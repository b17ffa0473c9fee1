#include "contact/analytic_shapes.hpp"

#include "common/error.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace sartor::contact {

namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;

std::string vector_text(const Vector3d& v) {
  std::ostringstream out;
  out << v.x() << "," << v.y() << "," << v.z();
  return out.str();
}

Vector3d unit(const Vector3d& v, const char* what) {
  const double length = v.norm();
  if (!(length > 0.0) || !std::isfinite(length)) {
    throw InputError(std::string(what) + " must be a non-zero vector, got " + vector_text(v));
  }
  return v / length;
}

void require_positive(double value, const char* what) {
  if (!(value > 0.0) || !std::isfinite(value)) {
    throw InputError(std::string(what) + " must be > 0, got " + std::to_string(value));
  }
}

// Any unit vector perpendicular to the unit vector `a`.
Vector3d perpendicular(const Vector3d& a) {
  const Vector3d trial = std::abs(a.x()) < 0.9 ? Vector3d::UnitX() : Vector3d::UnitY();
  return (trial - trial.dot(a) * a).normalized();
}

// The distance from p to a point core at `core`, inflated by `radius`. At the
// core itself (a medial point) the normal is `fallback`.
SurfaceQuery around_point(const Vector3d& p, const Vector3d& core, double radius,
                          const Vector3d& fallback) {
  SurfaceQuery q;
  const Vector3d w = p - core;
  const double rho = w.norm();
  if (rho > 0.0) {
    q.normal = w / rho;
    q.hessian = (Matrix3d::Identity() - q.normal * q.normal.transpose()) / rho;
  } else {
    q.normal = fallback;
  }
  q.distance = rho - radius;
  q.closest = core + radius * q.normal;
  return q;
}

} // namespace

Plane::Plane(const Vector3d& point, const Vector3d& normal)
    : point_(point), normal_(unit(normal, "plane normal")) {}

SurfaceQuery Plane::query(const Vector3d& p) const {
  SurfaceQuery q;
  q.distance = normal_.dot(p - point_);
  q.normal = normal_;
  q.closest = p - q.distance * normal_;
  return q;
}

std::string Plane::describe() const {
  return "plane point=" + vector_text(point_) + " normal=" + vector_text(normal_);
}

Sphere::Sphere(const Vector3d& center, double radius) : center_(center), radius_(radius) {
  require_positive(radius, "sphere radius");
}

SurfaceQuery Sphere::query(const Vector3d& p) const {
  return around_point(p, center_, radius_, Vector3d::UnitZ());
}

std::string Sphere::describe() const {
  std::ostringstream out;
  out << "sphere center=" << vector_text(center_) << " radius=" << radius_;
  return out.str();
}

Capsule::Capsule(const Vector3d& a, const Vector3d& b, double radius)
    : a_(a), b_(b), radius_(radius) {
  require_positive(radius, "capsule radius");
  unit(b - a, "capsule axis b - a");
}

SurfaceQuery Capsule::query(const Vector3d& p) const {
  const Vector3d axis = b_ - a_;
  const double length = axis.norm();
  const Vector3d u = axis / length;
  const double along = (p - a_).dot(u);
  if (along <= 0.0) return around_point(p, a_, radius_, -u);
  if (along >= length) return around_point(p, b_, radius_, u);
  // Beside the segment: the distance to a line, flat along it.
  SurfaceQuery q = around_point(p, a_ + along * u, radius_, perpendicular(u));
  const double rho = q.distance + radius_;
  if (rho > 0.0) q.hessian -= u * u.transpose() / rho;
  return q;
}

std::string Capsule::describe() const {
  std::ostringstream out;
  out << "capsule a=" << vector_text(a_) << " b=" << vector_text(b_) << " radius=" << radius_;
  return out.str();
}

Cylinder::Cylinder(const Vector3d& center, const Vector3d& direction, double radius, double height)
    : center_(center), axis_(unit(direction, "cylinder direction")), radius_(radius),
      half_height_(0.5 * height) {
  require_positive(radius, "cylinder radius");
  require_positive(height, "cylinder height");
}

SurfaceQuery Cylinder::query(const Vector3d& p) const {
  const Vector3d relative = p - center_;
  const double z = axis_.dot(relative);
  const Vector3d radial = relative - z * axis_;
  const double rho = radial.norm();
  const Vector3d e_r = rho > 0.0 ? Vector3d(radial / rho) : perpendicular(axis_);
  const double side = z >= 0.0 ? 1.0 : -1.0;
  const double beyond_side = rho - radius_;             // > 0 outside the mantle
  const double beyond_cap = std::abs(z) - half_height_; // > 0 beyond a cap
  const Matrix3d in_plane = Matrix3d::Identity() - axis_ * axis_.transpose();
  const Matrix3d hoop = in_plane - e_r * e_r.transpose(); // e_phi e_phi^T
  SurfaceQuery q;
  if (beyond_side > 0.0 && beyond_cap > 0.0) {
    // Nearest to the rim circle: the normal points from it to p; the Hessian
    // is that of the distance to a circle of radius R (hoop curvature R / rho).
    const Vector3d rim = center_ + radius_ * e_r + side * half_height_ * axis_;
    const Vector3d w = p - rim;
    q.distance = w.norm();
    q.normal = w / q.distance;
    q.closest = rim;
    q.hessian = (Matrix3d::Identity() - q.normal * q.normal.transpose()) / q.distance -
                radius_ / (rho * q.distance) * hoop;
    return q;
  }
  if (beyond_side > beyond_cap) {
    // The mantle: distance rho - R, curved around the axis.
    q.distance = beyond_side;
    q.normal = e_r;
    q.closest = p - beyond_side * e_r;
    if (rho > 0.0) q.hessian = hoop / rho;
    return q;
  }
  q.distance = beyond_cap; // a flat cap
  q.normal = side * axis_;
  q.closest = p - beyond_cap * q.normal;
  return q;
}

std::string Cylinder::describe() const {
  std::ostringstream out;
  out << "cylinder center=" << vector_text(center_) << " direction=" << vector_text(axis_)
      << " radius=" << radius_ << " height=" << 2.0 * half_height_;
  return out.str();
}

Box::Box(const Vector3d& center, const Vector3d& size, double rounding)
    : center_(center), core_half_(0.5 * size - Vector3d::Constant(rounding)), rounding_(rounding) {
  for (int i = 0; i < 3; ++i)
    require_positive(size[i], "box size");
  if (!(rounding >= 0.0) || core_half_.minCoeff() < 0.0) {
    throw InputError("box rounding must lie in [0, smallest size / 2], got " +
                     std::to_string(rounding));
  }
}

SurfaceQuery Box::query(const Vector3d& p) const {
  const Vector3d relative = p - center_;
  Vector3d sign, beyond;
  for (int i = 0; i < 3; ++i) {
    sign[i] = relative[i] >= 0.0 ? 1.0 : -1.0;
    beyond[i] = std::abs(relative[i]) - core_half_[i];
  }
  SurfaceQuery q;
  if (beyond.maxCoeff() > 0.0) {
    // Outside the core: the nearest feature (face, edge or corner) is spanned
    // by the directions still inside; the distance to it curves only across
    // the directions that are outside.
    Vector3d w = Vector3d::Zero();
    Matrix3d across = Matrix3d::Zero();
    for (int i = 0; i < 3; ++i) {
      if (beyond[i] <= 0.0) continue;
      w[i] = sign[i] * beyond[i];
      across(i, i) = 1.0;
    }
    const double core_distance = w.norm();
    q.normal = w / core_distance;
    q.hessian = (across - q.normal * q.normal.transpose()) / core_distance;
    q.distance = core_distance - rounding_;
    q.closest = p - q.distance * q.normal;
    return q;
  }
  // Inside the core: the nearest face.
  int face = 0;
  beyond.maxCoeff(&face);
  q.normal = sign[face] * Vector3d::Unit(face);
  q.distance = beyond[face] - rounding_;
  q.closest = p - q.distance * q.normal;
  return q;
}

std::string Box::describe() const {
  std::ostringstream out;
  out << "box center=" << vector_text(center_)
      << " size=" << vector_text(2.0 * (core_half_ + Vector3d::Constant(rounding_)));
  if (rounding_ > 0.0) out << " rounding=" << rounding_;
  return out.str();
}

} // namespace sartor::contact
