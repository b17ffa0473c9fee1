#pragma once
// The mannequin moving through a pose history (standing, sitting, standing)
// as a TimedShape for the wear (docs/wear.md#a-body-that-moves): at time t
// its shape is the sized model posed as history.at(t), every joint's angle
// interpolated linearly between keyframes.
//
// Its knots are the keyframes and, within every keyframe interval where a
// joint turns, evenly spaced times at which no joint has turned by more than
// `largest_turn` degrees since the last: the wear's steps land on them, so
// that each static solve starts from a state the body has moved only a
// little from (a knee swung 90 degrees in one step would land the shin metres
// of cloth away from where it was, and the penalty would push the cloth out
// on the wrong side).
//
// Its reference frame (friction anchors) is the unposed body's, one copy
// (chart) per bone: a point is taken there by the bone whose flesh it is
// nearest in the pose of the moment (the distance to the bone's segment less
// its radius there), and that bone, named by the chart, carries it in every
// other pose, so that cloth sticking to a shin swings with it and an anchor
// near a bent joint does not change bones on the way.

#include "contact/mannequin.hpp"
#include "contact/mannequin_surface.hpp"
#include "solvers/wear.hpp"

#include <memory>
#include <string>
#include <vector>

namespace sartor {

class PosedMannequin : public TimedShape {
public:
  // `model`: the sized mannequin (its own pose is replaced by the history's).
  // Throws InputError for an empty history, a pose out of a joint's range or
  // a largest turn that is not positive.
  PosedMannequin(MannequinModel model, contact::PoseHistory history, double largest_turn);
  contact::SurfaceQuery query(const Eigen::Vector3d& p, double time) const override;
  contact::SurfaceQuery partial_query(const Eigen::Vector3d& p, double time,
                                      contact::QueryNeeds needs) const override;
  std::string describe() const override;
  double slope_bound() const override { return slope_bound_; }
  std::vector<double> knots() const override;
  Eigen::Vector3d to_reference(const Eigen::Vector3d& p, double time) const override;
  Eigen::Vector3d from_reference(const Eigen::Vector3d& q, double time) const override;
  Eigen::Vector3d direction_to_reference(const Eigen::Vector3d& p, const Eigen::Vector3d& d,
                                         double time) const override;
  Eigen::Vector3d direction_from_reference(const Eigen::Vector3d& q, const Eigen::Vector3d& d,
                                           double time) const override;
  const contact::PoseHistory& history() const { return history_; }

private:
  struct Posed {
    double time = 0.0;
    std::unique_ptr<contact::Shape> shape;
    std::vector<Bone> bones;
    std::vector<BoneMotion> motions; // per bone, from the unposed body
  };
  // The body at `time`, rebuilt when the time differs from the last asked
  // for (posing takes microseconds; the contact queries of one solve all
  // come at one time). Not for concurrent use.
  const Posed& posed_at(double time) const;

  MannequinModel model_;
  contact::PoseHistory history_;
  double largest_turn_;
  double slope_bound_ = 1.0;
  std::vector<Bone> unposed_bones_;
  mutable Posed posed_;
};

} // namespace sartor
