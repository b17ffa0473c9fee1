#pragma once
// A rigid (or uniformly growing) obstacle: a Shape placed in the world by a
// motion over time, with Coulomb friction coefficients and a name.
//
// The motion maps a body-frame point p to the world at time t as
//     x = c + u(t) + s(t) R(t) (p - c),
// c the pivot (a fixed point of the body frame, e.g. the sphere's centre),
// u the translation, R a rotation by angle(t) about `rotation_axis` through
// the pivot, s a uniform scale about the pivot (the thesis' cylinder that
// expands to 1.5 times its radius). Each of u, angle, s is a piecewise-linear
// history of samples (t_i, value_i), held constant before the first and after
// the last sample. Signed distances scale with s, normals rotate with R and
// the distance Hessian transforms as R H R^T / s.

#include "contact/shape.hpp"

#include <Eigen/Core>

#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace sartor::contact {

class BoneIntervals; // contact/bone_intervals.hpp

// Samples (time, value), times strictly increasing; empty = always `fallback`.
template <typename Value>
class PiecewiseLinear {
public:
  explicit PiecewiseLinear(Value fallback) : fallback_(std::move(fallback)) {}
  // Throws InputError when `time` does not exceed the last sample's time.
  void add(double time, const Value& value);
  Value at(double time) const;
  bool empty() const { return samples_.empty(); }
  // The sample times, increasing.
  std::vector<double> times() const {
    std::vector<double> result;
    for (const auto& sample : samples_)
      result.push_back(sample.first);
    return result;
  }

private:
  Value fallback_;
  std::vector<std::pair<double, Value>> samples_;
};

struct Motion {
  PiecewiseLinear<Eigen::Vector3d> translation{Eigen::Vector3d::Zero()}; // m
  PiecewiseLinear<double> angle{0.0};                                    // rad
  Eigen::Vector3d rotation_axis = Eigen::Vector3d::UnitZ();              // unit
  PiecewiseLinear<double> scale{1.0};                                    // > 0
};

struct Friction {
  double static_coefficient = 0.0;  // mu_s: sticking while |f_t| <= mu_s f_n
  double kinetic_coefficient = 0.0; // mu_k: sliding friction |f_t| = mu_k f_n
  bool active() const { return static_coefficient > 0.0; }
};

class Body {
public:
  Body(std::string name, std::shared_ptr<const Shape> shape, const Eigen::Vector3d& pivot);

  const std::string& name() const { return name_; }
  const Shape& shape() const { return *shape_; }
  const Eigen::Vector3d& pivot() const { return pivot_; }
  Motion motion;
  Friction friction;
  // The thesis' spatial index of the body's mesh by bones and intervals, in
  // the body's frame, where one was built for finding points inside before a
  // solve (ClothProblem::push_out_of_bodies); null elsewhere.
  std::shared_ptr<const BoneIntervals> bone_intervals;

  // The shape's query at world point x and time t, in world terms.
  SurfaceQuery query(const Eigen::Vector3d& x, double time) const;
  // Only what `needs` asks for (Shape::partial_query), in world terms.
  SurfaceQuery query(const Eigen::Vector3d& x, double time, QueryNeeds needs) const;
  // The signed distance alone (QueryNeeds::distance), m.
  double distance(const Eigen::Vector3d& x, double time) const {
    return query(x, time, QueryNeeds::distance).distance;
  }
  // Body-frame point -> world point at time t, and back.
  Eigen::Vector3d to_world(const Eigen::Vector3d& p, double time) const;
  Eigen::Vector3d to_body(const Eigen::Vector3d& x, double time) const;
  // A body-frame direction (e.g. a normal) in the world at time t.
  Eigen::Vector3d direction_to_world(const Eigen::Vector3d& direction, double time) const;
  Eigen::Vector3d direction_to_body(const Eigen::Vector3d& direction, double time) const;
  // A friction anchor's place: a world point on the surface at time t as a
  // point of the shape's reference frame (Shape::to_reference), and back;
  // the anchor's plane normal likewise (`point`: the anchor's reference point).
  Eigen::Vector3d anchor_from_world(const Eigen::Vector3d& x, double time) const;
  Eigen::Vector3d anchor_to_world(const Eigen::Vector3d& point, double time) const;
  Eigen::Vector3d anchor_direction_from_world(const Eigen::Vector3d& x,
                                              const Eigen::Vector3d& direction, double time) const;
  Eigen::Vector3d anchor_direction_to_world(const Eigen::Vector3d& point,
                                            const Eigen::Vector3d& direction, double time) const;
  // "NAME: shape ..., mu_s=..., mu_k=..." for logs.
  std::string describe() const;

private:
  Eigen::Matrix3d rotation(double time) const;

  std::string name_;
  std::shared_ptr<const Shape> shape_;
  Eigen::Vector3d pivot_;
};

} // namespace sartor::contact
