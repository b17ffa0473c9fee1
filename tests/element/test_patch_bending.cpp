// The rotation-free patch bending triangle: derivatives by finite
// differences, rigid motions, exact curvature of quadratic surfaces on
// irregular and stretched patches, the free-edge condition, orthotropy and
// rest curvature, and the ill-conditioned fallback.

#include "element/patch_bending.hpp"

#include "common/error.hpp"
#include "finite_difference.hpp"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include <cmath>
#include <functional>

namespace sartor::element {
namespace {

using Eigen::Vector2d;
using Eigen::Vector3d;
using testing::numeric_gradient;
using testing::numeric_jacobian;
using testing::relative_error;

// An irregular patch: the triangle and the nodes across its three edges.
std::array<Vector2d, 6> irregular_patch() {
  return {Vector2d(0.0, 0.0), Vector2d(1.0, 0.1),  Vector2d(0.3, 0.9),
          Vector2d(1.1, 1.0), Vector2d(-0.6, 0.4), Vector2d(0.6, -0.8)};
}

// A triangle with its own patch's slopes on every edge (no neighbour
// patches: nodes 6..11 carry nothing), which is what step 3 does with any
// slopes; the shared slopes of the mesh are checked in tests/verification.
PatchRest rest_of(const std::array<Vector2d, 6>& uv, const BendingRigidity& d,
                  std::array<bool, 3> has_node = {true, true, true},
                  const Vector3d& rest_curvature = Vector3d::Zero()) {
  const std::array<Vector2d, 3> triangle = {uv[0], uv[1], uv[2]};
  const auto own = midedge_slopes(triangle, {uv[3], uv[4], uv[5]}, has_node, d);
  std::array<Eigen::Matrix<double, 1, 12>, 3> slopes;
  for (std::size_t k = 0; k < 3; ++k) {
    slopes[k].setZero();
    slopes[k].head<6>() = own[k];
  }
  return patch_rest(triangle, slopes, d, rest_curvature);
}

// Positions of the material points on the surface z = f(u, v).
// (Slots 6..11 hold further points of the surface, which carry no weight here.)
Vector36 lift(const std::array<Vector2d, 6>& uv,
              const std::function<Vector3d(const Vector2d&)>& surface) {
  Vector36 x;
  for (int i = 0; i < 12; ++i)
    x.segment<3>(3 * i) = surface(uv[std::size_t(i % 6)] + Vector2d(0.1 * (i / 6), 0.0));
  return x;
}

BendingRigidity orthotropic() {
  return {2.0, 0.7, 0.3, 0.4};
}

TEST(PatchBending, DerivativesMatchFiniteDifferences) {
  const auto uv = irregular_patch();
  for (const bool boundary : {false, true}) {
    const PatchRest rest =
        rest_of(uv, orthotropic(), {true, !boundary, true}, Vector3d(0.3, -0.2, 0.1));
    Vector36 x = lift(uv, [](const Vector2d& p) {
      return Vector3d(p.x() + 0.1 * p.y() * p.y(), p.y() - 0.05 * p.x() * p.y(),
                      0.4 * p.x() * p.x() - 0.3 * p.x() * p.y() + 0.2 * p.y() * p.y());
    });
    x(17) += 0.05;
    x(9) -= 0.03;
    x(29) += 0.04;
    const auto energy = [&](const Vector36& y) {
      return patch_bending(rest, y, Want::energy).energy;
    };
    const auto gradient = [&](const Vector36& y) {
      return Vector36(patch_bending(rest, y, Want::gradient).gradient);
    };
    const Result<36> r = patch_bending(rest, x, Want::hessian);
    EXPECT_LT(relative_error(numeric_gradient<36>(energy, x, 1e-6), r.gradient), 1e-7);
    EXPECT_LT(relative_error(numeric_jacobian<36, 36>(gradient, x, 1e-6), r.hessian), 1e-6);
  }
}

// The projection in the Hessian's 14-dimensional range is the full 36 x 36
// projection: on bent, twisted and stretched patches whose Hessians are
// indefinite (so that the projection changes them), with and without a
// boundary edge.
TEST(PatchBending, ProjectionInTheHessiansRangeIsTheFullProjection) {
  const auto uv = irregular_patch();
  int projected = 0;
  for (const bool boundary : {false, true}) {
    for (const double bend : {0.4, -1.5, 3.0}) {
      const PatchRest rest =
          rest_of(uv, orthotropic(), {true, !boundary, true}, Vector3d(-bend, 0.8, 0.5));
      Vector36 x = lift(uv, [bend](const Vector2d& p) {
        return Vector3d(1.2 * p.x() + 0.1 * p.y() * p.y(), p.y() - 0.05 * p.x() * p.y(),
                        bend * p.x() * p.x() - 0.3 * p.x() * p.y() + 0.2 * p.y() * p.y());
      });
      x(17) += 0.05;
      x(9) -= 0.03;
      const Eigen::Matrix<double, 36, 36> hessian = patch_bending(rest, x, Want::hessian).hessian;
      Eigen::Matrix<double, 36, 36> full = hessian, reduced = hessian;
      project_to_psd<36>(full);
      project_patch_hessian_to_psd(rest, x, reduced);
      if ((full - hessian).norm() > 1e-3 * hessian.norm()) ++projected;
      EXPECT_LT((reduced - full).norm(), 1e-10 * hessian.norm()) << bend << " " << boundary;
    }
  }
  EXPECT_GE(projected, 4); // indefinite Hessians, not only the early return
}

// The Gauss-Newton Hessian leaves out only the moments' share: where the
// patch carries no moment (its rest curvature set to the curvature it has,
// found by the test as the minimiser of the energy over the rest curvature,
// a quadratic, by central differences) it is the exact Hessian, that is,
// the finite-difference Jacobian of the gradient; where it bends against
// its rest curvature it stays symmetric and positive semi-definite, and
// differs from the exact Hessian.
TEST(PatchBending, GaussNewtonHessianIsExactWithoutMomentAndPsdWithOne) {
  const auto uv = irregular_patch();
  Vector36 x = lift(uv, [](const Vector2d& p) {
    return Vector3d(1.2 * p.x() + 0.1 * p.y() * p.y(), p.y() - 0.05 * p.x() * p.y(),
                    -1.5 * p.x() * p.x() - 0.3 * p.x() * p.y() + 0.2 * p.y() * p.y());
  });
  x(17) += 0.05;
  x(9) -= 0.03;
  const auto energy_at_rest = [&](const Vector3d& c) {
    return patch_bending(rest_of(uv, orthotropic(), {true, true, true}, c), x, Want::energy).energy;
  };
  const double h = 1e-3;
  Vector3d slope;
  Eigen::Matrix3d curvature;
  for (int i = 0; i < 3; ++i) {
    const Vector3d ei = h * Vector3d::Unit(i);
    slope(i) = (energy_at_rest(ei) - energy_at_rest(-ei)) / (2.0 * h);
    for (int j = 0; j < 3; ++j) {
      const Vector3d ej = h * Vector3d::Unit(j);
      curvature(i, j) = (energy_at_rest(ei + ej) - energy_at_rest(ei - ej) -
                         energy_at_rest(-ei + ej) + energy_at_rest(-ei - ej)) /
                        (4.0 * h * h);
    }
  }
  const Vector3d own_curvature = -curvature.ldlt().solve(slope);
  const PatchRest unloaded = rest_of(uv, orthotropic(), {true, true, true}, own_curvature);
  EXPECT_LT(patch_bending(unloaded, x, Want::gradient).gradient.norm(), 1e-9);
  const auto gradient = [&](const Vector36& y) {
    return Vector36(patch_bending(unloaded, y, Want::gradient).gradient);
  };
  const Eigen::Matrix<double, 36, 36> gauss_newton = patch_gauss_newton_hessian(unloaded, x);
  EXPECT_LT(relative_error(numeric_jacobian<36, 36>(gradient, x, 1e-6), gauss_newton), 1e-6);

  const PatchRest loaded = rest_of(uv, orthotropic(), {true, true, true}, Vector3d(1.5, 0.8, 0.5));
  const Eigen::Matrix<double, 36, 36> bent = patch_gauss_newton_hessian(loaded, x);
  const Eigen::Matrix<double, 36, 36> exact = patch_bending(loaded, x, Want::hessian).hessian;
  EXPECT_LT((bent - bent.transpose()).norm(), 1e-14 * bent.norm());
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 36, 36>> eigen(bent);
  EXPECT_GT(eigen.eigenvalues().minCoeff(), -1e-12 * bent.norm());
  EXPECT_GT((bent - exact).norm(), 1e-2 * exact.norm());
}

TEST(PatchBending, RigidMotionsStoreNothing) {
  const auto uv = irregular_patch();
  const PatchRest rest = rest_of(uv, orthotropic());
  const Eigen::Matrix3d turn =
      Eigen::AngleAxisd(0.8, Vector3d(1.0, -2.0, 0.5).normalized()).toRotationMatrix();
  const Vector36 x = lift(uv, [&](const Vector2d& p) {
    return Vector3d(turn * Vector3d(p.x(), p.y(), 0.0) + Vector3d(5.0, -3.0, 2.0));
  });
  const Result<36> r = patch_bending(rest, x, Want::gradient);
  EXPECT_LT(r.energy, 1e-28);
  EXPECT_LT(r.gradient.norm(), 1e-13);
}

// Isometric bending onto a cylinder of radius R along direction phi in the
// (u, v) plane: the curvature is (cos^2, sin^2, 2 sin cos) / R exactly.
Vector3d cylinder(const Vector2d& p, double radius, double phi) {
  const Vector2d along(std::cos(phi), std::sin(phi));
  const Vector2d across(-std::sin(phi), std::cos(phi));
  const double s = p.dot(along);
  const double t = p.dot(across);
  const Vector2d in_plane = radius * std::sin(s / radius) * along + t * across;
  return {in_plane.x(), in_plane.y(), radius * (1.0 - std::cos(s / radius))};
}

TEST(PatchBending, QuadraticSurfaceGivesExactCurvature) {
  // On a shallow paraboloid z = (a u^2 + 2 b u v + c v^2)/2 the curvature at
  // the (flat) material point is (a, c, 2 b) to first order in the slope; on
  // the irregular patch and on the same patch stretched four times along u.
  const double a = 0.02, b = -0.01, c = 0.03;
  for (const double stretch : {1.0, 4.0}) {
    auto uv = irregular_patch();
    for (auto& p : uv)
      p.x() *= stretch;
    const BendingRigidity d = orthotropic();
    const PatchRest rest = rest_of(uv, d);
    const Vector36 x = lift(uv, [&](const Vector2d& p) {
      return Vector3d(p.x(), p.y(),
                      0.5 * (a * p.x() * p.x() + 2.0 * b * p.x() * p.y() + c * p.y() * p.y()));
    });
    const Vector3d kappa(a, c, 2.0 * b);
    const double expected = 0.5 * rest.area * kappa.dot(d.matrix() * kappa);
    const double tilt = 0.1 * stretch; // largest slope over the patch, order of
    EXPECT_NEAR(patch_bending(rest, x, Want::energy).energy / expected, 1.0, 4.0 * tilt * tilt);
  }
}

TEST(PatchBending, CylinderEnergyAtLargeRotation) {
  // A deep cylinder (the patch spans a radian): the curvature stays 1/R
  // within the quadratic's error, in any direction.
  const auto uv = irregular_patch();
  const BendingRigidity d = BendingRigidity::isotropic(1.0);
  const PatchRest rest = rest_of(uv, d);
  for (const double phi : {0.0, 0.7, 2.0}) {
    const double radius = 5.0;
    const Vector36 x = lift(uv, [&](const Vector2d& p) { return cylinder(p, radius, phi); });
    const double expected = 0.5 * rest.area / (radius * radius);
    EXPECT_NEAR(patch_bending(rest, x, Want::energy).energy / expected, 1.0, 0.02) << phi;
  }
}

TEST(PatchBending, FreeEdgeCarriesNoMomentAcrossIt) {
  // A triangle whose edge (1, 2) is free, bent along the edge's normal: the
  // condition M_nn = 0 (nu = 0) makes x_,nn vanish, so the patch sees only
  // the curvature the other two nodes impose; bending along the free edge
  // is still seen exactly.
  const std::array<Vector2d, 6> uv = {Vector2d(0.0, 0.0), Vector2d(1.0, 0.0),  Vector2d(0.0, 1.0),
                                      Vector2d(0.0, 0.0), Vector2d(-1.0, 1.0), Vector2d(1.0, -1.0)};
  const BendingRigidity d = BendingRigidity::isotropic(1.0);
  const PatchRest rest = rest_of(uv, d, {false, true, true});
  // Curvature along the free edge's direction (1, -1)/sqrt 2: exact.
  const double radius = 20.0;
  const double along_edge = std::atan2(-1.0, 1.0);
  Vector36 x = lift(uv, [&](const Vector2d& p) { return cylinder(p, radius, along_edge); });
  x.segment<3>(9) = x.segment<3>(0); // the missing node's slot
  const double expected = 0.5 * rest.area / (radius * radius);
  EXPECT_NEAR(patch_bending(rest, x, Want::energy).energy / expected, 1.0, 1e-2);
}

TEST(PatchBending, NodeAcrossFromAnotherPanel) {
  // The neighbour's node given in a rotated, moved frame lands where it
  // would in this one.
  const Vector2d a(0.0, 0.0), b(1.0, 0.2), c(0.3, 0.9), p(0.7, -0.8);
  const Eigen::Rotation2Dd turn(2.1);
  const Vector2d shift(4.0, -1.0);
  const Vector2d placed =
      node_across<double>(a, b, c, turn * a + shift, turn * b + shift, turn * p + shift);
  EXPECT_LT((placed - p).norm(), 1e-12);
}

TEST(PatchBending, RejectsBadInput) {
  const auto uv = irregular_patch();
  EXPECT_THROW(rest_of(uv, {1.0, 1.0, 2.0, 0.5}), InputError); // coupling^2 > warp weft
  EXPECT_THROW(rest_of(uv, {-1.0, 1.0, 0.0, 0.5}), InputError);
  auto flat = uv;
  flat[2] = Vector2d(0.5, 0.05);
  EXPECT_THROW(rest_of(flat, orthotropic()), InputError); // node 3 on the wrong side
  flat[2] = Vector2d(2.0, 0.2);
  EXPECT_THROW(rest_of(flat, orthotropic()), InputError); // degenerate
}

TEST(PatchBending, NodesOnAConicAreRegularised) {
  // The six nodes of a regular hexagon-like patch on a circle: the quadratic
  // is not unique; the fallback keeps the result finite and still exact for
  // the quadratic fields it can resolve (rigid motions).
  std::array<Vector2d, 6> uv;
  const double angles[6] = {0.0, 2.0, 4.0, 3.0, 5.0, 1.0};
  for (int i = 0; i < 6; ++i)
    uv[std::size_t(i)] = Vector2d(std::cos(angles[i]), std::sin(angles[i]));
  const PatchRest rest = rest_of(uv, orthotropic());
  EXPECT_TRUE(rest.weights.allFinite());
  const Vector36 x = lift(uv, [](const Vector2d& p) { return Vector3d(p.x(), p.y(), 0.0); });
  EXPECT_LT(patch_bending(rest, x, Want::energy).energy, 1e-28);
}

} // namespace
} // namespace sartor::element

namespace sartor::element {
namespace {

// Moment-curvature curves (measured fabrics): energy the integral of the
// curves, derivatives by finite differences, and the moment of a cylinder.
TEST(PatchBending, MomentCurvatureCurves) {
  const auto uv = irregular_patch();
  PatchRest rest = rest_of(uv, orthotropic(), {true, false, true}, Vector3d(0.05, -0.02, 0.01));
  // Bilinear curves: kinks at 0.1, 0.2 and 0.15 1/m.
  rest.curves = std::make_shared<const FabricBending>(
      FabricBending{MomentCurve::piecewise({{0.1, 0.2}, {1.0, 0.5}}, "warp"),
                    MomentCurve::piecewise({{0.2, 0.14}, {1.0, 0.3}}, "weft"),
                    MomentCurve::piecewise({{0.15, 0.06}, {1.0, 0.1}}, "twist")});
  Vector36 x = lift(uv, [](const Vector2d& p) {
    return Vector3d(p.x(), p.y(), 0.4 * p.x() * p.x() - 0.3 * p.x() * p.y() + 0.2 * p.y() * p.y());
  });
  x(17) += 0.05;
  x(29) += 0.04;
  const auto energy = [&](const Vector36& y) {
    return patch_bending(rest, y, Want::energy).energy;
  };
  const auto gradient = [&](const Vector36& y) {
    return Vector36(patch_bending(rest, y, Want::gradient).gradient);
  };
  const Result<36> r = patch_bending(rest, x, Want::hessian);
  EXPECT_LT(relative_error(numeric_gradient<36>(energy, x, 1e-7), r.gradient), 1e-6);
  EXPECT_LT(relative_error(numeric_jacobian<36, 36>(gradient, x, 1e-7), r.hessian), 1e-5);

  // A shallow cylinder z = c u^2 / 2 (curvature c along the warp, on the
  // second piece of a warp curve with its kink at 0.01 1/m) from flat: energy
  // A W_warp(c), W the integral of the curve,
  // 0.01 * 0.2 / 2 + (c - 0.01)(0.2 + M(c)) / 2.
  PatchRest flat = rest_of(uv, orthotropic());
  flat.rigidity(0, 1) = flat.rigidity(1, 0) = 0.0;
  flat.curves = std::make_shared<const FabricBending>(
      FabricBending{MomentCurve::piecewise({{0.01, 0.2}, {0.1, 0.5}}, "warp"),
                    MomentCurve::linear(1.0, "weft"), MomentCurve::linear(1.0, "twist")});
  const double c = 0.06;
  const Vector36 cylinder =
      lift(uv, [c](const Vector2d& p) { return Vector3d(p.x(), p.y(), 0.5 * c * p.x() * p.x()); });
  const double moment = 0.2 + (c - 0.01) * (0.3 / 0.09);
  const double expected = flat.area * (0.5 * 0.01 * 0.2 + 0.5 * (c - 0.01) * (0.2 + moment));
  // The lift is isometric to O(c^2 u^2): 1 %.
  EXPECT_NEAR(patch_bending(flat, cylinder, Want::energy).energy, expected, 0.01 * expected);
}

} // namespace
} // namespace sartor::element
