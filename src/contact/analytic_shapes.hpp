#pragma once
// Analytic obstacles with exact signed distance, normal and distance Hessian.
//
// Every shape here is a point, segment, circle or box "inflated" by a radius:
// the distance to the core feature minus the radius. The normal is the unit
// vector from the closest core point to p; the Hessian is that of the distance
// to the core (the radius does not change it): zero on flat faces,
// (I - n n^T) / rho at a point core, the same minus the feature's tangent
// directions for a line core, and the curvature of the circle for a rim.

#include "contact/shape.hpp"

#include <Eigen/Core>

namespace sartor::contact {

// The half-space below the plane through `point` with outward `normal`.
class Plane : public Shape {
public:
  Plane(const Eigen::Vector3d& point, const Eigen::Vector3d& normal);
  SurfaceQuery query(const Eigen::Vector3d& p) const override;
  std::string describe() const override;

private:
  Eigen::Vector3d point_;
  Eigen::Vector3d normal_;
};

class Sphere : public Shape {
public:
  Sphere(const Eigen::Vector3d& center, double radius);
  SurfaceQuery query(const Eigen::Vector3d& p) const override;
  std::string describe() const override;

private:
  Eigen::Vector3d center_;
  double radius_;
};

// All points within `radius` of the segment a-b (round ends).
class Capsule : public Shape {
public:
  Capsule(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double radius);
  SurfaceQuery query(const Eigen::Vector3d& p) const override;
  std::string describe() const override;

private:
  Eigen::Vector3d a_;
  Eigen::Vector3d b_;
  double radius_;
};

// A finite cylinder with flat caps (sharp rims): `center` is the middle of its
// axis, `direction` the axis, `height` the distance between the caps. A disk
// (a thin round table top) is a short one.
class Cylinder : public Shape {
public:
  Cylinder(const Eigen::Vector3d& center, const Eigen::Vector3d& direction, double radius,
           double height);
  SurfaceQuery query(const Eigen::Vector3d& p) const override;
  std::string describe() const override;

private:
  Eigen::Vector3d center_;
  Eigen::Vector3d axis_;
  double radius_;
  double half_height_;
};

// An axis-aligned box of full extents `size` around `center`; with
// `rounding` > 0 its edges and corners are rounded with that radius (the
// outer extents stay `size`).
class Box : public Shape {
public:
  Box(const Eigen::Vector3d& center, const Eigen::Vector3d& size, double rounding = 0.0);
  SurfaceQuery query(const Eigen::Vector3d& p) const override;
  std::string describe() const override;

private:
  Eigen::Vector3d center_;
  Eigen::Vector3d core_half_; // half extents of the box before rounding
  double rounding_;
};

} // namespace sartor::contact
