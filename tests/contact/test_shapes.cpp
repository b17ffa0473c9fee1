// Analytic shapes and body motions: the distance's gradient is the normal and
// the normal's Jacobian is the Hessian (central differences at random points
// off the medial axes), closest points lie on the surface, and known values.

#include "common/error.hpp"
#include "contact/analytic_shapes.hpp"
#include "contact/body.hpp"
#include "contact/body_spec.hpp"
#include "tests/element/finite_difference.hpp"

#include <gtest/gtest.h>

#include <functional>
#include <memory>
#include <random>

namespace sartor::contact {
namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;
using element::testing::numeric_gradient;
using element::testing::numeric_jacobian;

using Query = std::function<SurfaceQuery(const Vector3d&)>;

// Checks the derivatives of `query` at `count` random points of the cube
// [-extent, extent]^3 around `center`.
void check_derivatives(const Query& query, const Vector3d& center, double extent, int count) {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> uniform(-extent, extent);
  const double step = 1e-6;
  for (int i = 0; i < count; ++i) {
    const Vector3d p = center + Vector3d(uniform(random), uniform(random), uniform(random));
    const SurfaceQuery q = query(p);
    SCOPED_TRACE("p = " + std::to_string(p.x()) + "," + std::to_string(p.y()) + "," +
                 std::to_string(p.z()));
    EXPECT_NEAR(q.normal.norm(), 1.0, 1e-12);
    EXPECT_LT((q.closest - (p - q.distance * q.normal)).norm(), 1e-12);
    EXPECT_NEAR(query(q.closest).distance, 0.0, 1e-12);
    EXPECT_LT((q.hessian - q.hessian.transpose()).norm(), 1e-12);
    const Vector3d gradient =
        numeric_gradient<3>([&](const Vector3d& x) { return query(x).distance; }, p, step);
    EXPECT_LT((gradient - q.normal).norm(), 1e-7);
    const Matrix3d hessian =
        numeric_jacobian<3, 3>([&](const Vector3d& x) { return query(x).normal; }, p, step);
    EXPECT_LT((hessian - q.hessian).norm(), 1e-5 * std::max(1.0, q.hessian.norm()));
  }
}

Query of(const Shape& shape) {
  return [&shape](const Vector3d& p) { return shape.query(p); };
}

TEST(Shapes, PlaneDerivativesAndValues) {
  const Plane plane(Vector3d(0, 0, 1), Vector3d(0, 1, 1));
  check_derivatives(of(plane), Vector3d::Zero(), 2.0, 50);
  EXPECT_NEAR(plane.query(Vector3d(5, 1, 2)).distance, std::sqrt(2.0), 1e-14);
  EXPECT_TRUE(plane.query(Vector3d(5, 1, 2)).hessian.isZero());
}

TEST(Shapes, SphereDerivativesAndValues) {
  const Sphere sphere(Vector3d(0.1, -0.2, 0.3), 0.5);
  check_derivatives(of(sphere), Vector3d(0.1, -0.2, 0.3), 1.0, 200);
  const SurfaceQuery q = sphere.query(Vector3d(0.1, -0.2, 1.3));
  EXPECT_NEAR(q.distance, 0.5, 1e-14);
  EXPECT_LT((q.hessian - Vector3d(1, 1, 0).asDiagonal().toDenseMatrix()).norm(), 1e-14);
  EXPECT_NEAR(sphere.query(Vector3d(0.1, -0.2, 0.4)).distance, -0.4, 1e-14);
}

TEST(Shapes, CapsuleDerivativesAndValues) {
  const Capsule capsule(Vector3d(-0.5, 0, 0), Vector3d(0.5, 0.2, 0.1), 0.2);
  check_derivatives(of(capsule), Vector3d::Zero(), 1.2, 300);
  const Capsule along_x(Vector3d(-1, 0, 0), Vector3d(1, 0, 0), 0.5);
  const SurfaceQuery side = along_x.query(Vector3d(0.3, 0, 1.5));
  EXPECT_NEAR(side.distance, 1.0, 1e-14);
  EXPECT_LT((side.hessian - Vector3d(0, 1.0 / 1.5, 0).asDiagonal().toDenseMatrix()).norm(), 1e-14);
  EXPECT_NEAR(along_x.query(Vector3d(3, 0, 0)).distance, 1.5, 1e-14);
}

TEST(Shapes, CylinderDerivativesAndValues) {
  const Cylinder cylinder(Vector3d(0, 0, 0.1), Vector3d(1, 1, 2), 0.4, 0.6);
  check_derivatives(of(cylinder), Vector3d(0, 0, 0.1), 1.0, 400);
  const Cylinder upright(Vector3d::Zero(), Vector3d::UnitZ(), 1.0, 2.0);
  const SurfaceQuery side = upright.query(Vector3d(2, 0, 0.5));
  EXPECT_NEAR(side.distance, 1.0, 1e-14);
  EXPECT_LT((side.hessian - Vector3d(0, 0.5, 0).asDiagonal().toDenseMatrix()).norm(), 1e-14);
  EXPECT_NEAR(upright.query(Vector3d(0.2, 0.3, 3)).distance, 2.0, 1e-14);
  EXPECT_NEAR(upright.query(Vector3d(2, 0, 2)).distance, std::sqrt(2.0), 1e-14); // rim
  EXPECT_NEAR(upright.query(Vector3d(0.1, 0, 0.8)).distance, -0.2, 1e-14);       // inside
}

TEST(Shapes, BoxDerivativesAndValues) {
  const Box sharp(Vector3d(0.1, 0, 0), Vector3d(1.0, 0.6, 0.4));
  check_derivatives(of(sharp), Vector3d(0.1, 0, 0), 1.0, 400);
  const Box rounded(Vector3d::Zero(), Vector3d(1.0, 0.6, 0.4), 0.1);
  check_derivatives(of(rounded), Vector3d::Zero(), 1.0, 400);
  const Box cube(Vector3d::Zero(), Vector3d(2, 2, 2));
  EXPECT_NEAR(cube.query(Vector3d(0.2, 3, 0.1)).distance, 2.0, 1e-14); // face
  EXPECT_NEAR(cube.query(Vector3d(2, 2, 0.5)).distance, std::sqrt(2.0), 1e-14);
  EXPECT_NEAR(cube.query(Vector3d(2, 2, 2)).distance, std::sqrt(3.0), 1e-14);
  EXPECT_NEAR(cube.query(Vector3d(0.5, 0.2, 0)).distance, -0.5, 1e-14);
  // Rounding keeps the outer extents: a face is where it was.
  EXPECT_NEAR(rounded.query(Vector3d(0, 0, 1)).distance, 0.8, 1e-14);
}

TEST(Shapes, BadParametersAreInputErrors) {
  EXPECT_THROW(Sphere(Vector3d::Zero(), -1.0), InputError);
  EXPECT_THROW(Plane(Vector3d::Zero(), Vector3d::Zero()), InputError);
  EXPECT_THROW(Box(Vector3d::Zero(), Vector3d(1, 1, 1), 0.6), InputError);
  EXPECT_THROW(Cylinder(Vector3d::Zero(), Vector3d::UnitZ(), 1.0, 0.0), InputError);
}

TEST(Bodies, MotionsInterpolateAndHold) {
  PiecewiseLinear<double> scale(1.0);
  EXPECT_EQ(scale.at(3.0), 1.0);
  scale.add(1.0, 1.0);
  scale.add(3.0, 1.5);
  EXPECT_EQ(scale.at(0.0), 1.0);
  EXPECT_NEAR(scale.at(2.0), 1.25, 1e-15);
  EXPECT_EQ(scale.at(9.0), 1.5);
  EXPECT_THROW(scale.add(3.0, 2.0), InputError);
}

// A moved, turned and scaled body: world distances, normals and Hessians are
// the derivatives of each other, and known values hold.
TEST(Bodies, WorldQueryOfAMovingBody) {
  const Vector3d center(0.2, 0.1, 0.0);
  Body body("drum", std::make_shared<Cylinder>(center, Vector3d(0, 1, 0), 0.3, 0.8), center);
  body.motion.translation.add(0.0, Vector3d::Zero());
  body.motion.translation.add(2.0, Vector3d(0.4, 0.0, -0.2));
  body.motion.rotation_axis = Vector3d(1, 0, 1).normalized();
  body.motion.angle.add(0.0, 0.0);
  body.motion.angle.add(2.0, 1.0);
  body.motion.scale.add(0.0, 1.0);
  body.motion.scale.add(2.0, 1.5);
  const double t = 1.3;
  check_derivatives([&](const Vector3d& x) { return body.query(x, t); },
                    center + Vector3d(0.26, 0, -0.13), 1.0, 300);
  const Vector3d p(0.5, -0.2, 0.4);
  EXPECT_LT((body.to_body(body.to_world(p, t), t) - p).norm(), 1e-14);
  // Scaling by 1.5 about the axis: a point on the grown mantle.
  Body grown("drum", std::make_shared<Cylinder>(center, Vector3d(0, 1, 0), 0.3, 0.8), center);
  grown.motion.scale.add(0.0, 1.0);
  grown.motion.scale.add(10.0, 1.5);
  EXPECT_NEAR(grown.query(center + Vector3d(0.45, 0, 0), 10.0).distance, 0.0, 1e-14);
  EXPECT_NEAR(grown.query(center + Vector3d(0.45, 0, 0), 0.0).distance, 0.15, 1e-14);
  EXPECT_NEAR(grown.query(center + Vector3d(0.9, 0, 0), 10.0).hessian(2, 2), 1.0 / 0.9, 1e-13);
}

TEST(Bodies, BonesAreTheAxesOrTheSkeleton) {
  const std::vector<Bone> capsule = body_bones("capsule a=0,0,1.2 b=0.6,0,1.2 radius=0.05", "test");
  ASSERT_EQ(capsule.size(), 1u);
  EXPECT_EQ(capsule[0].start, Vector3d(0.0, 0.0, 1.2));
  EXPECT_EQ(capsule[0].end, Vector3d(0.6, 0.0, 1.2));
  // A cylinder's axis runs from cap to cap: centre -/+ height/2 along it.
  const std::vector<Bone> cylinder =
      body_bones("cylinder center=1,0,0 direction=0,0,2 radius=0.1 height=0.4", "test");
  ASSERT_EQ(cylinder.size(), 1u);
  EXPECT_NEAR((cylinder[0].start - Vector3d(1.0, 0.0, -0.2)).norm(), 0.0, 1e-15);
  EXPECT_NEAR((cylinder[0].end - Vector3d(1.0, 0.0, 0.2)).norm(), 0.0, 1e-15);
  EXPECT_TRUE(body_bones("sphere center=0,0,0 radius=0.3", "test").empty());
  // The mannequin's skeleton: its 20 bones, the knee moved by the pose.
  const std::vector<Bone> standing = body_bones("mannequin", "test");
  const std::vector<Bone> kneeling = body_bones("mannequin pose=knee_l:90", "test");
  ASSERT_EQ(standing.size(), 20u);
  ASSERT_EQ(kneeling.size(), 20u);
  for (std::size_t k = 0; k < standing.size(); ++k) {
    if (standing[k].name != "shin_l") continue;
    const Vector3d before = standing[k].end - standing[k].start;
    const Vector3d after = kneeling[k].end - kneeling[k].start;
    EXPECT_NEAR(std::acos(before.dot(after) / (before.norm() * after.norm())), M_PI / 2, 1e-9);
  }
  EXPECT_THROW(body_bones("capsule a=0,0,0 radius=0.1", "test"), InputError);
}

} // namespace
} // namespace sartor::contact
