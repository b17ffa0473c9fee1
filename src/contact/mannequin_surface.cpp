#include "contact/mannequin_surface.hpp"

#include "common/error.hpp"

#include <set>
#include <sstream>

namespace sartor::contact {

namespace {

class SmoothMannequin : public Shape {
public:
  explicit SmoothMannequin(MannequinModel model, std::string description)
      : model_(std::move(model)), description_(std::move(description)) {}

  SurfaceQuery query(const Eigen::Vector3d& p) const override {
    return from_field(p, model_.field_derivatives(p));
  }

  // The field's value and gradient come out of the same arithmetic whether
  // or not its Hessian is computed too.
  SurfaceQuery partial_query(const Eigen::Vector3d& p, QueryNeeds needs) const override {
    if (needs == QueryNeeds::curvature) return query(p);
    if (needs == QueryNeeds::normal) return from_field(p, model_.field_gradient(p));
    SurfaceQuery result;
    result.distance = model_.field(p);
    return result;
  }

  std::string describe() const override { return description_; }

  // The ellipsoids' first-order distances steepen away from their surfaces:
  // the default's flat hand's slope reaches 6.7 a few metres from the body
  // (sampled in a 6 m box; far out the gradient is homogeneous of degree 0,
  // so it grows no further). Sized bodies scale the bound with their
  // ellipsoids' largest aspect ratio (MannequinModel::slope_bound).
  double slope_bound() const override { return model_.slope_bound(); }

private:
  static SurfaceQuery from_field(const Eigen::Vector3d& p, const MannequinFieldValue& field) {
    SurfaceQuery result;
    result.distance = field.value;
    result.normal = field.gradient;
    result.hessian = field.hessian;
    const double slope = field.gradient.squaredNorm();
    result.closest = slope > 0.0 ? Eigen::Vector3d(p - field.value / slope * field.gradient) : p;
    return result;
  }

  MannequinModel model_;
  std::string description_;
};

std::string pose_text(const Pose& pose) {
  std::ostringstream out;
  for (const auto& [joint, degrees] : pose.degrees)
    out << (out.tellp() > 0 ? "," : "") << joint << ":" << degrees;
  return out.str();
}

} // namespace

std::unique_ptr<Shape> make_smooth_mannequin_shape() {
  return std::make_unique<SmoothMannequin>(MannequinModel(), "mannequin (smooth implicit surface)");
}

std::unique_ptr<Shape> make_posed_mannequin_shape(const MannequinModel& model, const Pose& pose) {
  std::string description = model.is_default() && pose.neutral()
                                ? "mannequin (smooth implicit surface)"
                                : "mannequin (smooth implicit surface, sized";
  if (!pose.neutral()) description += ", posed " + pose_text(pose);
  if (!(model.is_default() && pose.neutral())) description += ")";
  return std::make_unique<SmoothMannequin>(model.posed(pose), description);
}

std::unique_ptr<Shape> make_posed_mannequin_shape(const Measurements& measurements,
                                                  const Pose& pose) {
  return make_posed_mannequin_shape(MannequinModel(measurements), pose);
}

void PoseHistory::add(double time, const Pose& pose) {
  if (!keyframes_.empty() && !(time > keyframes_.back().first)) {
    std::ostringstream message;
    message << "pose history: keyframe times must increase: " << time << " follows "
            << keyframes_.back().first;
    throw InputError(message.str());
  }
  check_pose(pose);
  keyframes_.emplace_back(time, pose);
}

Pose PoseHistory::at(double time) const {
  if (keyframes_.empty()) return {};
  if (time <= keyframes_.front().first) return keyframes_.front().second;
  if (time >= keyframes_.back().first) return keyframes_.back().second;
  std::size_t k = 1;
  while (keyframes_[k].first < time)
    ++k;
  const auto& [t0, p0] = keyframes_[k - 1];
  const auto& [t1, p1] = keyframes_[k];
  const double w = (time - t0) / (t1 - t0);
  std::set<std::string> joints;
  for (const Pose* pose : {&p0, &p1})
    for (const auto& [joint, degrees] : pose->degrees)
      joints.insert(joint);
  Pose pose;
  for (const std::string& joint : joints)
    pose.degrees[joint] = (1.0 - w) * p0.angle(joint) + w * p1.angle(joint);
  return pose;
}

PoseHistory parse_pose_history(const std::string& text) {
  PoseHistory history;
  std::istringstream keyframes(text);
  std::string keyframe;
  while (std::getline(keyframes, keyframe, ';')) {
    const auto colon = keyframe.find(':');
    double time = 0.0;
    std::size_t used = 0;
    try {
      if (colon != std::string::npos) time = std::stod(keyframe.substr(0, colon), &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (colon == std::string::npos || used != colon || !std::isfinite(time))
      throw InputError("pose history: '" + keyframe + "' is not TIME:POSE (e.g. 60:knee_l:90)");
    const std::string pose = keyframe.substr(colon + 1);
    history.add(time, pose.empty() ? Pose{} : parse_pose(pose));
  }
  if (history.empty()) throw InputError("pose history: no keyframes in '" + text + "'");
  return history;
}

} // namespace sartor::contact
