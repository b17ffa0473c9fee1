// Physical checks of the membrane triangle: rest data, rigid motions, the
// unloaded state after creep, uniaxial and patch tests against the analytic
// tension, degenerate current shapes and compression stabilisation.

#include "element/membrane.hpp"

#include "common/error.hpp"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include <cmath>
#include <limits>
#include <string>

namespace sartor::element {
namespace {

using Eigen::Vector2d;
using Eigen::Vector3d;

constexpr double nan = std::numeric_limits<double>::quiet_NaN();
const double k_warp = 32600.0; // N/m
const double k_weft = 21000.0; // N/m

MembraneMaterial linear_material(double shear_modulus, double poisson) {
  return {TensionCurve::linear(k_warp, "warp"), TensionCurve::linear(k_weft, "weft"), shear_modulus,
          poisson};
}

constexpr MembraneModel both_models[] = {MembraneModel::baraff_witkin,
                                         MembraneModel::saint_venant_kirchhoff};

std::string name(MembraneModel model) {
  return model == MembraneModel::baraff_witkin ? "Baraff-Witkin" : "StVK";
}

// Positions of the material points uv mapped by x = t + R [map (u, v)].
Vector9 place(const std::array<Vector2d, 3>& uv, const Eigen::Matrix<double, 3, 2>& map,
              const Eigen::Matrix3d& rotation = Eigen::Matrix3d::Identity(),
              const Vector3d& shift = Vector3d::Zero()) {
  Vector9 x;
  for (int i = 0; i < 3; ++i) {
    x.segment<3>(3 * i) = shift + rotation * map * uv[static_cast<std::size_t>(i)];
  }
  return x;
}

Eigen::Matrix<double, 3, 2> stretch_map(double su, double sv, double shear = 0.0) {
  Eigen::Matrix<double, 3, 2> map = Eigen::Matrix<double, 3, 2>::Zero();
  map(0, 0) = su;
  map(0, 1) = shear;
  map(1, 1) = sv;
  return map;
}

// --- rest data -------------------------------------------------------------------

TEST(TriangleRest, AreaAndInverseMaterialMatrix) {
  const std::array<Vector2d, 3> uv{Vector2d(1.0, 2.0), Vector2d(1.3, 2.0), Vector2d(1.1, 2.2)};
  const TriangleRest rest = triangle_rest(uv);
  EXPECT_NEAR(rest.area, 0.5 * 0.3 * 0.2, 1e-15);
  Eigen::Matrix2d material;
  material << 0.3, 0.1, 0.0, 0.2;
  EXPECT_LT((rest.inverse_material * material - Eigen::Matrix2d::Identity()).norm(), 1e-14);
}

TEST(TriangleRest, ClockwiseTriangleHasPositiveArea) {
  const std::array<Vector2d, 3> uv{Vector2d(0.0, 0.0), Vector2d(0.0, 0.1), Vector2d(0.1, 0.0)};
  EXPECT_NEAR(triangle_rest(uv).area, 0.005, 1e-15);
}

TEST(TriangleRest, DegenerateTrianglesAreRejected) {
  const Vector2d a(0.0, 0.0), b(0.1, 0.0);
  EXPECT_THROW(triangle_rest({a, b, Vector2d(0.2, 0.0)}), InputError); // collinear
  EXPECT_THROW(triangle_rest({a, a, b}), InputError);                  // coincident
  EXPECT_THROW(triangle_rest({a, b, Vector2d(nan, 0.1)}), InputError); // not a number
  try {
    triangle_rest({a, b, Vector2d(0.05, 0.0)});
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("degenerate triangle"), std::string::npos);
  }
}

// --- rigid motions -----------------------------------------------------------------

TEST(Membrane, RigidMotionsStoreNoEnergy) {
  const std::array<Vector2d, 3> uv{Vector2d(0.3, 0.1), Vector2d(0.31, 0.102),
                                   Vector2d(0.302, 0.109)};
  const TriangleRest rest = triangle_rest(uv);
  const MembraneMaterial material = linear_material(700.0, 0.3);
  const Eigen::Matrix3d rotation =
      Eigen::AngleAxisd(1.1, Vector3d(0.3, -0.5, 0.8).normalized()).toRotationMatrix();
  for (const MembraneModel model : both_models) {
    for (const NonelasticStrain creep :
         {NonelasticStrain{0.0, 0.0}, NonelasticStrain{0.06, 0.02}}) {
      SCOPED_TRACE(name(model) + ", creep " + std::to_string(creep.warp));
      // The unloaded shape (material lengths times 1 + n), rotated and moved.
      const Vector9 x = place(uv, stretch_map(1.0 + creep.warp, 1.0 + creep.weft), rotation,
                              Vector3d(0.4, -2.0, 1.5));
      const Result<9> r = membrane(model, material, rest, creep, x, Want::hessian);
      EXPECT_LT(std::abs(r.energy), 1e-14);
      EXPECT_LT(r.gradient.cwiseAbs().maxCoeff(), 1e-9);
      // The Hessian is positive semi-definite there, with the six rigid modes
      // (three translations, three rotations) in its null space.
      const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 9, 9>> eigen(r.hessian);
      const double largest = eigen.eigenvalues().maxCoeff();
      EXPECT_GT(eigen.eigenvalues().minCoeff(), -1e-10 * largest);
      EXPECT_LT(std::abs(eigen.eigenvalues()(5)), 1e-10 * largest);
      EXPECT_GT(eigen.eigenvalues()(6), 1e-6 * largest);
    }
  }
}

TEST(Membrane, RotatingADeformedTriangleChangesNoStrain) {
  const std::array<Vector2d, 3> uv{Vector2d(0.0, 0.0), Vector2d(0.01, 0.0), Vector2d(0.0, 0.01)};
  const TriangleRest rest = triangle_rest(uv);
  const MembraneMaterial material = linear_material(700.0, 0.3);
  const NonelasticStrain creep{0.03, 0.01};
  const Eigen::Matrix3d rotation =
      Eigen::AngleAxisd(2.3, Vector3d(1.0, 2.0, -0.5).normalized()).toRotationMatrix();
  for (const MembraneModel model : both_models) {
    SCOPED_TRACE(name(model));
    const Vector9 x = place(uv, stretch_map(1.08, 0.95, 0.1));
    const Vector9 moved = place(uv, stretch_map(1.08, 0.95, 0.1), rotation, Vector3d(1, 2, 3));
    const Result<9> a = membrane(model, material, rest, creep, x, Want::gradient);
    const Result<9> b = membrane(model, material, rest, creep, moved, Want::gradient);
    EXPECT_NEAR(b.energy, a.energy, 1e-12 * a.energy);
    for (int i = 0; i < 3; ++i) {
      const Vector3d expected = rotation * a.gradient.segment<3>(3 * i);
      EXPECT_LT((b.gradient.segment<3>(3 * i) - expected).norm(),
                1e-10 * a.gradient.cwiseAbs().maxCoeff());
    }
    // Internal forces are in equilibrium: no net force.
    const Vector3d net =
        a.gradient.segment<3>(0) + a.gradient.segment<3>(3) + a.gradient.segment<3>(6);
    EXPECT_LT(net.norm(), 1e-10 * a.gradient.cwiseAbs().maxCoeff());
  }
}

// --- uniaxial stretch and creep -------------------------------------------------

TEST(Membrane, UniaxialBaraffWitkinTensionIsModulusTimesStrain) {
  const double length = 0.02, height = 0.01;
  const std::array<Vector2d, 3> uv{Vector2d(0.0, 0.0), Vector2d(length, 0.0),
                                   Vector2d(0.0, height)};
  const TriangleRest rest = triangle_rest(uv);
  const MembraneMaterial material = linear_material(0.0, 0.0);
  for (const double stretch : {0.9, 1.0, 1.01, 1.05, 1.2}) {
    const Vector9 x = place(uv, stretch_map(stretch, 1.0));
    const MembraneStrain s = membrane_strain(MembraneModel::baraff_witkin, material, rest, {}, x);
    EXPECT_NEAR(s.warp, stretch - 1.0, 1e-14);
    EXPECT_NEAR(s.tension_warp, k_warp * (stretch - 1.0), 1e-9);
    EXPECT_NEAR(s.weft, 0.0, 1e-14);
    EXPECT_NEAR(s.tension_weft, 0.0, 1e-9);
    const Result<9> r = membrane(MembraneModel::baraff_witkin, material, rest, {}, x, Want::energy);
    EXPECT_NEAR(r.energy, rest.area * 0.5 * k_warp * (stretch - 1.0) * (stretch - 1.0),
                1e-12 * rest.area * k_warp);
  }
}

TEST(Membrane, CreepMovesTheUnloadedStateToOnePlusN) {
  const double length = 0.02, height = 0.01;
  const std::array<Vector2d, 3> uv{Vector2d(0.0, 0.0), Vector2d(length, 0.0),
                                   Vector2d(0.0, height)};
  const TriangleRest rest = triangle_rest(uv);
  const MembraneMaterial material = linear_material(0.0, 0.0);
  const NonelasticStrain creep{0.075, 0.0};
  // Unloaded at |w_u| = 1 + n: no energy, no force.
  const Vector9 unloaded = place(uv, stretch_map(1.0 + creep.warp, 1.0));
  const Result<9> r0 =
      membrane(MembraneModel::baraff_witkin, material, rest, creep, unloaded, Want::gradient);
  EXPECT_LT(std::abs(r0.energy), 1e-16);
  EXPECT_LT(r0.gradient.cwiseAbs().maxCoeff(), 1e-10);
  // Stretched 4 % beyond the unloaded length: tension k e, energy per
  // unloaded area.
  const double e = 0.04;
  const Vector9 x = place(uv, stretch_map((1.0 + creep.warp) * (1.0 + e), 1.0));
  const MembraneStrain s = membrane_strain(MembraneModel::baraff_witkin, material, rest, creep, x);
  EXPECT_NEAR(s.warp, e, 1e-14);
  EXPECT_NEAR(s.tension_warp, k_warp * e, 1e-9);
  const Result<9> r =
      membrane(MembraneModel::baraff_witkin, material, rest, creep, x, Want::gradient);
  EXPECT_NEAR(r.energy, rest.area * (1.0 + creep.warp) * 0.5 * k_warp * e * e, 1e-15);
  // Without creep the same shape is 11.8 % stretched.
  const MembraneStrain elastic =
      membrane_strain(MembraneModel::baraff_witkin, material, rest, {}, x);
  EXPECT_NEAR(elastic.warp, (1.0 + creep.warp) * (1.0 + e) - 1.0, 1e-14);
}

TEST(Membrane, PiecewiseCurvesGiveTheCurveTension) {
  // Kinks at strains 0.01, 0.03 and 0.05: the stretches below reach each segment.
  const TensionCurve warp =
      TensionCurve::piecewise({{0.01, 100.0}, {0.03, 900.0}, {0.05, 2900.0}}, "warp");
  const MembraneMaterial material{warp, TensionCurve::linear(k_weft, "weft"), 0.0, 0.0};
  const std::array<Vector2d, 3> uv{Vector2d(0.0, 0.0), Vector2d(0.02, 0.0), Vector2d(0.0, 0.01)};
  const TriangleRest rest = triangle_rest(uv);
  const NonelasticStrain creep{0.02, 0.0};
  for (const double e : {-0.01, 0.005, 0.02, 0.04, 0.07}) {
    const double lu = (1.0 + creep.warp) * (1.0 + e);
    const Vector9 x = place(uv, stretch_map(lu, 1.0));
    const MembraneStrain bw =
        membrane_strain(MembraneModel::baraff_witkin, material, rest, creep, x);
    EXPECT_NEAR(bw.tension_warp, warp.tension(e), 1e-9);
    const double e11 = 0.5 * ((1.0 + e) * (1.0 + e) - 1.0);
    const MembraneStrain stvk =
        membrane_strain(MembraneModel::saint_venant_kirchhoff, material, rest, creep, x);
    EXPECT_NEAR(stvk.warp, e11, 1e-14);
    EXPECT_NEAR(stvk.tension_warp, warp.tension(e11) * (1.0 + e), 1e-9);
    const Result<9> r =
        membrane(MembraneModel::saint_venant_kirchhoff, material, rest, creep, x, Want::energy);
    EXPECT_NEAR(r.energy, rest.area * (1.0 + creep.warp) * warp.energy_density(e11), 1e-15);
  }
}

// --- patch test ------------------------------------------------------------------

// A rectangle of two triangles under uniform stretch (su, sv) of its material
// shape: the internal forces on the right edge add up to the warp tension
// times the unloaded width, those on the top edge to the weft tension times
// the unloaded length; the element tensions are the analytic ones.
struct PatchResult {
  double right_force = 0.0; // N, sum over the right edge of d energy / d x
  double top_force = 0.0;   // N, sum over the top edge of d energy / d y
  double energy = 0.0;
  MembraneStrain strain;
};

PatchResult patch(MembraneModel model, const MembraneMaterial& material,
                  const NonelasticStrain& creep, double su, double sv, double length,
                  double height) {
  const std::array<Vector2d, 4> corners{Vector2d(0.0, 0.0), Vector2d(length, 0.0),
                                        Vector2d(length, height), Vector2d(0.0, height)};
  const std::array<std::array<int, 3>, 2> triangles{{{0, 1, 2}, {0, 2, 3}}};
  Eigen::Matrix<double, 12, 1> gradient = Eigen::Matrix<double, 12, 1>::Zero();
  PatchResult p;
  for (const auto& t : triangles) {
    const std::array<Vector2d, 3> uv{corners[static_cast<std::size_t>(t[0])],
                                     corners[static_cast<std::size_t>(t[1])],
                                     corners[static_cast<std::size_t>(t[2])]};
    const TriangleRest rest = triangle_rest(uv);
    const Vector9 x = place(uv, stretch_map(su, sv));
    const Result<9> r = membrane(model, material, rest, creep, x, Want::gradient);
    p.energy += r.energy;
    for (int i = 0; i < 3; ++i)
      gradient.segment<3>(3 * t[static_cast<std::size_t>(i)]) += r.gradient.segment<3>(3 * i);
    p.strain = membrane_strain(model, material, rest, creep, x);
  }
  p.right_force = gradient(3 * 1 + 0) + gradient(3 * 2 + 0);
  p.top_force = gradient(3 * 2 + 1) + gradient(3 * 3 + 1);
  return p;
}

TEST(Membrane, PatchTestBaraffWitkin) {
  const double length = 0.03, height = 0.02;
  const MembraneMaterial material = linear_material(900.0, 0.0);
  for (const NonelasticStrain creep : {NonelasticStrain{0.0, 0.0}, NonelasticStrain{0.05, 0.02}}) {
    const double su = 1.06, sv = 1.03;
    const double eu = su / (1.0 + creep.warp) - 1.0;
    const double ev = sv / (1.0 + creep.weft) - 1.0;
    const PatchResult p =
        patch(MembraneModel::baraff_witkin, material, creep, su, sv, length, height);
    EXPECT_NEAR(p.strain.warp, eu, 1e-14);
    EXPECT_NEAR(p.strain.weft, ev, 1e-14);
    EXPECT_NEAR(p.strain.shear, 0.0, 1e-14);
    EXPECT_NEAR(p.strain.tension_warp, k_warp * eu, 1e-9);
    EXPECT_NEAR(p.strain.tension_weft, k_weft * ev, 1e-9);
    EXPECT_NEAR(p.right_force, k_warp * eu * height * (1.0 + creep.weft), 1e-11);
    EXPECT_NEAR(p.top_force, k_weft * ev * length * (1.0 + creep.warp), 1e-11);
    const double unloaded_area = length * height * (1.0 + creep.warp) * (1.0 + creep.weft);
    EXPECT_NEAR(p.energy, unloaded_area * 0.5 * (k_warp * eu * eu + k_weft * ev * ev), 1e-14);
  }
}

TEST(Membrane, PatchTestSaintVenantKirchhoff) {
  const double length = 0.03, height = 0.02;
  const double poisson = 0.3;
  const MembraneMaterial material = linear_material(900.0, poisson);
  const double c12 = poisson * std::sqrt(k_warp * k_weft);
  for (const NonelasticStrain creep : {NonelasticStrain{0.0, 0.0}, NonelasticStrain{0.05, 0.02}}) {
    const double su = 1.06, sv = 1.03;
    const double lu = su / (1.0 + creep.warp), lv = sv / (1.0 + creep.weft);
    const double e11 = 0.5 * (lu * lu - 1.0), e22 = 0.5 * (lv * lv - 1.0);
    const double tension_warp = (k_warp * e11 + c12 * e22) * lu;
    const double tension_weft = (k_weft * e22 + c12 * e11) * lv;
    const PatchResult p =
        patch(MembraneModel::saint_venant_kirchhoff, material, creep, su, sv, length, height);
    EXPECT_NEAR(p.strain.warp, e11, 1e-14);
    EXPECT_NEAR(p.strain.weft, e22, 1e-14);
    EXPECT_NEAR(p.strain.tension_warp, tension_warp, 1e-9);
    EXPECT_NEAR(p.strain.tension_weft, tension_weft, 1e-9);
    EXPECT_NEAR(p.right_force, tension_warp * height * (1.0 + creep.weft), 1e-11);
    EXPECT_NEAR(p.top_force, tension_weft * length * (1.0 + creep.warp), 1e-11);
    const double unloaded_area = length * height * (1.0 + creep.warp) * (1.0 + creep.weft);
    EXPECT_NEAR(p.energy,
                unloaded_area *
                    (0.5 * k_warp * e11 * e11 + 0.5 * k_weft * e22 * e22 + c12 * e11 * e22),
                1e-14);
  }
}

TEST(Membrane, SimpleShearStoresTheShearEnergy) {
  const std::array<Vector2d, 3> uv{Vector2d(0.0, 0.0), Vector2d(0.01, 0.0), Vector2d(0.0, 0.01)};
  const TriangleRest rest = triangle_rest(uv);
  const double shear_modulus = 900.0;
  const MembraneMaterial material = linear_material(shear_modulus, 0.0);
  // Pure shear rotation of both axes by +-gamma/2 keeps the fibres unstretched.
  const double gamma = 0.1;
  Eigen::Matrix<double, 3, 2> map = Eigen::Matrix<double, 3, 2>::Zero();
  map(0, 0) = std::cos(gamma / 2);
  map(1, 0) = std::sin(gamma / 2);
  map(0, 1) = std::sin(gamma / 2);
  map(1, 1) = std::cos(gamma / 2);
  const Vector9 x = place(uv, map);
  const double g = std::sin(gamma); // (F e1).(F e2)
  for (const MembraneModel model : both_models) {
    SCOPED_TRACE(name(model));
    const MembraneStrain s = membrane_strain(model, material, rest, {}, x);
    EXPECT_NEAR(s.shear, g, 1e-14);
    EXPECT_NEAR(s.warp, 0.0, 1e-14);
    EXPECT_NEAR(s.weft, 0.0, 1e-14);
    const Result<9> r = membrane(model, material, rest, {}, x, Want::energy);
    EXPECT_NEAR(r.energy, rest.area * 0.5 * shear_modulus * g * g, 1e-15);
  }
}

// --- robustness and options -------------------------------------------------------

TEST(Membrane, DegenerateCurrentTrianglesGiveFiniteResults) {
  const std::array<Vector2d, 3> uv{Vector2d(0.0, 0.0), Vector2d(0.01, 0.0), Vector2d(0.0, 0.01)};
  const TriangleRest rest = triangle_rest(uv);
  const MembraneMaterial material = linear_material(900.0, 0.3);
  Vector9 collapsed;
  collapsed << 0.1, 0.2, 0.3, 0.1, 0.2, 0.3, 0.1, 0.2, 0.3;
  // Warp fibre of zero length, weft fibre stretched.
  const Vector9 no_warp = place(uv, stretch_map(0.0, 1.1));
  for (const MembraneModel model : both_models) {
    for (const Vector9& x : {collapsed, no_warp}) {
      SCOPED_TRACE(name(model));
      const Result<9> r = membrane(model, material, rest, {0.02, 0.01}, x, Want::hessian);
      EXPECT_TRUE(std::isfinite(r.energy));
      EXPECT_GT(r.energy, 0.0);
      EXPECT_TRUE(r.gradient.allFinite());
      EXPECT_TRUE(r.hessian.allFinite());
      const MembraneStrain s = membrane_strain(model, material, rest, {0.02, 0.01}, x);
      EXPECT_TRUE(std::isfinite(s.tension_warp) && std::isfinite(s.tension_weft));
    }
  }
}

TEST(Membrane, WantSelectsWhatIsComputed) {
  const std::array<Vector2d, 3> uv{Vector2d(0.0, 0.0), Vector2d(0.01, 0.002),
                                   Vector2d(0.001, 0.01)};
  const TriangleRest rest = triangle_rest(uv);
  const MembraneMaterial material = linear_material(900.0, 0.3);
  const Vector9 x = place(uv, stretch_map(1.05, 0.97, 0.08));
  for (const MembraneModel model : both_models) {
    const Result<9> e = membrane(model, material, rest, {0.01, 0.0}, x, Want::energy);
    const Result<9> g = membrane(model, material, rest, {0.01, 0.0}, x, Want::gradient);
    const Result<9> h = membrane(model, material, rest, {0.01, 0.0}, x, Want::hessian);
    EXPECT_EQ(e.energy, h.energy);
    EXPECT_EQ(g.energy, h.energy);
    EXPECT_EQ(g.gradient, h.gradient);
    EXPECT_TRUE(e.gradient.isZero(0.0));
    EXPECT_TRUE(g.hessian.isZero(0.0));
    EXPECT_FALSE(h.hessian.isZero(0.0));
  }
}

// Sensitive Couture's stabilisation: a compressed StVK element has an
// indefinite Hessian; the projection makes it positive semi-definite and
// leaves a stretched element's Hessian alone when it is already so.
TEST(Membrane, CompressedStVKHessianIsIndefiniteUntilProjected) {
  const std::array<Vector2d, 3> uv{Vector2d(0.0, 0.0), Vector2d(0.01, 0.0), Vector2d(0.0, 0.01)};
  const TriangleRest rest = triangle_rest(uv);
  const MembraneMaterial material = linear_material(900.0, 0.3);
  const Vector9 x = place(uv, stretch_map(0.8, 0.85));
  Eigen::Matrix<double, 9, 9> hessian =
      membrane(MembraneModel::saint_venant_kirchhoff, material, rest, {}, x, Want::hessian).hessian;
  const double largest = hessian.cwiseAbs().maxCoeff();
  using Solver = Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 9, 9>>;
  EXPECT_LT(Solver(hessian).eigenvalues().minCoeff(), -1e-3 * largest);
  project_to_psd<9>(hessian);
  EXPECT_GT(Solver(hessian).eigenvalues().minCoeff(), -1e-12 * largest);
}

} // namespace
} // namespace sartor::element
