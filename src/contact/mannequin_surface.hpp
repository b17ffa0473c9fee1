#pragma once
// The built-in mannequin for contact: its smooth implicit surface
// (contact/mannequin.hpp) instead of the triangles polygonised from it.
//
// The distance to a triangle mesh has a kink wherever the surface is
// concave: on the outside of a concave edge the nearest face switches from
// one side to the other across the bisecting plane, and the penalty's
// force jumps with it. A cloth vertex pressed into a crease (groin, armpit,
// between the shoulder blades) comes to rest on that plane, and Newton stalls
// there. The implicit function is C1 everywhere the cloth goes, so the
// penalty's force is continuous and its Jacobian exact (it jumps only where a
// fillet begins).
//
// The query returns the function's value as the distance (near the surface,
// the distance to the piece of the body there: exactly for the capsules, to
// first order for the ellipsoids; less in the fillets between pieces), its
// gradient as the normal (unit on the surface of a piece, shorter in the
// fillets) and its Hessian; the closest point is one Newton step from p onto
// the zero level set. Where the cloth rests (within millimetres of the
// surface) these agree with the exact distance to first order; the penalty
// is exact for the function it is given. Away from the surface the
// function is a rough distance only: its gradient reaches 2.8 within 3 cm
// of the hands and is bounded by slope_bound() everywhere outside the body.
//
// Sized and posed mannequins (docs/bodies.md#sizing-and-posing) answer the
// same way. A body that moves through poses over time (wear: standing,
// sitting, standing) is a PoseHistory: ask it for the pose at time t and
// make the shape of that pose from the sized model, which is cheap (the
// sizing, a fraction of a second, is done once):
//
//     const sartor::MannequinModel sized(read_measurement_file(path).measurements);
//     const PoseHistory history = parse_pose_history("0:;3600:hip_l:90,knee_l:90");
//     auto shape = make_posed_mannequin_shape(sized, history.at(t));

#include "contact/mannequin.hpp"
#include "contact/shape.hpp"

#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace sartor::contact {

// The built-in mannequin.
std::unique_ptr<Shape> make_smooth_mannequin_shape();

// `model` (sized, perhaps posed) in `pose` (replacing the model's own), and
// a sized one straight from measurements (sizing takes a few tenths of a
// second: keep the MannequinModel when several poses are wanted).
std::unique_ptr<Shape> make_posed_mannequin_shape(const MannequinModel& model, const Pose& pose);
std::unique_ptr<Shape> make_posed_mannequin_shape(const Measurements& measurements,
                                                  const Pose& pose);

// Keyframes (time s, pose), times increasing; at(t) interpolates every
// joint's angle linearly between keyframes (a joint a keyframe omits is
// straight there) and holds the first and last poses outside them.
class PoseHistory {
public:
  // Throws InputError when `time` does not exceed the last keyframe's.
  void add(double time, const Pose& pose);
  Pose at(double time) const;
  bool empty() const { return keyframes_.empty(); }
  const std::vector<std::pair<double, Pose>>& keyframes() const { return keyframes_; }

private:
  std::vector<std::pair<double, Pose>> keyframes_;
};

// "T:JOINT:DEG,JOINT:DEG;T:...;" (an empty pose after "T:" is standing),
// e.g. "0:;1800:hip_l:90,hip_r:90,knee_l:90,knee_r:90;9000:".
PoseHistory parse_pose_history(const std::string& text);

} // namespace sartor::contact
