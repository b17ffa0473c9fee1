#pragma once
// Sartor's built-in mannequin: a standing human body, about 1.75 m tall, made
// by Sartor itself (no external model data). It is the zero level set of a
// smooth union of ellipsoids and tapered capsules (head, neck, chest, waist,
// hips, arms, hands, legs, feet), polygonised by marching tetrahedra on a
// regular grid and relaxed onto the surface, which gives a closed,
// 2-manifold, outward-oriented triangle mesh. The result is deterministic.
//
// Frame: metres, z up, feet on z = 0, the body faces -y (its front is at
// -y), its left side at +x; arms 45 degrees away from the torso (an A-pose).
//
// The skeleton names the segments that garment placement wraps cylinders
// around: pelvis, torso, neck, head, clavicle_l/r, upper_arm_l/r,
// forearm_l/r, hand_l/r, hip_l/r, thigh_l/r, shin_l/r, foot_l/r. Every joint
// lies inside the body. docs/bodies.md has the dimensions.

#include "contact/body_obj.hpp"

#include <Eigen/Core>

#include <map>
#include <memory>
#include <string>
#include <vector>

namespace sartor {

struct Bone {
  std::string name;
  std::string parent;    // empty for the root (pelvis)
  Eigen::Vector3d start; // joint nearer the root, m
  Eigen::Vector3d end;   // m
  // A cone around start-end that roughly encloses the segment's flesh: for
  // limbs, the radii of the tapered capsule the limb is made of; for the
  // trunk, the larger half-width of its cross-section. m.
  double start_radius;
  double end_radius;
};

struct Mannequin {
  BodyMesh mesh;
  std::vector<Bone> skeleton; // parents before children
  // The bone called `name`; throws InputError naming the bones when there is none.
  const Bone& bone(const std::string& name) const;
};

// Generated on the first call (a fraction of a second), then shared.
const Mannequin& default_mannequin();

// A fresh generation, bit for bit the same as default_mannequin().
Mannequin generate_mannequin();

// The implicit function the mannequin is the zero level set of (< 0 inside,
// roughly a distance in m near the surface), in the mannequin's frame.
double mannequin_field(const Eigen::Vector3d& p);

// The same with its gradient and Hessian. The function is C1 everywhere but
// on the soles' rims (a smooth union of smooth pieces); the Hessian jumps
// where a fillet begins. On the surface |gradient| is 1 on a piece and less
// in the fillets between two; off it the ellipsoids' first-order distances
// steepen (contact/mannequin_surface.hpp).
struct MannequinFieldValue {
  double value;             // m
  Eigen::Vector3d gradient; // 1
  Eigen::Matrix3d hessian;  // 1/m
};
MannequinFieldValue mannequin_field_derivatives(const Eigen::Vector3d& p);

// --- sizing and posing (docs/bodies.md#sizing-and-posing) ---------------------

// Body measurements in mm under FreeSewing's names (camelCase: "waist",
// "seat", "shoulderToWrist", ...; plus "height").
using Measurements = std::map<std::string, double>;

// The measurements the mannequin is sized to, in a fixed order, with what
// each sets.
struct MeasurementUse {
  std::string name;
  std::string meaning;
  bool girth; // fitted by widening pieces; otherwise a height, length or level
};
const std::vector<MeasurementUse>& mannequin_measurements();
// The default mannequin's value of each of them, measured on it, mm.
const Measurements& default_measurements();
// Whether `name` is a measurement FreeSewing's models hold (or "height"):
// such names are accepted even where the mannequin does not use them.
bool is_known_measurement(const std::string& name);

// Joint angles in degrees, flexion in the sagittal plane: hip, shoulder,
// elbow and neck forward, knee backward. Joints: neck, shoulder_l/r,
// elbow_l/r, hip_l/r, knee_l/r; a joint not named is straight (0).
struct Pose {
  std::map<std::string, double> degrees;
  double angle(const std::string& joint) const;
  bool neutral() const;
};
// The joints with their allowed range of angles, degrees.
struct JointRange {
  std::string name;
  double least;
  double most;
};
const std::vector<JointRange>& pose_joints();
// "knee_l:90,hip_l:45"; throws InputError naming the joint or the word.
Pose parse_pose(const std::string& text);
// Throws InputError for an unknown joint or an angle out of its range.
void check_pose(const Pose& pose);

// A bone's rigid motion from the unposed (sized) body to a pose: a point of
// the bone's flesh at x in the unposed body is at rotation x + shift.
struct BoneMotion {
  std::string bone; // skeleton() name
  Eigen::Matrix3d rotation;
  Eigen::Vector3d shift;
};

// The mannequin sized to a measurement set and posed. Sizing fits the
// pieces' radii until each girth, measured on the body, is within 0.2 % of
// the request (a few tenths of a second); posing turns the limbs about their
// joints (microseconds). The default-constructed model is the built-in
// mannequin, bit for bit, and so is a model asked for its default values.
class MannequinModel {
public:
  MannequinModel();
  // Measurements not given keep default_measurements(); unknown or
  // implausible values and impossible poses throw InputError naming them.
  explicit MannequinModel(const Measurements& requested, const Pose& pose = {});
  // The same sizing in another pose.
  MannequinModel posed(const Pose& pose) const;

  double field(const Eigen::Vector3d& p) const;
  // The value and gradient alone (the Hessian zero): cheaper by about half;
  // field(p) computes the value alone.
  MannequinFieldValue field_gradient(const Eigen::Vector3d& p) const;
  MannequinFieldValue field_derivatives(const Eigen::Vector3d& p) const;
  // A bound on |gradient| outside the body (8 for the default's hands).
  double slope_bound() const;
  // Polygonised as default_mannequin() is (about 0.4 s).
  Mannequin generate() const;
  std::vector<Bone> skeleton() const;
  // Per bone of skeleton(), in its order: its motion from the unposed body
  // (the identity for bones no joint moves).
  std::vector<BoneMotion> bone_motions() const;
  bool is_default() const;
  const Pose& pose() const;
  // The measurements it was sized to (defaults filled in), mm.
  const Measurements& requested() const;
  // Those measurements taken on the unposed body as sizing takes them, mm.
  const Measurements& achieved() const;

  struct Parts; // the pieces of the body (src/contact/mannequin.cpp)

private:
  std::shared_ptr<const Parts> sized_;
  std::shared_ptr<const Parts> posed_;
  Pose pose_;
  Measurements requested_;
  Measurements achieved_;
};

} // namespace sartor
