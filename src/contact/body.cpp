#include "contact/body.hpp"

#include "common/error.hpp"

#include <Eigen/Geometry>

#include <sstream>

namespace sartor::contact {

template <typename Value>
void PiecewiseLinear<Value>::add(double time, const Value& value) {
  if (!samples_.empty() && !(time > samples_.back().first)) {
    std::ostringstream message;
    message << "motion sample times must increase: " << time << " follows "
            << samples_.back().first;
    throw InputError(message.str());
  }
  samples_.emplace_back(time, value);
}

template <typename Value>
Value PiecewiseLinear<Value>::at(double time) const {
  if (samples_.empty()) return fallback_;
  if (time <= samples_.front().first) return samples_.front().second;
  if (time >= samples_.back().first) return samples_.back().second;
  std::size_t k = 1;
  while (samples_[k].first < time)
    ++k;
  const auto& [t0, v0] = samples_[k - 1];
  const auto& [t1, v1] = samples_[k];
  const double w = (time - t0) / (t1 - t0);
  return Value((1.0 - w) * v0 + w * v1);
}

template class PiecewiseLinear<double>;
template class PiecewiseLinear<Eigen::Vector3d>;

Body::Body(std::string name, std::shared_ptr<const Shape> shape, const Eigen::Vector3d& pivot)
    : name_(std::move(name)), shape_(std::move(shape)), pivot_(pivot) {}

Eigen::Matrix3d Body::rotation(double time) const {
  return Eigen::AngleAxisd(motion.angle.at(time), motion.rotation_axis).toRotationMatrix();
}

Eigen::Vector3d Body::to_world(const Eigen::Vector3d& p, double time) const {
  return pivot_ + motion.translation.at(time) +
         motion.scale.at(time) * rotation(time) * (p - pivot_);
}

Eigen::Vector3d Body::to_body(const Eigen::Vector3d& x, double time) const {
  return pivot_ + rotation(time).transpose() * (x - pivot_ - motion.translation.at(time)) /
                      motion.scale.at(time);
}

Eigen::Vector3d Body::direction_to_world(const Eigen::Vector3d& direction, double time) const {
  return rotation(time) * direction;
}

Eigen::Vector3d Body::direction_to_body(const Eigen::Vector3d& direction, double time) const {
  return rotation(time).transpose() * direction;
}

Eigen::Vector3d Body::anchor_from_world(const Eigen::Vector3d& x, double time) const {
  return shape_->to_reference(to_body(x, time));
}

Eigen::Vector3d Body::anchor_to_world(const Eigen::Vector3d& point, double time) const {
  return to_world(shape_->from_reference(point), time);
}

Eigen::Vector3d Body::anchor_direction_from_world(const Eigen::Vector3d& x,
                                                  const Eigen::Vector3d& direction,
                                                  double time) const {
  return shape_->direction_to_reference(to_body(x, time), direction_to_body(direction, time));
}

Eigen::Vector3d Body::anchor_direction_to_world(const Eigen::Vector3d& point,
                                                const Eigen::Vector3d& direction,
                                                double time) const {
  return direction_to_world(shape_->direction_from_reference(point, direction), time);
}

SurfaceQuery Body::query(const Eigen::Vector3d& x, double time) const {
  return query(x, time, QueryNeeds::curvature);
}

SurfaceQuery Body::query(const Eigen::Vector3d& x, double time, QueryNeeds needs) const {
  const Eigen::Matrix3d r = rotation(time);
  const double s = motion.scale.at(time);
  const Eigen::Vector3d shift = pivot_ + motion.translation.at(time);
  const Eigen::Vector3d p = pivot_ + r.transpose() * (x - shift) / s;
  const SurfaceQuery local = shape_->partial_query(p, needs);
  // d(x) = s d_b(p(x)), dp/dx = R^T / s: the normal rotates, the curvature
  // shrinks by the scale.
  SurfaceQuery world;
  world.distance = s * local.distance;
  if (needs == QueryNeeds::distance) return world;
  world.normal = r * local.normal;
  world.closest = shift + s * r * (local.closest - pivot_);
  if (needs == QueryNeeds::normal) return world;
  world.hessian = r * local.hessian * r.transpose() / s;
  return world;
}

std::string Body::describe() const {
  std::ostringstream out;
  out << name_ << ": " << shape_->describe();
  if (friction.active()) {
    out << ", mu_s=" << friction.static_coefficient << ", mu_k=" << friction.kinetic_coefficient;
  }
  if (!motion.translation.empty() || !motion.angle.empty() || !motion.scale.empty()) {
    out << ", moving";
  }
  return out.str();
}

} // namespace sartor::contact
