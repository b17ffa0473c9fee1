#include "solvers/posed_mannequin.hpp"

#include "common/error.hpp"

#include <algorithm>
#include <cmath>
#include <set>
#include <sstream>
#include <utility>

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

// The reference frame is an atlas of the bones' unposed frames: bone b's
// chart is the unposed body shifted by (b + 1) chart spacings along x, so a
// reference point names the bone that carries it and every pose carries it
// with that bone. (Near a bent joint the bone nearest a posed point and the
// one nearest its unposed image can differ, and choosing the carrier afresh
// on the way back made anchors there jump by centimetres.) Chart 0 is the
// unposed body itself, each point carried by the bone nearest it: the
// standing drape's anchors arrive in it.
constexpr double chart_spacing = 100.0; // m, far beyond any body's size

Eigen::Vector3d chart_offset(std::size_t chart) {
  return Eigen::Vector3d(chart_spacing * double(chart), 0.0, 0.0);
}

// The bone that carries reference point q and q in the unposed body.
std::pair<std::size_t, Eigen::Vector3d> carrier(const std::vector<Bone>& unposed,
                                                const Eigen::Vector3d& q) {
  const long chart = std::lround(q.x() / chart_spacing);
  if (chart <= 0) return {nearest_bone(unposed, q), q};
  if (std::size_t(chart) > unposed.size()) {
    throw InputError("posed mannequin: a friction anchor lies in chart " + std::to_string(chart) +
                     " (bone " + std::to_string(chart - 1) + "), but the body has " +
                     std::to_string(unposed.size()) +
                     " bones (anchors from a checkpoint of another body?)");
  }
  const Eigen::Vector3d unposed_point = q - chart_offset(std::size_t(chart));
  return {std::size_t(chart - 1), unposed_point};
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
  const std::size_t bone = nearest_bone(posed.bones, p);
  const BoneMotion& m = posed.motions[bone];
  return m.rotation.transpose() * (p - m.shift) + chart_offset(bone + 1);
}

Eigen::Vector3d PosedMannequin::from_reference(const Eigen::Vector3d& q, double time) const {
  const auto [bone, unposed_point] = carrier(unposed_bones_, q);
  const BoneMotion& m = posed_at(time).motions[bone];
  return m.rotation * unposed_point + m.shift;
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
  return posed_at(time).motions[carrier(unposed_bones_, q).first].rotation * d;
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
