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

#include "mesh/body_obj.hpp"

#include <Eigen/Core>

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

} // namespace sartor
