#include "fem/posed_mannequin.hpp"

#include "common/error.hpp"

#include <algorithm>
#include <cmath>
#include <set>
#include <sstream>

namespace sartor {

namespace {

// The largest change of any joint's angle between two poses, degrees.
double largest_change(const Pose& a, const Pose& b) {
  std::set<std::string> joints;
  for (const Pose* pose : {&a, &b})
    for (const auto& [joint, degrees] : pose->degrees)
      joints.insert(joint);
  double change = 0.0;
  for (const std::string& joint : joints)
    change = std::max(change, std::abs(a.angle(joint) - b.angle(joint)));
  return change;
}

// The bone whose flesh p is nearest: the distance to its segment less its
// radius there (interpolated along it).
std::size_t nearest_bone(const std::vector<Bone>& bones, const Eigen::Vector3d& p) {
  std::size_t nearest = 0;
  double least = INFINITY;
  for (std::size_t b = 0; b < bones.size(); ++b) {
    const Eigen::Vector3d axis = bones[b].end - bones[b].start;
    const double length2 = axis.squaredNorm();
    const double s =
        length2 > 0.0 ? std::clamp((p - bones[b].start).dot(axis) / length2, 0.0, 1.0) : 0.0;
    const double radius = (1.0 - s) * bones[b].start_radius + s * bones[b].end_radius;
    const double distance = (p - (bones[b].start + s * axis)).norm() - radius;
    if (distance < least) {
      least = distance;
      nearest = b;
    }
  }
  return nearest;
}

} // namespace

PosedMannequin::PosedMannequin(MannequinModel model, contact::PoseHistory history,
                               double largest_turn)
    : model_(std::move(model)), history_(std::move(history)), largest_turn_(largest_turn) {
  if (history_.empty()) throw InputError("posed mannequin: the pose history has no keyframes");
  if (!(largest_turn_ > 0.0)) {
    throw InputError("posed mannequin: the largest turn per step must be positive, got " +
                     std::to_string(largest_turn_));
  }
  for (const auto& [time, pose] : history_.keyframes()) {
    check_pose(pose);
    slope_bound_ = std::max(slope_bound_, model_.posed(pose).slope_bound());
  }
  unposed_bones_ = model_.posed(Pose{}).skeleton();
  posed_at(history_.keyframes().front().first);
}

const PosedMannequin::Posed& PosedMannequin::posed_at(double time) const {
  if (!posed_.shape || time != posed_.time) {
    const MannequinModel posed = model_.posed(history_.at(time));
    posed_.shape = contact::make_posed_mannequin_shape(posed, posed.pose());
    posed_.bones = posed.skeleton();
    posed_.motions = posed.bone_motions();
    posed_.time = time;
  }
  return posed_;
}

contact::SurfaceQuery PosedMannequin::query(const Eigen::Vector3d& p, double time) const {
  return posed_at(time).shape->query(p);
}

contact::SurfaceQuery PosedMannequin::partial_query(const Eigen::Vector3d& p, double time,
                                                    contact::QueryNeeds needs) const {
  return posed_at(time).shape->partial_query(p, needs);
}

Eigen::Vector3d PosedMannequin::to_reference(const Eigen::Vector3d& p, double time) const {
  const Posed& posed = posed_at(time);
  const BoneMotion& m = posed.motions[nearest_bone(posed.bones, p)];
  return m.rotation.transpose() * (p - m.shift);
}

Eigen::Vector3d PosedMannequin::from_reference(const Eigen::Vector3d& q, double time) const {
  const BoneMotion& m = posed_at(time).motions[nearest_bone(unposed_bones_, q)];
  return m.rotation * q + m.shift;
}

Eigen::Vector3d PosedMannequin::direction_to_reference(const Eigen::Vector3d& p,
                                                       const Eigen::Vector3d& d,
                                                       double time) const {
  const Posed& posed = posed_at(time);
  return posed.motions[nearest_bone(posed.bones, p)].rotation.transpose() * d;
}

Eigen::Vector3d PosedMannequin::direction_from_reference(const Eigen::Vector3d& q,
                                                         const Eigen::Vector3d& d,
                                                         double time) const {
  return posed_at(time).motions[nearest_bone(unposed_bones_, q)].rotation * d;
}

std::string PosedMannequin::describe() const {
  std::ostringstream out;
  out << "mannequin following a pose history (" << history_.keyframes().size()
      << " keyframes, at most " << largest_turn_ << " deg per step)";
  return out.str();
}

std::vector<double> PosedMannequin::knots() const {
  const auto& keyframes = history_.keyframes();
  std::vector<double> times{keyframes.front().first};
  for (std::size_t k = 1; k < keyframes.size(); ++k) {
    const auto& [t0, p0] = keyframes[k - 1];
    const auto& [t1, p1] = keyframes[k];
    const auto pieces = long(std::ceil(largest_change(p0, p1) / largest_turn_ - 1e-9));
    for (long i = 1; i < pieces; ++i)
      times.push_back(t0 + (t1 - t0) * double(i) / double(pieces));
    times.push_back(t1);
  }
  return times;
}

} // namespace sartor
