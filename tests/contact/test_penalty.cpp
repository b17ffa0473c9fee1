// Contact kernels: penalty and anchor spring derivatives by central
// differences, Coulomb's law of the anchor update, the stiffness rule, and the
// body specifications of case files.

#include "common/error.hpp"
#include "contact/analytic_shapes.hpp"
#include "contact/body_spec.hpp"
#include "contact/penalty.hpp"
#include "tests/element/finite_difference.hpp"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <limits>

#include <random>

namespace sartor::contact {
namespace {

using Eigen::Vector3d;
using element::Want;
using element::testing::numeric_gradient;
using element::testing::numeric_jacobian;

TEST(Penalty, DerivativesOnCurvedBodies) {
  const double k = 2.5e4, offset = 0.01;
  Body body("ball", std::make_shared<Sphere>(Vector3d(0, 0, 0), 0.3), Vector3d::Zero());
  body.motion.scale.add(0.0, 1.0);
  body.motion.scale.add(1.0, 1.2);
  body.motion.angle.add(0.0, 0.0);
  body.motion.angle.add(1.0, 0.5);
  Body edge("table", std::make_shared<Box>(Vector3d::Zero(), Vector3d(1, 1, 0.1), 0.02),
            Vector3d::Zero());
  std::mt19937 random(3);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  // The plain quadratic, and the smooth onset over 3 mm.
  for (double band : {0.0, 0.3 * offset}) {
    for (const Body* b : {&body, &edge}) {
      for (int i = 0; i < 50; ++i) {
        // Points in the contact layer: just outside, inside the offset, or slightly in.
        const Vector3d direction =
            Vector3d(uniform(random), uniform(random), uniform(random)).normalized();
        const Vector3d surface = b->query(2.0 * direction, 0.7).closest;
        const Vector3d x = surface + 0.012 * (uniform(random) + 0.2) * direction;
        const auto energy = [&](const Vector3d& y) {
          return penalty(k, offset, b->query(y, 0.7), Want::energy, band).energy;
        };
        const auto gradient = [&](const Vector3d& y) {
          return penalty(k, offset, b->query(y, 0.7), Want::gradient, band).gradient;
        };
        const PointResult exact = penalty(k, offset, b->query(x, 0.7), Want::hessian, band);
        if (exact.energy == 0.0) continue;
        EXPECT_LT((numeric_gradient<3>(energy, x, 1e-8) - exact.gradient).norm(),
                  1e-6 * exact.gradient.norm());
        EXPECT_LT((numeric_jacobian<3, 3>(gradient, x, 1e-8) - exact.hessian).norm(),
                  1e-6 * exact.hessian.norm());
      }
    }
  }
}

TEST(Penalty, ZeroOutsideTheOffsetLayer) {
  const Plane floor(Vector3d::Zero(), Vector3d::UnitZ());
  const PointResult out = penalty(1e3, 0.01, floor.query(Vector3d(0, 0, 0.02)), Want::hessian);
  EXPECT_EQ(out.energy, 0.0);
  EXPECT_TRUE(out.gradient.isZero() && out.hessian.isZero());
  const PointResult in = penalty(1e3, 0.01, floor.query(Vector3d(0, 0, 0.005)), Want::hessian);
  EXPECT_NEAR(in.energy, 0.5 * 1e3 * 0.005 * 0.005, 1e-15);
  EXPECT_NEAR(in.gradient.z(), -5.0, 1e-12); // the force on the vertex pushes it out: +5 N
  // 5 mm deep, past a 3 mm onset band: the plain law's force k g and
  // stiffness k, and its energy less the onset's saving, k b^2 / 12.
  const PointResult banded =
      penalty(1e3, 0.01, floor.query(Vector3d(0, 0, 0.005)), Want::hessian, 0.003);
  EXPECT_NEAR(banded.energy, 0.5 * 1e3 * 0.005 * 0.005 - 1e3 * 0.003 * 0.003 / 12.0, 1e-15);
  EXPECT_NEAR(banded.gradient.z(), -5.0, 1e-12);
  EXPECT_NEAR(banded.hessian(2, 2), 1e3, 1e-9);
}

// The normal force's onset over the band b: zero force and stiffness at the
// layer's edge, k g and k from the band on, continuous in value and slope
// at b, never above k g, its energy the integral of the force (Simpson's
// rule here) and its stiffness the force's slope (central differences).
TEST(Penalty, SmoothOnsetMeetsThePlainLawAtTheBand) {
  const double k = 2e4, offset = 1e-3, band = 0.3 * offset;
  const auto force = [&](double g) { return penalty_law(k, band, g).force; };
  EXPECT_EQ(penalty_law(k, band, 0.0).force, 0.0);
  EXPECT_EQ(penalty_law(k, band, -1e-4).energy, 0.0);
  EXPECT_LT(penalty_law(k, band, 1e-9 * band).stiffness, 1e-8 * k);
  const double h = 1e-9 * band;
  EXPECT_NEAR(force(band - h), force(band + h), 1e-6 * k * band);
  EXPECT_NEAR(penalty_law(k, band, band - h).stiffness, penalty_law(k, band, band + h).stiffness,
              1e-6 * k);
  for (double g : {0.1 * band, 0.5 * band, 0.9 * band, band, 1.5 * band, 0.8 * offset}) {
    const PenaltyLaw law = penalty_law(k, band, g);
    EXPECT_LE(law.force, k * g * (1.0 + 1e-14));
    if (g >= band) {
      EXPECT_NEAR(law.force, k * g, 1e-12 * k * g);
      EXPECT_EQ(law.stiffness, k);
    }
    const double slope = (force(g + 1e-7 * band) - force(g - 1e-7 * band)) / (2e-7 * band);
    EXPECT_NEAR(law.stiffness, slope, 1e-5 * k);
    const int n = 2000; // Simpson's rule on [0, g]: the force is piecewise cubic
    double integral = force(0.0) + force(g);
    for (int i = 1; i < n; ++i)
      integral += (i % 2 ? 4.0 : 2.0) * force(g * i / n);
    integral *= g / (3.0 * n);
    EXPECT_NEAR(law.energy, integral, 1e-9 * k * g * g);
  }
}

TEST(Penalty, AnchorSpringDerivatives) {
  const double inf = std::numeric_limits<double>::infinity();
  const Vector3d anchor(0.1, 0.2, 0.0), normal = Vector3d(0.2, -0.1, 1.0).normalized();
  const Vector3d x(0.13, 0.18, 0.004);
  const auto energy = [&](const Vector3d& y) {
    return anchor_spring(3e3, y, anchor, normal, inf, Want::energy).energy;
  };
  const auto gradient = [&](const Vector3d& y) {
    return anchor_spring(3e3, y, anchor, normal, inf, Want::gradient).gradient;
  };
  const PointResult exact = anchor_spring(3e3, x, anchor, normal, inf, Want::hessian);
  EXPECT_LT((numeric_gradient<3>(energy, x, 1e-7) - exact.gradient).norm(),
            1e-7 * exact.gradient.norm());
  EXPECT_LT((numeric_jacobian<3, 3>(gradient, x, 1e-7) - exact.hessian).norm(), 1e-6 * 3e3);
  EXPECT_NEAR(exact.gradient.dot(normal), 0.0, 1e-10); // purely tangential
}

// Past its bound the spring pulls with the bound along the stretch (Coulomb's
// sliding force), whatever the stretch; below it, it is the plain spring.
TEST(Penalty, BoundedAnchorSpringSlidesAtItsBound) {
  const Vector3d anchor(0.1, 0.2, 0.0), normal = Vector3d(0.2, -0.1, 1.0).normalized();
  const double k = 3e3, bound = 12.0;  // reach: 4 mm
  const Vector3d x(0.13, 0.18, 0.004); // |P (x - a)| about 36 mm: sliding
  const auto energy = [&](const Vector3d& y) {
    return anchor_spring(k, y, anchor, normal, bound, Want::energy).energy;
  };
  const auto gradient = [&](const Vector3d& y) {
    return anchor_spring(k, y, anchor, normal, bound, Want::gradient).gradient;
  };
  const PointResult exact = anchor_spring(k, x, anchor, normal, bound, Want::hessian);
  const Vector3d stretch = (x - anchor) - normal.dot(x - anchor) * normal;
  EXPECT_NEAR(exact.gradient.norm(), bound, 1e-12 * bound);
  EXPECT_NEAR(exact.gradient.normalized().dot(stretch.normalized()), 1.0, 1e-12);
  // E = bound (s - r/2), s = |stretch|, r = bound / k.
  EXPECT_NEAR(exact.energy, bound * (stretch.norm() - 0.5 * bound / k), 1e-12);
  EXPECT_LT((numeric_gradient<3>(energy, x, 1e-7) - exact.gradient).norm(), 1e-6 * bound);
  EXPECT_LT((numeric_jacobian<3, 3>(gradient, x, 1e-7) - exact.hessian).norm(),
            1e-5 * bound / stretch.norm());
  EXPECT_LT((exact.hessian * stretch).norm(), 1e-9 * bound); // no stiffness along the slip
  // Within the reach: the plain spring.
  const Vector3d near = anchor + 0.5 * (bound / k) * stretch.normalized();
  const PointResult held = anchor_spring(k, near, anchor, normal, bound, Want::hessian);
  EXPECT_NEAR(held.gradient.norm(), 0.5 * bound, 1e-9 * bound);
  EXPECT_LT((held.hessian - k * (Eigen::Matrix3d::Identity() - normal * normal.transpose())).norm(),
            1e-9 * k);
}

// The spring in the tangent plane at the vertex, on a ball and a rounded
// box moving on the clock: its gradient is the energy's (central
// differences); its force lies in the plane at the vertex and, sliding,
// has the bound's size; with the anchor at the vertex's level (m . r = 0,
// where the one term left out of the Hessian vanishes) the Hessian is the
// gradient's derivative on curved and flat parts alike, sticking or sliding.
TEST(Penalty, SurfaceAnchorSpringPullsInThePlaneAtTheVertex) {
  Body ball("ball", std::make_shared<Sphere>(Vector3d(0, 0, 0), 0.3), Vector3d::Zero());
  ball.motion.angle.add(0.0, 0.0);
  ball.motion.angle.add(1.0, 0.5);
  Body table("table", std::make_shared<Box>(Vector3d::Zero(), Vector3d(1, 1, 0.1), 0.02),
             Vector3d::Zero());
  const double k = 3e3, clock = 0.7;
  int sticking = 0, sliding = 0;
  std::mt19937 random(5);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  for (const Body* body : {&ball, &table}) {
    for (int i = 0; i < 40; ++i) {
      const Vector3d direction =
          Vector3d(uniform(random), uniform(random), uniform(random)).normalized();
      const SurfaceQuery at_surface = body->query(2.0 * direction, clock);
      const Vector3d normal = at_surface.normal.normalized();
      // The vertex 1 mm off the surface; the anchor at its level, 0 to 3 cm
      // away along the surface's tangent (sticking for the small ones).
      const Vector3d x = at_surface.closest + 1e-3 * normal;
      Vector3d tangent = normal.cross(Vector3d(uniform(random), uniform(random), uniform(random)));
      tangent.normalize();
      const Vector3d anchor = x + 0.015 * (uniform(random) + 1.0) * tangent;
      const double bound = 12.0; // reach 4 mm
      const auto energy = [&](const Vector3d& y) {
        return surface_anchor_spring(k, y, anchor, body->query(y, clock), bound, Want::energy)
            .energy;
      };
      const auto gradient = [&](const Vector3d& y) {
        return surface_anchor_spring(k, y, anchor, body->query(y, clock), bound, Want::gradient)
            .gradient;
      };
      const SurfaceQuery here = body->query(x, clock);
      const PointResult exact = surface_anchor_spring(k, x, anchor, here, bound, Want::hessian);
      const double force = exact.gradient.norm();
      EXPECT_LT((numeric_gradient<3>(energy, x, 1e-7) - exact.gradient).norm(), 1e-6 * force);
      EXPECT_LT(std::abs(exact.gradient.dot(here.normal.normalized())), 1e-9 * force);
      const double slip = (anchor - x).norm();
      if (k * slip > bound) {
        EXPECT_NEAR(force, bound, 1e-9 * bound);
        ++sliding;
      } else {
        ++sticking;
      }
      // The force's derivative in the stiffness at a fixed bound.
      const auto force_at = [&](double stiffness) {
        return surface_anchor_spring(stiffness, x, anchor, here, bound, Want::gradient).gradient;
      };
      const Vector3d by_stiffness = (force_at(1.001 * k) - force_at(0.999 * k)) / (0.002 * k);
      if (std::abs(k * slip / bound - 1.0) > 0.01) {
        EXPECT_LT(
            (surface_anchor_spring_stiffness_derivative(k, x, anchor, here, bound) - by_stiffness)
                .norm(),
            1e-9 * force / k);
      }
      const Eigen::Matrix3d differenced = numeric_jacobian<3, 3>(gradient, x, 1e-7);
      EXPECT_LT((differenced - exact.hessian).norm(), 1e-6 * differenced.norm())
          << body->name() << " slip " << slip;
    }
  }
  EXPECT_GT(sticking, 5);
  EXPECT_GT(sliding, 5);
}

TEST(Penalty, CoulombAnchorUpdate) {
  const Vector3d normal = Vector3d::UnitZ(), anchor = Vector3d::Zero();
  const double k = 100.0, normal_force = 2.0; // mu_s = 0.5 -> sticks up to 1 N = 1 cm
  const AnchorUpdate stick =
      slide_anchor(k, Vector3d(0.006, 0.008, 0.001), anchor, normal, normal_force, 0.5, 0.4);
  EXPECT_FALSE(stick.slid);
  EXPECT_EQ(stick.anchor, anchor);
  const Vector3d x(0.012, 0.016, 0.001); // 2 N of spring force: slides
  const AnchorUpdate slip = slide_anchor(k, x, anchor, normal, normal_force, 0.5, 0.4);
  ASSERT_TRUE(slip.slid);
  const Vector3d stretch = x - slip.anchor - normal.dot(x - slip.anchor) * normal;
  EXPECT_NEAR(k * stretch.norm(), 0.4 * normal_force, 1e-12); // kinetic force
  EXPECT_NEAR(stretch.normalized().dot(Vector3d(0.6, 0.8, 0)), 1.0, 1e-12);
}

TEST(Penalty, StiffnessRule) {
  EXPECT_NEAR(penalty_stiffness(10.0, 3e4, 0.005, 0.1), 10.0 * 3e4 * 0.5, 1e-9);
}

TEST(BodySpec, ParsesShapesFrictionAndMotions) {
  const Body ball = parse_body("sphere center=0,0,0.5 radius=0.3 mu=0.4", "option --body", "body");
  EXPECT_EQ(ball.name(), "body");
  EXPECT_NEAR(ball.query(Vector3d(0, 0, 1.0), 0.0).distance, 0.2, 1e-14);
  EXPECT_EQ(ball.friction.static_coefficient, 0.4);
  EXPECT_EQ(ball.friction.kinetic_coefficient, 0.4);
  const Body disk = parse_body("disk top=0,0,0.5 radius=0.09 thickness=0.02 name=support",
                               "option --body2", "body2");
  EXPECT_EQ(disk.name(), "support");
  EXPECT_NEAR(disk.query(Vector3d(0, 0, 0.6), 0.0).distance, 0.1, 1e-14);
  EXPECT_NEAR(disk.query(Vector3d(0, 0, 0.49), 0.0).distance, -0.01, 1e-14);
  const Body lift = parse_body(
      "box size=1,1,0.1 translate=0:0,0,0;2:0,0,1 rotate=0:0;2:90 rotate_axis=0,1,0 mu_s=0.5 "
      "mu_k=0.3",
      "option --body", "body");
  // At t = 2 the slab stands on edge (turned 90 degrees about y) around z = 1.
  EXPECT_NEAR(lift.query(Vector3d(0.15, 0.2, 1.1), 2.0).distance, 0.1, 1e-14);
  EXPECT_EQ(lift.friction.kinetic_coefficient, 0.3);
  const Body grown = parse_body("cylinder radius=0.1 height=1 direction=0,1,0 scale=0:1;10:1.5",
                                "option --body", "body");
  EXPECT_NEAR(grown.query(Vector3d(0.2, 0, 0), 10.0).distance, 0.05, 1e-14);
  EXPECT_NO_THROW(parse_body("plane normal=0,1,1", "option --body", "floor"));
  EXPECT_NO_THROW(parse_body("capsule a=0,0,0 b=1,0,0 radius=0.1", "option --body", "arm"));
}

void expect_error(const std::string& spec, const std::string& message) {
  try {
    parse_body(spec, "option --body3", "body3");
    ADD_FAILURE() << "no error for '" << spec << "'";
  } catch (const InputError& error) {
    EXPECT_EQ(std::string(error.what()), "option --body3: " + message) << spec;
  }
}

TEST(BodySpec, BadSpecificationsNameTheOptionAndTheProblem) {
  expect_error("", "empty body specification (expected e.g. 'sphere radius=0.3')");
  expect_error(
      "cube size=1,1,1",
      "unknown body 'cube' (plane, sphere, capsule, cylinder, disk, box, mesh, mannequin)");
  expect_error("mesh", "mesh needs file=");
  expect_error("sphere center=0,0,0", "sphere needs radius=");
  expect_error("sphere radius=0.3 radius=0.4", "key 'radius' is given twice");
  expect_error("sphere radius=abc", "radius: 'abc' is not a number");
  expect_error("sphere radius=-1", "radius must be > 0, got -1");
  expect_error("sphere radius=1 centre=0,0,0", "unknown key 'centre' for a sphere");
  expect_error("sphere radius=1 center=0,0", "center: expected X,Y,Z, got '0,0'");
  expect_error("sphere radius=1 mu_s=0.2 mu_k=0.3",
               "friction coefficients must satisfy 0 <= mu_k <= mu_s, got mu_s=0.2 mu_k=0.3");
  expect_error("sphere radius=1 translate=1:0,0,0;0:0,0,1",
               "translate: motion sample times must increase: 0 follows 1");
  expect_error("plane normal=0,0,0", "plane normal must be a non-zero vector, got 0,0,0");
  expect_error("box size=1,1,1 rounding=0.7",
               "rounding must lie in [0, smallest size / 2], got 0.7");
  expect_error("sphere radius", "'radius' is not key=value");
}

} // namespace
} // namespace sartor::contact
