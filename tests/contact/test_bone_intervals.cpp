// The thesis' spatial index for penetration detection (ch. 4, Alg. 1):
// against a tessellated capsule its verdicts and depths match the capsule's
// closed form away from the chords' sagitta; on the mannequin exported as a
// mesh its verdicts match the mesh's own signed distance (CGAL's AABB tree,
// contact/mesh_shape.hpp) wherever it gives one.

#include "contact/bone_intervals.hpp"
#include "contact/mannequin.hpp"
#include "contact/mesh_shape.hpp"
#include "tests/contact/capsule_mesh.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

namespace sartor {
namespace {

using contact::BoneIntervals;
using Eigen::Vector3d;

constexpr double radius = 0.05, length = 0.3;

// The capsule's signed distance and the point's distance from the axis.
double capsule_distance(const Vector3d& p) {
  const double z = std::clamp(p.z(), 0.0, length);
  return (p - Vector3d(0, 0, z)).norm() - radius;
}

TEST(BoneIntervals, TellTheInsideOfATessellatedCapsuleByItsAxis) {
  const BodyMesh mesh = test::capsule_mesh(radius, length);
  check_body_mesh(mesh, "capsule");
  const BoneIntervals index(
      mesh, {{"axis", "", Vector3d::Zero(), Vector3d(0, 0, length), radius, radius}}, 0.02);
  EXPECT_EQ(index.bones(), 1u);
  EXPECT_EQ(index.intervals(), 15u);
  EXPECT_EQ(index.intervals_outside(), 0u);
  // The chords' sagitta: r (1 - cos(pi / 32)) around, r (1 - cos(pi / 32)) over the caps' rings.
  const double band = 2.0 * radius * (1.0 - std::cos(M_PI / 16.0));
  std::mt19937 random(3);
  std::uniform_real_distribution<double> across(-2 * radius, 2 * radius),
      along(-2 * radius, length + 2 * radius);
  int judged = 0, unknown = 0;
  for (int i = 0; i < 20000; ++i) {
    const Vector3d p(across(random), across(random), along(random));
    const double exact = capsule_distance(p);
    if (std::abs(exact) < band) continue;
    const BoneIntervals::Detection d = index.detect(p);
    if (d.side == BoneIntervals::Side::unknown) {
      ++unknown;
      continue;
    }
    ++judged;
    ASSERT_EQ(d.side == BoneIntervals::Side::inside, exact < 0.0) << p.transpose();
    // From the axis the ray is the radius on the cylinder, a ray through the
    // cap's centre on the caps: the depth is the distance.
    ASSERT_NEAR(d.depth, -exact, band) << p.transpose();
  }
  EXPECT_GT(judged, 19000); // measured 19,523, none unknown
  EXPECT_LT(unknown, judged / 100);
}

TEST(BoneIntervals, FindTheMannequinsInsideAsItsMeshDoes) {
  const Mannequin& mannequin = default_mannequin();
  const BoneIntervals index(mannequin.mesh, mannequin.skeleton, 0.01);
  EXPECT_EQ(index.intervals_outside(), 0u);           // every bone lies inside
  const auto exact = contact::make_mannequin_shape(); // the same mesh, CGAL's distance
  // Points from 6 cm inside to 3 cm outside the surface all over the body.
  std::mt19937 random(7);
  std::uniform_int_distribution<std::size_t> pick(0, mannequin.mesh.vertices.size() - 1);
  std::uniform_real_distribution<double> offset(-0.06, 0.03);
  int inside = 0, outside = 0, unknown = 0;
  for (int i = 0; i < 20000; ++i) {
    const Vector3d& v = mannequin.mesh.vertices[pick(random)];
    const Vector3d p = v + offset(random) * mannequin_field_derivatives(v).gradient;
    const double distance = exact->query(p).distance;
    const BoneIntervals::Detection d = index.detect(p);
    if (d.side == BoneIntervals::Side::unknown) {
      ++unknown;
      continue;
    }
    (d.side == BoneIntervals::Side::inside ? inside : outside)++;
    // The index's distance is along its ray, never shorter than the nearest.
    if (d.side == BoneIntervals::Side::inside)
      ASSERT_LT(distance, 1e-9) << p.transpose();
    else
      ASSERT_GT(distance, -1e-3) << p.transpose() << " (the thesis' approximation)";
    ASSERT_GE(std::abs(d.depth), std::abs(distance) - 1e-9) << p.transpose();
  }
  EXPECT_GT(inside, 10000); // measured 11,835

  EXPECT_GT(outside, 6000); // 6,844
  EXPECT_LT(unknown, 2000); // 1,321
}

} // namespace
} // namespace sartor
