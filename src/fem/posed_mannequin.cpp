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
  shape_time_ = history_.keyframes().front().first;
  shape_ = contact::make_posed_mannequin_shape(model_, history_.at(shape_time_));
}

const contact::Shape& PosedMannequin::shape_at(double time) const {
  if (time != shape_time_) {
    shape_ = contact::make_posed_mannequin_shape(model_, history_.at(time));
    shape_time_ = time;
  }
  return *shape_;
}

contact::SurfaceQuery PosedMannequin::query(const Eigen::Vector3d& p, double time) const {
  return shape_at(time).query(p);
}

contact::SurfaceQuery PosedMannequin::partial_query(const Eigen::Vector3d& p, double time,
                                                    contact::QueryNeeds needs) const {
  return shape_at(time).partial_query(p, needs);
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
