// The built-in mannequin: a closed, 2-manifold, outward body of human size,
// arms clear of the torso, joints inside, deterministic.

#include "common/error.hpp"
#include "contact/mannequin.hpp"
#include "contact/mannequin_surface.hpp"
#include "contact/mesh_shape.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <random>

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

// Smoothing folded the polygonised hands over one another; a sized and a
// posed mannequin are polygonised and checked as the default is, crossing
// faces included.
TEST(Mannequin, SizedAndPosedPolygonisationsAreClosedAndDoNotCrossThemselves) {
  const sartor::MannequinModel sized({{"height", 1900.0}, {"waist", 900.0}});
  const sartor::MannequinModel posed = sartor::MannequinModel().posed(
      sartor::contact::parse_pose_history("0:knee_l:60,elbow_r:90").at(0.0));
  for (const sartor::MannequinModel* model : {&sized, &posed}) {
    const sartor::Mannequin generated = model->generate();
    EXPECT_NO_THROW(sartor::check_body_mesh(generated.mesh, "mannequin"));
    EXPECT_GT(sartor::measure_body(generated.mesh).smallest_angle_deg, 1.0);
  }
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

// Points near the surface all over the body: mesh vertices pushed off along
// their normals by a deterministic random distance in [below, above].
std::vector<Eigen::Vector3d> points_near_the_surface(std::size_t count, double below = -0.01,
                                                     double above = 0.03) {
  const auto& mesh = mannequin().mesh;
  std::mt19937 random(7);
  std::uniform_int_distribution<std::size_t> pick(0, mesh.vertices.size() - 1);
  std::uniform_real_distribution<double> offset(below, above);
  std::vector<Eigen::Vector3d> points;
  for (std::size_t i = 0; i < count; ++i) {
    const Eigen::Vector3d& v = mesh.vertices[pick(random)];
    points.push_back(v + offset(random) * sartor::mannequin_field_derivatives(v).gradient);
  }
  return points;
}

TEST(SmoothMannequin, GradientAndHessianMatchFiniteDifferencesOfTheField) {
  const double step = 1e-6;
  for (const Eigen::Vector3d& p : points_near_the_surface(2000)) {
    const sartor::MannequinFieldValue at = sartor::mannequin_field_derivatives(p);
    for (int d = 0; d < 3; ++d) {
      const Eigen::Vector3d e = step * Eigen::Vector3d::Unit(d);
      const sartor::MannequinFieldValue plus = sartor::mannequin_field_derivatives(p + e);
      const sartor::MannequinFieldValue minus = sartor::mannequin_field_derivatives(p - e);
      ASSERT_NEAR((plus.value - minus.value) / (2 * step), at.gradient[d], 1e-6)
          << "at " << p.transpose() << ", direction " << d;
      // Where a fillet begins between the two points the Hessian jumps.
      const bool fillet_edge =
          (plus.hessian - minus.hessian).norm() > 1e-3 * (1 + at.hessian.norm());
      if (fillet_edge) continue;
      const Eigen::Vector3d column = (plus.gradient - minus.gradient) / (2 * step);
      ASSERT_LT((column - at.hessian.col(d)).norm(), 1e-5 * (1.0 + at.hessian.norm()))
          << "at " << p.transpose() << ", direction " << d;
    }
    ASSERT_LT((at.hessian - at.hessian.transpose()).norm(), 1e-9 * (1.0 + at.hessian.norm()));
  }
}

// Contact skips a vertex's query while it has moved less than its last
// distance beyond the offset over the shape's slope bound
// (fem/cloth_contact.cpp), which is sound only if the bound holds.
TEST(SmoothMannequin, FunctionFallsNoFasterThanItsSlopeBound) {
  const auto shape = sartor::contact::make_smooth_mannequin_shape();
  double outside = 0.0;
  std::mt19937 random(11);
  std::uniform_real_distribution<double> x(-3.0, 3.0), y(-3.0, 3.0), z(-2.0, 4.0);
  for (int i = 0; i < 200000; ++i) {
    const sartor::MannequinFieldValue f =
        sartor::mannequin_field_derivatives(Eigen::Vector3d(x(random), y(random), z(random)));
    if (f.value > 0.0) outside = std::max(outside, f.gradient.norm());
  }
  EXPECT_LT(outside, shape->slope_bound());
}

TEST(SmoothMannequin, SurfaceIsTheMeshsSurfaceAndQueriesAreConsistent) {
  const auto shape = sartor::contact::make_smooth_mannequin_shape();
  for (const auto& v : mannequin().mesh.vertices)
    ASSERT_NEAR(shape->query(v).distance, 0.0, 1e-9) << v.transpose();
  // Within contact's range of the surface.
  for (const Eigen::Vector3d& p : points_near_the_surface(2000, -0.002, 0.002)) {
    const sartor::contact::SurfaceQuery q = shape->query(p);
    const sartor::contact::SurfaceQuery mesh_q = mannequin_shape().query(p);
    // The mesh's chords lie within about 1 mm of the smooth surface.
    EXPECT_NEAR(q.distance, mesh_q.distance, 1.5e-3) << p.transpose();
    // One Newton step: a tenth of the contact offset's millimetre at most.
    EXPECT_NEAR(shape->query(q.closest).distance, 0.0, 1e-4) << p.transpose();
    // The same side (the 2 cm grid polygonises the 4 cm thin hands coarsely).
    EXPECT_GT(q.normal.dot(mesh_q.normal), 0.0) << p.transpose();
  }
}

// Contact asks for the distance alone (energies, step bounds) or with the
// normal (forces): those are the full query's, computed without the
// curvature, and a posed, sized body answers the same way.
TEST(SmoothMannequin, PartialQueriesAreTheFullQuerysFields) {
  using sartor::contact::QueryNeeds;
  const auto standing = sartor::contact::make_smooth_mannequin_shape();
  const auto posed = sartor::contact::make_posed_mannequin_shape(
      sartor::MannequinModel(), sartor::contact::parse_pose_history("0:knee_l:60").at(0.0));
  for (const auto* shape : {standing.get(), posed.get()}) {
    for (const Eigen::Vector3d& p : points_near_the_surface(500, -0.01, 0.05)) {
      const sartor::contact::SurfaceQuery full = shape->query(p);
      const sartor::contact::SurfaceQuery normal = shape->partial_query(p, QueryNeeds::normal);
      const double distance = shape->partial_query(p, QueryNeeds::distance).distance;
      EXPECT_NEAR(distance, full.distance, 1e-12) << p.transpose();
      EXPECT_NEAR(normal.distance, full.distance, 1e-12) << p.transpose();
      EXPECT_LT((normal.normal - full.normal).norm(), 1e-12) << p.transpose();
      EXPECT_LT((normal.closest - full.closest).norm(), 1e-12) << p.transpose();
      EXPECT_TRUE(normal.hessian.isZero(0.0));
    }
  }
}

} // namespace
