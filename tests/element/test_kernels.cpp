// Derivative checks of every element kernel: the analytic gradient against
// central differences of the energy, the Hessian (or Jacobian) against
// central differences of the gradient (or force), at random configurations.

#include "element/bending.hpp"
#include "element/membrane.hpp"
#include "element/pressure.hpp"
#include "finite_difference.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>
#include <random>
#include <string>
#include <vector>

namespace sartor::element {
namespace {

using testing::numeric_gradient;
using testing::numeric_jacobian;
using testing::relative_error;
using Matrix9 = Eigen::Matrix<double, 9, 9>;
using Matrix12 = Eigen::Matrix<double, 12, 12>;

constexpr double relative_step = 1e-6;
constexpr double tolerance = 1e-6;

Eigen::Matrix3d random_rotation(std::mt19937& random) {
  std::normal_distribution<double> normal;
  Eigen::Quaterniond q(normal(random), normal(random), normal(random), normal(random));
  return q.normalized().toRotationMatrix();
}

double uniform(std::mt19937& random, double low, double high) {
  return std::uniform_real_distribution<double>(low, high)(random);
}

// Kinks at strains 0.01, 0.03 and 0.05 (slopes 1e4, 4e4, 1e5 N/m).
TensionCurve kinked_warp() {
  return TensionCurve::piecewise({{0.01, 100.0}, {0.03, 900.0}, {0.05, 2900.0}}, "test warp");
}
TensionCurve kinked_weft() {
  return TensionCurve::piecewise({{0.02, 100.0}, {0.04, 500.0}}, "test weft");
}
const std::vector<double> kinks{0.0, 0.01, 0.02, 0.03, 0.04, 0.05};

bool near_a_kink(double strain) {
  for (const double k : kinks) {
    if (std::abs(strain - k) < 1e-3) return true;
  }
  return false;
}

MembraneMaterial material(bool kinked) {
  if (kinked) return {kinked_warp(), kinked_weft(), 800.0, 0.3};
  return {TensionCurve::linear(32600.0, "warp"), TensionCurve::linear(21000.0, "weft"), 650.0,
          0.25};
}

enum class State { stretched, compressed, sheared, mixed };

const char* state_name(State state) {
  switch (state) {
  case State::stretched:
    return "stretched";
  case State::compressed:
    return "compressed";
  case State::sheared:
    return "sheared";
  case State::mixed:
    return "mixed";
  }
  return "";
}

struct MembraneCase {
  TriangleRest rest;
  NonelasticStrain nonelastic;
  Vector9 x;
  double size = 0.0; // m
};

// A well-shaped material triangle about 1 cm across, deformed by an in-plane
// map of the state's kind after the creep shift, then rotated, moved and
// perturbed off the affine map.
MembraneCase membrane_case(std::mt19937& random, State state, bool creep) {
  MembraneCase c;
  std::array<Eigen::Vector2d, 3> uv;
  for (;;) {
    uv[0] = Eigen::Vector2d(uniform(random, 0.0, 0.5), uniform(random, 0.0, 0.5));
    const double angle = uniform(random, 0.0, 6.3);
    for (int i = 1; i < 3; ++i) {
      const double a = angle + (i - 1) * uniform(random, 1.0, 1.7);
      uv[i] = uv[0] + uniform(random, 0.008, 0.012) * Eigen::Vector2d(std::cos(a), std::sin(a));
    }
    const double area = 0.5 * std::abs((uv[1] - uv[0]).x() * (uv[2] - uv[0]).y() -
                                       (uv[1] - uv[0]).y() * (uv[2] - uv[0]).x());
    if (area > 2e-5) break;
  }
  c.rest = triangle_rest(uv);
  c.size = 0.01;
  if (creep) c.nonelastic = {uniform(random, 0.0, 0.08), uniform(random, -0.02, 0.05)};

  double su = 1.0, sv = 1.0, shear = 0.0;
  switch (state) {
  case State::stretched:
    su = uniform(random, 1.005, 1.12);
    sv = uniform(random, 1.005, 1.08);
    shear = uniform(random, -0.02, 0.02);
    break;
  case State::compressed:
    su = uniform(random, 0.6, 0.98);
    sv = uniform(random, 0.6, 0.98);
    shear = uniform(random, -0.02, 0.02);
    break;
  case State::sheared:
    su = uniform(random, 0.98, 1.03);
    sv = uniform(random, 0.98, 1.03);
    shear = uniform(random, 0.15, 0.5) * (uniform(random, -1.0, 1.0) < 0.0 ? -1.0 : 1.0);
    break;
  case State::mixed:
    su = uniform(random, 0.7, 1.1);
    sv = uniform(random, 0.7, 1.1);
    shear = uniform(random, -0.4, 0.4);
    break;
  }
  Eigen::Matrix<double, 3, 2> map = Eigen::Matrix<double, 3, 2>::Zero();
  map(0, 0) = su * (1.0 + c.nonelastic.warp);
  map(0, 1) = shear * (1.0 + c.nonelastic.weft);
  map(1, 1) = sv * (1.0 + c.nonelastic.weft);
  const Eigen::Matrix3d rotation = random_rotation(random);
  const Eigen::Vector3d shift(uniform(random, -1.0, 1.0), uniform(random, -1.0, 1.0),
                              uniform(random, -1.0, 1.0));
  for (int i = 0; i < 3; ++i) {
    const Eigen::Vector3d noise(uniform(random, -1.0, 1.0), uniform(random, -1.0, 1.0),
                                uniform(random, -1.0, 1.0));
    c.x.segment<3>(3 * i) =
        shift + rotation * map * uv[static_cast<std::size_t>(i)] + 0.02 * c.size * noise;
  }
  return c;
}

void check_membrane_derivatives(MembraneModel model, bool kinked, const std::string& label) {
  std::mt19937 random(kinked ? 11 : 7);
  const MembraneMaterial mat = material(kinked);
  for (const State state : {State::stretched, State::compressed, State::sheared, State::mixed}) {
    for (const bool creep : {false, true}) {
      for (int sample = 0; sample < 10;) {
        const MembraneCase c = membrane_case(random, state, creep);
        const MembraneStrain strain = membrane_strain(model, mat, c.rest, c.nonelastic, c.x);
        if (kinked && (near_a_kink(strain.warp) || near_a_kink(strain.weft))) continue;
        ++sample;
        SCOPED_TRACE(label + ", " + state_name(state) + (creep ? ", creep" : "") + ", sample " +
                     std::to_string(sample));
        const auto energy = [&](const Vector9& y) {
          return membrane(model, mat, c.rest, c.nonelastic, y, Want::energy).energy;
        };
        const auto gradient = [&](const Vector9& y) -> Vector9 {
          return membrane(model, mat, c.rest, c.nonelastic, y, Want::gradient).gradient;
        };
        const Result<9> exact = membrane(model, mat, c.rest, c.nonelastic, c.x, Want::hessian);
        const double step = relative_step * c.size;
        EXPECT_LT(relative_error(numeric_gradient<9>(energy, c.x, step), exact.gradient),
                  tolerance);
        const Matrix9 numeric = numeric_jacobian<9, 9>(gradient, c.x, step);
        EXPECT_LT(relative_error(numeric, exact.hessian), tolerance);
        EXPECT_EQ(exact.hessian, exact.hessian.transpose());
      }
    }
  }
}

TEST(MembraneDerivatives, BaraffWitkinLinearCurves) {
  check_membrane_derivatives(MembraneModel::baraff_witkin, false, "BW linear");
}

TEST(MembraneDerivatives, BaraffWitkinPiecewiseCurves) {
  check_membrane_derivatives(MembraneModel::baraff_witkin, true, "BW piecewise");
}

TEST(MembraneDerivatives, SaintVenantKirchhoffLinearCurves) {
  check_membrane_derivatives(MembraneModel::saint_venant_kirchhoff, false, "StVK linear");
}

TEST(MembraneDerivatives, SaintVenantKirchhoffPiecewiseCurves) {
  check_membrane_derivatives(MembraneModel::saint_venant_kirchhoff, true, "StVK piecewise");
}

// The monolithic creep coupling's sensitivities: tensions against central
// differences of membrane_strain in x and n, the force's n-derivative against
// central differences of membrane()'s gradient in n.
void check_creep_sensitivity(MembraneModel model, bool kinked, const std::string& label) {
  std::mt19937 random(kinked ? 23 : 19);
  const MembraneMaterial mat = material(kinked);
  for (const State state : {State::stretched, State::compressed, State::sheared, State::mixed}) {
    for (int sample = 0; sample < 10;) {
      const MembraneCase c = membrane_case(random, state, true);
      const MembraneStrain strain = membrane_strain(model, mat, c.rest, c.nonelastic, c.x);
      if (kinked && (near_a_kink(strain.warp) || near_a_kink(strain.weft))) continue;
      ++sample;
      SCOPED_TRACE(label + ", " + state_name(state) + ", sample " + std::to_string(sample));
      const MembraneCreepSensitivity exact =
          membrane_creep_sensitivity(model, mat, c.rest, c.nonelastic, c.x);
      EXPECT_EQ(exact.tension, Eigen::Vector2d(strain.tension_warp, strain.tension_weft));

      const auto tension_at = [&](const Vector9& y) -> Eigen::Vector2d {
        const MembraneStrain s = membrane_strain(model, mat, c.rest, c.nonelastic, y);
        return {s.tension_warp, s.tension_weft};
      };
      const double step = relative_step * c.size;
      EXPECT_LT(
          relative_error(numeric_jacobian<2, 9>(tension_at, c.x, step), exact.tension_per_position),
          tolerance);

      const auto with = [&](const Eigen::Vector2d& n) { return NonelasticStrain{n(0), n(1)}; };
      const Eigen::Vector2d n(c.nonelastic.warp, c.nonelastic.weft);
      const auto tension_of_n = [&](const Eigen::Vector2d& m) -> Eigen::Vector2d {
        const MembraneStrain s = membrane_strain(model, mat, c.rest, with(m), c.x);
        return {s.tension_warp, s.tension_weft};
      };
      const auto force_of_n = [&](const Eigen::Vector2d& m) -> Vector9 {
        return membrane(model, mat, c.rest, with(m), c.x, Want::gradient).gradient;
      };
      EXPECT_LT(relative_error(numeric_jacobian<2, 2>(tension_of_n, n, relative_step),
                               exact.tension_per_nonelastic),
                tolerance);
      EXPECT_LT(relative_error(numeric_jacobian<9, 2>(force_of_n, n, relative_step),
                               exact.force_per_nonelastic),
                tolerance);
    }
  }
}

TEST(MembraneCreepSensitivity, BaraffWitkin) {
  check_creep_sensitivity(MembraneModel::baraff_witkin, false, "BW linear");
  check_creep_sensitivity(MembraneModel::baraff_witkin, true, "BW piecewise");
}

TEST(MembraneCreepSensitivity, SaintVenantKirchhoff) {
  check_creep_sensitivity(MembraneModel::saint_venant_kirchhoff, false, "StVK linear");
  check_creep_sensitivity(MembraneModel::saint_venant_kirchhoff, true, "StVK piecewise");
}

// --- bending -------------------------------------------------------------------

struct HingeCase {
  HingeRest rest;
  Vector12 x;
  double size = 0.0;
};

// Two material triangles about 1 cm across sharing an edge, folded by a
// random angle about it, stretched a little, rotated and moved.
HingeCase hinge_case(std::mt19937& random, double rest_angle) {
  const double length = uniform(random, 0.007, 0.013);
  const Eigen::Vector2d u0(0.1, 0.2);
  const Eigen::Vector2d u1 = u0 + Eigen::Vector2d(length, 0.0);
  const Eigen::Vector2d u2 =
      u0 + Eigen::Vector2d(uniform(random, -0.3, 1.3) * length, uniform(random, 0.4, 1.2) * length);
  const Eigen::Vector2d u3 = u0 + Eigen::Vector2d(uniform(random, -0.3, 1.3) * length,
                                                  -uniform(random, 0.4, 1.2) * length);
  HingeCase c;
  c.rest = hinge_rest({u0, u1, u2}, {u1, u0, u3}, rest_angle);
  c.size = length;

  const double fold = uniform(random, -2.6, 2.6);
  const std::array<Eigen::Vector2d, 4> uv{u0, u1, u2, u3};
  const Eigen::Matrix3d rotation = random_rotation(random);
  const Eigen::Vector3d shift(uniform(random, -1.0, 1.0), uniform(random, -1.0, 1.0),
                              uniform(random, -1.0, 1.0));
  for (std::size_t i = 0; i < 4; ++i) {
    const Eigen::Vector2d p = uv[i] - u0;
    Eigen::Vector3d flat(p.x(), p.y(), 0.0);
    if (i == 3) flat = Eigen::Vector3d(p.x(), p.y() * std::cos(fold), p.y() * std::sin(fold));
    const Eigen::Vector3d noise(uniform(random, -1.0, 1.0), uniform(random, -1.0, 1.0),
                                uniform(random, -1.0, 1.0));
    c.x.segment<3>(3 * static_cast<int>(i)) = shift + rotation * (flat + 0.05 * length * noise);
  }
  return c;
}

void check_bending_derivatives(BendingModel model, const std::string& label) {
  std::mt19937 random(3);
  const double stiffness = 2e-5;
  for (int sample = 0; sample < 40; ++sample) {
    const double rest_angle = sample < 10 ? 0.0 : uniform(random, -1.0, 1.0);
    const HingeCase c = hinge_case(random, rest_angle);
    SCOPED_TRACE(label + ", sample " + std::to_string(sample));
    const auto energy = [&](const Vector12& y) {
      return bending(model, stiffness, c.rest, y, Want::energy).energy;
    };
    const auto gradient = [&](const Vector12& y) -> Vector12 {
      return bending(model, stiffness, c.rest, y, Want::gradient).gradient;
    };
    const Result<12> exact = bending(model, stiffness, c.rest, c.x, Want::hessian);
    const double step = relative_step * c.size;
    EXPECT_LT(relative_error(numeric_gradient<12>(energy, c.x, step), exact.gradient), tolerance);
    EXPECT_LT(relative_error(numeric_jacobian<12, 12>(gradient, c.x, step), exact.hessian),
              tolerance);
    EXPECT_EQ(exact.hessian, exact.hessian.transpose());
  }
}

TEST(BendingDerivatives, DiscreteShell) {
  check_bending_derivatives(BendingModel::discrete_shell, "discrete shell");
}

TEST(BendingDerivatives, Quadratic) {
  check_bending_derivatives(BendingModel::quadratic, "quadratic");
}

// --- pressure ------------------------------------------------------------------

TEST(PressureDerivatives, JacobianMatchesFiniteDifferences) {
  std::mt19937 random(5);
  for (int sample = 0; sample < 20; ++sample) {
    Vector9 x;
    for (int i = 0; i < 9; ++i)
      x(i) = uniform(random, -0.01, 0.01);
    const double pressure = uniform(random, -200.0, 200.0);
    const auto force = [&](const Vector9& y) -> Vector9 {
      return follower_pressure(pressure, y).force;
    };
    const PressureLoad exact = follower_pressure(pressure, x);
    SCOPED_TRACE("sample " + std::to_string(sample));
    EXPECT_LT(
        relative_error(numeric_jacobian<9, 9>(force, x, relative_step * 0.01), exact.jacobian),
        tolerance);
  }
}

} // namespace
} // namespace sartor::element
