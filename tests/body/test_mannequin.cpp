// The built-in mannequin: a closed, 2-manifold, outward body of human size,
// arms clear of the torso, joints inside, deterministic.

#include "common/error.hpp"
#include "contact/mesh_shape.hpp"
#include "mesh/mannequin.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cstdint>
#include <cstring>

namespace {

const sartor::Mannequin& mannequin() {
  return sartor::default_mannequin();
}

const sartor::contact::Shape& mannequin_shape() {
  static const auto shape = sartor::contact::make_mannequin_shape();
  return *shape;
}

std::uint64_t fingerprint(const sartor::Mannequin& m) {
  std::uint64_t hash = 1469598103934665603ull; // FNV-1a
  const auto mix = [&hash](const void* data, std::size_t size) {
    const auto* bytes = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < size; ++i)
      hash = (hash ^ bytes[i]) * 1099511628211ull;
  };
  for (const auto& v : m.mesh.vertices)
    mix(v.data(), 3 * sizeof(double));
  for (const auto& f : m.mesh.faces)
    mix(f.data(), sizeof f);
  for (const auto& b : m.skeleton) {
    mix(b.name.data(), b.name.size());
    mix(b.start.data(), 3 * sizeof(double));
    mix(b.end.data(), 3 * sizeof(double));
  }
  return hash;
}

TEST(Mannequin, IsAClosedOutwardSurfaceOfOnePieceWithoutHandles) {
  EXPECT_NO_THROW(sartor::check_body_mesh(mannequin().mesh, "mannequin"));
  const sartor::BodyMeasures m = sartor::measure_body(mannequin().mesh);
  EXPECT_EQ(m.components, 1u);
  EXPECT_EQ(m.euler_characteristic, 2); // a sphere's: no handles, no tunnels
  EXPECT_GT(m.volume, 0.05);            // m^3: a human of about 60-80 kg
  EXPECT_LT(m.volume, 0.09);
  EXPECT_GE(mannequin().mesh.faces.size(), 10000u);
  EXPECT_LE(mannequin().mesh.faces.size(), 40000u);
  EXPECT_GT(m.smallest_angle_deg, 1.0);
}

TEST(Mannequin, StandsOnTheFloorAtHumanHeightFacingMinusY) {
  const sartor::BodyMeasures m = sartor::measure_body(mannequin().mesh);
  EXPECT_NEAR(m.lower.z(), 0.0, 1e-9);
  EXPECT_GE(m.upper.z(), 1.70);
  EXPECT_LE(m.upper.z(), 1.80);
  EXPECT_NEAR(m.lower.x(), -m.upper.x(), 1e-3); // left-right symmetric
  // Toes and nose point to -y.
  for (const char* foot : {"foot_l", "foot_r"}) {
    const sartor::Bone& bone = mannequin().bone(foot);
    EXPECT_LT(bone.end.y(), bone.start.y() - 0.1) << foot;
  }
  double front = 0.0;
  double back = 0.0;
  for (const auto& v : mannequin().mesh.vertices) {
    if (v.z() < 1.55 || v.z() > 1.70) continue;
    front = std::min(front, v.y());
    back = std::max(back, v.y());
  }
  EXPECT_GT(-front, back + 0.01);
}

TEST(Mannequin, EveryTriangleFacesOutward) {
  const auto& mesh = mannequin().mesh;
  const sartor::contact::Shape& shape = mannequin_shape();
  for (std::size_t f = 0; f < mesh.faces.size(); ++f) {
    const Eigen::Vector3d& a = mesh.vertices[static_cast<std::size_t>(mesh.faces[f][0])];
    const Eigen::Vector3d& b = mesh.vertices[static_cast<std::size_t>(mesh.faces[f][1])];
    const Eigen::Vector3d& c = mesh.vertices[static_cast<std::size_t>(mesh.faces[f][2])];
    const Eigen::Vector3d centre = (a + b + c) / 3.0;
    const Eigen::Vector3d normal = (b - a).cross(c - a).normalized();
    ASSERT_GT(shape.query(centre + 1e-5 * normal).distance, 0.0) << "face " << f;
    ASSERT_LT(shape.query(centre - 1e-5 * normal).distance, 0.0) << "face " << f;
  }
}

TEST(Mannequin, ArmsHangClearOfTheTorso) {
  for (const char* side : {"_l", "_r"}) {
    const sartor::Bone& upper_arm = mannequin().bone(std::string("upper_arm") + side);
    const double height = 0.5 * (upper_arm.start.z() + upper_arm.end.z());
    const double outward = upper_arm.end.x() > 0.0 ? 1.0 : -1.0;
    // Across the slab at mid upper-arm height, on this side: the widest gap
    // between neighbouring vertices' |x| is the space between torso and arm.
    std::vector<double> x;
    for (const auto& v : mannequin().mesh.vertices)
      if (std::abs(v.z() - height) < 0.01 && outward * v.x() > 0.0) x.push_back(outward * v.x());
    std::sort(x.begin(), x.end());
    double gap = 0.0;
    double gap_at = 0.0;
    for (std::size_t i = 1; i < x.size(); ++i) {
      if (x[i] - x[i - 1] > gap) {
        gap = x[i] - x[i - 1];
        gap_at = x[i];
      }
    }
    EXPECT_GT(gap, 0.03) << side;                           // m between torso and arm
    EXPECT_LT(gap_at, outward * upper_arm.end.x()) << side; // the gap is inside the arm
  }
}

TEST(Mannequin, SkeletonHasTheNamedBonesWithJointsInsideTheBody) {
  for (const char* name : {"pelvis", "torso", "neck", "head", "upper_arm_l", "upper_arm_r",
                           "forearm_l", "forearm_r", "thigh_l", "thigh_r", "shin_l", "shin_r"})
    EXPECT_NO_THROW(mannequin().bone(name)) << name;
  EXPECT_THROW(mannequin().bone("tail"), sartor::InputError);
  const sartor::contact::Shape& shape = mannequin_shape();
  std::vector<std::string> seen;
  for (const sartor::Bone& bone : mannequin().skeleton) {
    EXPECT_TRUE(bone.parent.empty() ||
                std::find(seen.begin(), seen.end(), bone.parent) != seen.end())
        << bone.name << ": parent " << bone.parent << " is not listed before it";
    seen.push_back(bone.name);
    EXPECT_LT(shape.query(bone.start).distance, -0.005) << bone.name;
    EXPECT_LT(shape.query(bone.end).distance, -0.005) << bone.name;
    EXPECT_GT(bone.start_radius, 0.0);
    EXPECT_GT(bone.end_radius, 0.0);
  }
  // For limbs the radius profile is the flesh around the bone: at mid-bone
  // the surface lies about that far from the axis.
  for (const char* limb : {"upper_arm_l", "forearm_r", "thigh_l", "shin_r"}) {
    const sartor::Bone& bone = mannequin().bone(limb);
    const double depth = -shape.query(0.5 * (bone.start + bone.end)).distance;
    EXPECT_NEAR(depth, 0.5 * (bone.start_radius + bone.end_radius), 0.01) << limb;
  }
}

TEST(Mannequin, GenerationIsDeterministic) {
  EXPECT_EQ(fingerprint(sartor::generate_mannequin()), fingerprint(mannequin()));
}

} // namespace
