// The kernels' rest-coordinate derivatives (element/rest_derivative.hpp,
// membrane_rest_derivative, membrane_tension_rest_derivative, the patch
// geometry on AutoDiff): each against central differences of the
// kernel's own force (or tensions, or rest data) with its rest data rebuilt
// at X +- h dX.

#include "common/autodiff.hpp"
#include "element/membrane.hpp"
#include "element/patch_bending.hpp"
#include "element/rest_derivative.hpp"
#include "element/seam.hpp"
#include "tests/element/finite_difference.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>

namespace sartor::element {
namespace {

using Eigen::Vector2d;
using Eigen::Vector3d;
using testing::relative_error;

template <std::size_t N>
std::array<Vector2d, N> moved(const std::array<Vector2d, N>& uv, const std::array<Vector2d, N>& d,
                              double h) {
  std::array<Vector2d, N> out;
  for (std::size_t i = 0; i < N; ++i)
    out[i] = uv[i] + h * d[i];
  return out;
}

// d/dh f(h) at 0 by a central difference, f returning a vector.
template <class Function>
auto central(const Function& f, double h) {
  return ((f(h) - f(-h)) / (2.0 * h)).eval();
}

const std::array<Vector2d, 3> triangle_uv = {Vector2d(0.0, 0.0), Vector2d(0.11, 0.01),
                                             Vector2d(0.03, 0.09)};
const std::array<Vector2d, 3> triangle_change = {Vector2d(0.2, -0.1), Vector2d(0.5, 0.3),
                                                 Vector2d(-0.4, 0.7)};

// A triangle stretched, sheared and turned out of its plane.
Vector9 deformed_triangle() {
  const Eigen::Matrix3d turn =
      Eigen::AngleAxisd(0.4, Vector3d(1.0, 2.0, 0.5).normalized()).toRotationMatrix();
  Vector9 x;
  const std::array<Vector3d, 3> p = {Vector3d(0.0, 0.0, 0.0), Vector3d(0.12, 0.015, 0.004),
                                     Vector3d(0.028, 0.097, -0.006)};
  for (int i = 0; i < 3; ++i)
    x.segment<3>(3 * i) = turn * p[std::size_t(i)] + Vector3d(0.3, -0.2, 1.0);
  return x;
}

void expect_membrane_derivative(MembraneModel model) {
  const MembraneMaterial material{TensionCurve::linear(800.0, "warp"),
                                  TensionCurve::linear(500.0, "weft"), 60.0, 0.3};
  const NonelasticStrain nonelastic{0.02, -0.01};
  const Vector9 x = deformed_triangle();
  const Vector9 exact =
      membrane_rest_derivative(model, material, triangle_uv, nonelastic, x, triangle_change);
  const auto force = [&](double h) {
    const TriangleRest rest = triangle_rest(moved(triangle_uv, triangle_change, h));
    return membrane(model, material, rest, nonelastic, x, Want::gradient).gradient;
  };
  EXPECT_LT(relative_error(central(force, 1e-6), exact), 1e-7) << membrane_model_name(model);
}

TEST(RestDerivative, MembraneBaraffWitkin) {
  expect_membrane_derivative(MembraneModel::baraff_witkin);
}

TEST(RestDerivative, MembraneSaintVenantKirchhoff) {
  expect_membrane_derivative(MembraneModel::saint_venant_kirchhoff);
}

// The tensions the monolithic creep coupling's strains follow.
void expect_tension_derivative(MembraneModel model) {
  const MembraneMaterial material{TensionCurve::linear(800.0, "warp"),
                                  TensionCurve::linear(500.0, "weft"), 60.0, 0.3};
  const NonelasticStrain nonelastic{0.02, -0.01};
  const Vector9 x = deformed_triangle();
  const Vector2d exact = membrane_tension_rest_derivative(model, material, triangle_uv, nonelastic,
                                                          x, triangle_change);
  const auto tensions = [&](double h) {
    const TriangleRest rest = triangle_rest(moved(triangle_uv, triangle_change, h));
    const MembraneStrain s = membrane_strain(model, material, rest, nonelastic, x);
    return Vector2d(s.tension_warp, s.tension_weft);
  };
  EXPECT_GT(exact.norm(), 0.0);
  EXPECT_LT(relative_error(central(tensions, 1e-6), exact), 1e-7) << membrane_model_name(model);
}

TEST(RestDerivative, MembraneTensionsBaraffWitkin) {
  expect_tension_derivative(MembraneModel::baraff_witkin);
}

TEST(RestDerivative, MembraneTensionsSaintVenantKirchhoff) {
  expect_tension_derivative(MembraneModel::saint_venant_kirchhoff);
}

TEST(RestDerivative, TriangleArea) {
  const auto area = [](double h) {
    return Eigen::Matrix<double, 1, 1>(triangle_rest(moved(triangle_uv, triangle_change, h)).area);
  };
  const double exact = triangle_area_derivative(triangle_uv, triangle_change);
  EXPECT_NEAR(central(area, 1e-6)(0), exact, 1e-8 * std::abs(exact));
}

// A hinge of two triangles from different panels, folded by 0.5 rad.
struct HingeCase {
  std::array<Vector2d, 3> first = {Vector2d(0.0, 0.0), Vector2d(0.1, 0.01), Vector2d(0.04, 0.08)};
  std::array<Vector2d, 3> second = {Vector2d(0.3, 0.0), Vector2d(0.2, -0.01),
                                    Vector2d(0.27, -0.09)};
  std::array<Vector2d, 3> d_first = {Vector2d(0.1, 0.2), Vector2d(-0.3, 0.1), Vector2d(0.2, 0.4)};
  std::array<Vector2d, 3> d_second = {Vector2d(0.2, -0.1), Vector2d(0.1, 0.3), Vector2d(-0.2, 0.1)};
  Vector12 x() const {
    Vector12 x;
    x << 0.0, 0.0, 0.0, 0.1, 0.0, 0.0, 0.05, 0.08, 0.0, 0.04, -0.07, 0.04;
    return x;
  }
  HingeRest rest(double h) const {
    return hinge_rest(moved(first, d_first, h), moved(second, d_second, h), 0.3);
  }
};

TEST(RestDerivative, HingeRestData) {
  const HingeCase c;
  const HingeRest exact = hinge_rest_derivative(c.first, c.second, c.d_first, c.d_second);
  const auto weight = [&](double h) { return Eigen::Matrix<double, 1, 1>(c.rest(h).weight); };
  EXPECT_NEAR(central(weight, 1e-6)(0), exact.weight, 1e-7 * std::abs(exact.weight));
  const auto quadratic = [&](double h) { return c.rest(h).quadratic; };
  EXPECT_LT(relative_error(central(quadratic, 1e-6), exact.quadratic), 1e-7);
}

TEST(RestDerivative, HingeForces) {
  const HingeCase c;
  const HingeRest delta = hinge_rest_derivative(c.first, c.second, c.d_first, c.d_second);
  for (const BendingModel model : {BendingModel::discrete_shell, BendingModel::quadratic}) {
    const Vector12 exact = bending_rest_derivative(model, 2e-3, c.rest(0.0), delta, c.x());
    const auto force = [&](double h) {
      return bending(model, 2e-3, c.rest(h), c.x(), Want::gradient).gradient;
    };
    EXPECT_LT(relative_error(central(force, 1e-6), exact), 1e-7) << model.index();
  }
}

// An irregular patch with its own slopes (as tests/element/test_patch_bending.cpp),
// curved, with a rest curvature; the change of its rest data is arbitrary.
TEST(RestDerivative, PatchForces) {
  const std::array<Vector2d, 3> triangle = {Vector2d(0.0, 0.0), Vector2d(1.0, 0.1),
                                            Vector2d(0.3, 0.9)};
  const BendingRigidity rigidity{2.0, 1.5, 0.4, 0.6};
  const auto own =
      midedge_slopes(triangle, {Vector2d(1.1, 1.0), Vector2d(-0.6, 0.4), Vector2d(0.6, -0.8)},
                     {true, true, true}, rigidity);
  std::array<Eigen::Matrix<double, 1, 12>, 3> slopes;
  for (std::size_t k = 0; k < 3; ++k) {
    slopes[k].setZero();
    slopes[k].head<6>() = own[k];
    slopes[k].tail<6>() = 0.1 * own[k];
  }
  const PatchRest rest = patch_rest(triangle, slopes, rigidity, Vector3d(0.1, -0.2, 0.05));
  PatchRestChange delta;
  delta.area = 0.3;
  delta.weights = Eigen::Matrix<double, 3, 12>::Random();
  Vector36 x;
  for (int i = 0; i < 12; ++i) {
    const double u = 0.1 * i, v = 0.07 * i * i - 0.3;
    x.segment<3>(3 * i) = Vector3d(u + 0.02 * v, v, 0.3 * u * u - 0.2 * u * v + 0.1 * v * v);
  }
  const Vector36 exact = patch_bending_rest_derivative(rest, delta, x);
  const auto force = [&](double h) {
    PatchRest r = rest;
    r.area += h * delta.area;
    r.weights += h * delta.weights;
    return patch_bending(r, x, Want::gradient).gradient;
  };
  EXPECT_LT(relative_error(central(force, 1e-6), exact), 1e-7);
}

// A patch's rest data (edge slopes, curvature weights, area) as one vector,
// on either scalar.
template <typename Scalar>
Eigen::Matrix<Scalar, Eigen::Dynamic, 1>
patch_data(const PatchTriangle<Scalar>& triangle, const PatchTriangle<Scalar>& across,
           const std::array<bool, 3>& has_node, const BendingRigidity& rigidity) {
  const EdgeSlopes<Scalar> own = midedge_slopes(triangle, across, has_node, rigidity);
  std::array<Eigen::Matrix<Scalar, 1, 12>, 3> twelve;
  for (std::size_t k = 0; k < 3; ++k) {
    twelve[k].setZero();
    twelve[k].template head<6>() = own[k];
    twelve[k].template tail<6>() = 0.3 * own[(k + 1) % 3]; // as a neighbour's share
  }
  const PatchWeights<Scalar> weights = patch_weights(triangle, twelve);
  Eigen::Matrix<Scalar, Eigen::Dynamic, 1> data(18 + 36 + 1);
  for (std::size_t k = 0; k < 3; ++k)
    data.template segment<6>(6 * long(k)) = own[k].transpose();
  data.template segment<36>(18) = weights.weights.reshaped();
  data(54) = weights.area;
  return data;
}

PatchTriangle<AutoDiff> carrying(const std::array<Vector2d, 3>& uv,
                                 const std::array<Vector2d, 3>& change) {
  PatchTriangle<AutoDiff> points;
  for (std::size_t i = 0; i < 3; ++i)
    points[i] = {seeded(uv[i].x(), change[i].x()), seeded(uv[i].y(), change[i].y())};
  return points;
}

// The patch geometry run on AutoDiff against central differences
// (Richardson-extrapolated) of it on double, for patches with three nodes
// across, with a boundary edge (the free-edge row), and with six nodes near
// a conic (an ellipse), where the edge system is nearly singular and is
// solved with its Tikhonov term.
TEST(RestDerivative, PatchRestDataMatchesDifferences) {
  const auto ellipse = [](double degrees, double stretch) {
    const double a = degrees * M_PI / 180.0;
    return Vector2d(0.05 * stretch * std::cos(a), 0.03 * stretch * std::sin(a));
  };
  struct Case {
    const char* name;
    std::array<Vector2d, 3> triangle, across;
    std::array<bool, 3> has_node;
  };
  const std::array<Vector2d, 3> triangle = {Vector2d(0.0, 0.0), Vector2d(0.1, 0.01),
                                            Vector2d(0.03, 0.09)};
  const std::array<Vector2d, 3> across = {Vector2d(0.11, 0.1), Vector2d(-0.06, 0.04),
                                          Vector2d(0.06, -0.08)};
  const std::vector<Case> cases = {{"three nodes across", triangle, across, {true, true, true}},
                                   {"a boundary edge", triangle, across, {true, false, true}},
                                   {"near a conic",
                                    {ellipse(10, 1), ellipse(130, 1), ellipse(250, 1)},
                                    {ellipse(190, 1.002), ellipse(310, 1), ellipse(70, 1)},
                                    {true, true, true}}};
  const BendingRigidity rigidity{2.0, 1.5, 0.4, 0.6};
  const std::array<Vector2d, 3> d_across = {Vector2d(-0.3, 0.2), Vector2d(0.1, 0.6),
                                            Vector2d(0.4, -0.5)};
  for (const Case& c : cases) {
    const auto data = [&](double h) {
      return patch_data<double>(moved(c.triangle, triangle_change, h), moved(c.across, d_across, h),
                                c.has_node, rigidity);
    };
    const double h = 1e-6;
    const Eigen::VectorXd difference = (4.0 * central(data, 0.5 * h) - central(data, h)) / 3.0;
    const Eigen::VectorXd exact = derivatives(patch_data<AutoDiff>(
        carrying(c.triangle, triangle_change), carrying(c.across, d_across), c.has_node, rigidity));
    EXPECT_LT(relative_error(difference, exact), 1e-7) << c.name;
  }
}

TEST(RestDerivative, SeamSprings) {
  Eigen::Matrix<double, 9, 1> x;
  x << 0.1, 0.2, 0.3, 0.0, 0.05, 0.25, 0.02, 0.3, 0.31;
  const double k = 500.0, s = 0.3, dk = 40.0, ds = 0.2;
  const auto edge = [&](double h) {
    return seam_vertex_edge(k + h * dk, s + h * ds, x, Want::gradient).gradient;
  };
  EXPECT_LT(relative_error(central(edge, 1e-6), seam_vertex_edge_rest_derivative(k, s, dk, ds, x)),
            1e-7);
  const Eigen::Matrix<double, 6, 1> y = x.head<6>();
  const auto pair = [&](double h) {
    return seam_vertex_vertex(k + h * dk, y, Want::gradient).gradient;
  };
  EXPECT_LT(relative_error(central(pair, 1e-6), seam_vertex_vertex_rest_derivative(dk, y)), 1e-7);
}

} // namespace
} // namespace sartor::element
