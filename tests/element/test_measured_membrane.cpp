// The measured membrane model (Wang et al. 2011 table, ARCSim's grid):
// derivatives by finite differences, and the energy of uniaxial stretches
// along the warp, the weft and the bias against the table evaluated here
// (the definition at the grid's nodes, Catmull-Rom cubics between them).

#include "element/membrane.hpp"

#include "common/error.hpp"
#include "finite_difference.hpp"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>

#include <cmath>

namespace sartor::element {
namespace {

using Eigen::Matrix2d;
using Eigen::Vector2d;
using testing::numeric_gradient;
using testing::numeric_jacobian;
using testing::relative_error;

constexpr double pi = 3.14159265358979323846;

StretchingTable made_up() {
  StretchingTable t;
  t.rows = {{{1000, 150, 800, 40},
             {9000, 250, 7000, 120},
             {7000, 230, 5500, 160},
             {4000, 200, 3500, 240},
             {6500, 230, 6000, 160},
             {8000, 250, 7500, 120}}};
  return t;
}

// The definition: largest eigenvalue of I + 2G, its direction's angle to
// the warp, rows every 22.5 degrees, strain weight 6 (w - 1), doubled. Equal
// eigenvalues (grid nodes with G00 = G11, G01 = 0) take the warp's row, as
// ARCSim's eigensolver returns the axes for a multiple of the identity.
Eigen::Vector4d definition(const StretchingTable& t, const Matrix2d& g) {
  Eigen::SelfAdjointEigenSolver<Matrix2d> eigen(Matrix2d::Identity() + 2.0 * g);
  const bool tie = eigen.eigenvalues()[1] - eigen.eigenvalues()[0] < 1e-12;
  const double angle =
      tie ? 0.0 : std::acos(std::min(1.0, std::abs(eigen.eigenvectors().col(1)[0])));
  const double s = std::clamp(6.0 * (std::sqrt(eigen.eigenvalues()[1]) - 1.0), 0.0, 1.0);
  const double position = angle / (pi / 8.0);
  const int low = std::min(int(position), 3);
  const double f = position - low;
  Eigen::Vector4d k;
  for (int i = 0; i < 4; ++i) {
    const auto c = std::size_t(i);
    k[i] = 2.0 *
           std::max(0.0, (1 - s) * t.rows[0][c] + s * ((1 - f) * t.rows[std::size_t(1 + low)][c] +
                                                       f * t.rows[std::size_t(2 + low)][c]));
  }
  return k;
}

// The Catmull-Rom cubic through p0..p3 at t in [0, 1] between p1 and p2.
Eigen::Vector4d catmull_rom(const std::array<Eigen::Vector4d, 4>& p, double t) {
  return p[1] + 0.5 * t * (p[2] - p[0]) + t * t * (p[0] - 2.5 * p[1] + 2.0 * p[2] - 0.5 * p[3]) +
         t * t * t * (1.5 * (p[1] - p[2]) + 0.5 * (p[3] - p[0]));
}

// The grid's lookup: the definition at nodes G00, G11 = -0.25 + i/30,
// |G01| = k/30, interpolated by Catmull-Rom cubics one axis after the
// other; node -1 is node 0 on the G00 and G11 axes and node 1 on the |G01|
// axis (k even in G01).
Eigen::Vector4d interpolated(const StretchingTable& t, const Matrix2d& g) {
  const double coordinate[3] = {(g(0, 0) + 0.25) * 30.0, (g(1, 1) + 0.25) * 30.0,
                                std::abs(g(0, 1)) * 30.0};
  int cell[3];
  double frac[3];
  for (int d = 0; d < 3; ++d) {
    cell[d] = int(std::floor(coordinate[d]));
    frac[d] = coordinate[d] - cell[d];
  }
  const auto index = [&](int d, int n) {
    const int i = cell[d] - 1 + n;
    return i < 0 ? (d == 2 ? -i : 0) : i;
  };
  std::array<Eigen::Vector4d, 4> along_g00;
  for (int i = 0; i < 4; ++i) {
    std::array<Eigen::Vector4d, 4> along_g11;
    for (int j = 0; j < 4; ++j) {
      std::array<Eigen::Vector4d, 4> along_g01;
      for (int l = 0; l < 4; ++l) {
        Matrix2d node;
        node(0, 0) = -0.25 + index(0, i) / 30.0;
        node(1, 1) = -0.25 + index(1, j) / 30.0;
        node(0, 1) = node(1, 0) = index(2, l) / 30.0;
        along_g01[std::size_t(l)] = definition(t, node);
      }
      along_g11[std::size_t(j)] = catmull_rom(along_g01, frac[2]);
    }
    along_g00[std::size_t(i)] = catmull_rom(along_g11, frac[1]);
  }
  return catmull_rom(along_g00, frac[0]);
}

MembraneMaterial measured_material() {
  MembraneMaterial m{TensionCurve::linear(1.0, "unused"), TensionCurve::linear(1.0, "unused"), 0.0,
                     0.0};
  m.stretching = std::make_shared<const MeasuredStretching>(made_up());
  return m;
}

const std::array<Vector2d, 3> corners = {Vector2d(0.0, 0.0), Vector2d(0.04, 0.005),
                                         Vector2d(0.012, 0.03)};

// Corner positions of the triangle under the in-plane deformation f.
Vector9 deformed(const Matrix2d& f) {
  Vector9 x;
  for (int i = 0; i < 3; ++i)
    x.segment<3>(3 * i) << f * corners[std::size_t(i)], 0.0;
  return x;
}

TEST(MeasuredMembrane, UniaxialStretchAlongWarpWeftAndBiasIsTheTablesEnergy) {
  const MembraneMaterial material = measured_material();
  const TriangleRest rest = triangle_rest(corners);
  for (const double degrees : {0.0, 90.0, 45.0, 30.0}) {
    const Vector2d n(std::cos(degrees * pi / 180), std::sin(degrees * pi / 180));
    for (const double stretch : {1.01, 1.04, 1.1, 1.25}) {
      const Matrix2d f = Matrix2d::Identity() + (stretch - 1.0) * n * n.transpose();
      const Matrix2d g = 0.5 * (f.transpose() * f - Matrix2d::Identity());
      const Eigen::Vector4d k = interpolated(made_up(), g);
      const double reference = 0.5 * (k[0] * g(0, 0) * g(0, 0) + 2 * k[1] * g(0, 0) * g(1, 1) +
                                      k[2] * g(1, 1) * g(1, 1) + k[3] * g(0, 1) * g(0, 1));
      const double energy =
          membrane(MembraneModel::measured, material, rest, {}, deformed(f), Want::energy).energy /
          rest.area;
      EXPECT_NEAR(energy, reference, 1e-10 * reference) << degrees << " deg, " << stretch;
    }
  }
  // On the grid's nodes the energy is the definition's: G00 = 0.25 (node
  // 15), G11 = 1/60 (node 8), G01 = 0.
  Matrix2d g = Matrix2d::Zero();
  g(0, 0) = 0.25;
  g(1, 1) = 1.0 / 60;
  Matrix2d f = Matrix2d::Zero();
  f(0, 0) = std::sqrt(1.5);
  f(1, 1) = std::sqrt(1.0 + 2.0 / 60);
  const Eigen::Vector4d k = definition(made_up(), g);
  const double at_node =
      0.5 * (k[0] * g(0, 0) * g(0, 0) + 2 * k[1] * g(0, 0) * g(1, 1) + k[2] * g(1, 1) * g(1, 1));
  EXPECT_NEAR(
      membrane(MembraneModel::measured, material, rest, {}, deformed(f), Want::energy).energy /
          rest.area,
      at_node, 1e-10 * at_node);
}

TEST(MeasuredMembrane, DerivativesMatchFiniteDifferences) {
  const MembraneMaterial material = measured_material();
  const TriangleRest rest = triangle_rest(corners);
  Vector9 x = deformed((Matrix2d() << 1.07, 0.03, -0.02, 0.96).finished());
  x(2) += 0.004;
  x(7) -= 0.003;
  const NonelasticStrain creep{0.01, -0.005};
  const auto energy = [&](const Vector9& y) {
    return membrane(MembraneModel::measured, material, rest, creep, y, Want::energy).energy;
  };
  const auto gradient = [&](const Vector9& y) {
    return Vector9(
        membrane(MembraneModel::measured, material, rest, creep, y, Want::gradient).gradient);
  };
  const Result<9> r = membrane(MembraneModel::measured, material, rest, creep, x, Want::hessian);
  EXPECT_LT(relative_error(numeric_gradient<9>(energy, x, 1e-8), r.gradient), 1e-6);
  EXPECT_LT(relative_error(numeric_jacobian<9, 9>(gradient, x, 1e-8), r.hessian), 1e-5);
  // The tensions for the creep coupling: their position derivatives.
  const auto tensions = [&](const Vector9& y) {
    return Eigen::Vector2d(
        membrane_creep_sensitivity(MembraneModel::measured, material, rest, creep, y).tension);
  };
  const auto s = membrane_creep_sensitivity(MembraneModel::measured, material, rest, creep, x);
  EXPECT_LT(relative_error(numeric_jacobian<2, 9>(tensions, x, 1e-8), s.tension_per_position),
            1e-5);
}

TEST(MeasuredMembrane, NeedsATable) {
  MembraneMaterial m = measured_material();
  m.stretching.reset();
  EXPECT_THROW(membrane(MembraneModel::measured, m, triangle_rest(corners), {},
                        deformed(Matrix2d::Identity()), Want::energy),
               InputError);
}

} // namespace
} // namespace sartor::element
