// Physical checks of the bending hinges: the sign and value of the dihedral
// angle, rigid motions, rest data, the agreement of the two models for small
// folds, and the calibration on meshes bent isometrically onto a cylinder.

#include "element/bending.hpp"

#include "common/error.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>
#include <iostream>
#include <limits>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace sartor::element {
namespace {

using Eigen::Vector2d;
using Eigen::Vector3d;

constexpr double pi = 3.14159265358979323846;
constexpr BendingModel both_models[] = {BendingModel::discrete_shell, BendingModel::quadratic};

std::string name(BendingModel model) {
  return model == BendingModel::discrete_shell ? "discrete shell" : "quadratic";
}

// Edge from (0,0,0) to (1,0,0), x2 above it at y = 1, x3 rotated by `fold`
// about the edge from y = -1: x3 moves to -z for fold > 0.
Vector12 folded_hinge(double fold) {
  Vector12 x;
  x << 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.4, 1.0, 0.0, 0.7, -std::cos(fold), -std::sin(fold);
  return x;
}

HingeRest unit_hinge_rest(double rest_angle = 0.0) {
  const Vector2d u0(0.0, 0.0), u1(1.0, 0.0), u2(0.4, 1.0), u3(0.7, -1.0);
  return hinge_rest({u0, u1, u2}, {u1, u0, u3}, rest_angle);
}

double dihedral(const Vector12& x) {
  // The weight is |e|^2/(A1 + A2) = 1, so E = theta^2 / 2 with k_b = 1.
  const Result<12> r =
      bending(BendingModel::discrete_shell, 1.0, unit_hinge_rest(), x, Want::energy);
  return std::sqrt(2.0 * r.energy);
}

TEST(HingeRest, WeightAndCotangents) {
  const HingeRest rest = unit_hinge_rest(0.2);
  EXPECT_NEAR(rest.weight, 1.0 / (0.5 + 0.5), 1e-15);
  EXPECT_EQ(rest.rest_angle, 0.2);
  // Cotangents: triangle 1 at x0 = 0.4, at x1 = 0.6; triangle 2 at x0 = 0.7,
  // at x1 = 0.3. K = (0.6 + 0.3, 0.4 + 0.7, -1, -1), Q = K K^T (x) I3 / 1.
  const Eigen::Vector4d k(0.9, 1.1, -1.0, -1.0);
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) {
      const Eigen::Matrix3d block = rest.quadratic.block<3, 3>(3 * i, 3 * j);
      EXPECT_LT((block - k(i) * k(j) * Eigen::Matrix3d::Identity()).norm(), 1e-14);
    }
  }
}

TEST(HingeRest, TrianglesFromDifferentPanels) {
  // The second triangle in another panel's coordinates, rotated and moved,
  // its copy of the edge 2 % longer: |e| is the mean.
  const Vector2d u0(0.0, 0.0), u1(0.01, 0.0), u2(0.005, 0.008);
  const Eigen::Rotation2Dd turn(0.7);
  const Vector2d origin(3.0, -1.0);
  const Vector2d v1 = origin + turn * Vector2d(0.0102, 0.0);
  const Vector2d v0 = origin;
  const Vector2d v3 = origin + turn * Vector2d(0.004, -0.009);
  const HingeRest rest = hinge_rest({u0, u1, u2}, {v1, v0, v3});
  const double area_sum = 0.5 * 0.01 * 0.008 + 0.5 * 0.0102 * 0.009;
  EXPECT_NEAR(rest.weight, 0.0101 * 0.0101 / area_sum, 1e-12);
}

TEST(HingeRest, DegenerateTrianglesAreRejected) {
  const Vector2d u0(0.0, 0.0), u1(1.0, 0.0), u2(0.4, 1.0);
  EXPECT_THROW(hinge_rest({u0, u1, Vector2d(0.5, 0.0)}, {u1, u0, Vector2d(0.5, -1.0)}), InputError);
  EXPECT_THROW(hinge_rest({u0, u1, u2}, {u1, u0, u0}), InputError);
  EXPECT_THROW(hinge_rest({u0, u1, u2}, {u1, u0, Vector2d(0.5, -1.0)},
                          std::numeric_limits<double>::infinity()),
               InputError);
}

TEST(DiscreteShell, DihedralAngleIsSignedAndExact) {
  for (const double fold : {-2.5, -1.0, -0.1, 0.0, 0.3, 1.5, 3.0}) {
    EXPECT_NEAR(dihedral(folded_hinge(fold)), std::abs(fold), 1e-12);
  }
  // Sign: with rest angle +0.3 the hinge folded by +0.3 stores nothing,
  // folded by -0.3 it stores (0.6)^2 / 2.
  const HingeRest rest = unit_hinge_rest(0.3);
  EXPECT_NEAR(
      bending(BendingModel::discrete_shell, 1.0, rest, folded_hinge(0.3), Want::energy).energy, 0.0,
      1e-24);
  EXPECT_NEAR(
      bending(BendingModel::discrete_shell, 1.0, rest, folded_hinge(-0.3), Want::energy).energy,
      0.5 * 0.36, 1e-14);
  // Folded to the rest angle the hinge is in equilibrium.
  const Result<12> r =
      bending(BendingModel::discrete_shell, 1.0, rest, folded_hinge(0.3), Want::hessian);
  EXPECT_LT(r.gradient.cwiseAbs().maxCoeff(), 1e-14);
}

TEST(Bending, FlatRestShapeStoresNothingWhereverItIs) {
  const HingeRest rest = unit_hinge_rest();
  const Eigen::Matrix3d rotation =
      Eigen::AngleAxisd(0.8, Vector3d(1.0, -2.0, 0.5).normalized()).toRotationMatrix();
  const Vector12 flat = folded_hinge(0.0);
  Vector12 moved;
  for (int i = 0; i < 4; ++i) {
    moved.segment<3>(3 * i) = rotation * flat.segment<3>(3 * i) + Vector3d(0.3, 4.0, -1.0);
  }
  for (const BendingModel model : both_models) {
    SCOPED_TRACE(name(model));
    const Result<12> r = bending(model, 2.0, rest, moved, Want::gradient);
    EXPECT_LT(std::abs(r.energy), 1e-14); // round-off of |x|^2 |Q| ~ 1
    EXPECT_LT(r.gradient.cwiseAbs().maxCoeff(), 1e-12);
  }
}

TEST(Bending, RigidMotionsRotateTheForces) {
  const HingeRest rest = unit_hinge_rest();
  const Eigen::Matrix3d rotation =
      Eigen::AngleAxisd(2.1, Vector3d(0.3, 1.0, 0.2).normalized()).toRotationMatrix();
  const Vector12 x = folded_hinge(0.7);
  Vector12 moved;
  for (int i = 0; i < 4; ++i) {
    moved.segment<3>(3 * i) = rotation * x.segment<3>(3 * i) + Vector3d(-1.0, 0.5, 2.0);
  }
  for (const BendingModel model : both_models) {
    SCOPED_TRACE(name(model));
    const Result<12> a = bending(model, 1.0, rest, x, Want::gradient);
    const Result<12> b = bending(model, 1.0, rest, moved, Want::gradient);
    EXPECT_NEAR(b.energy, a.energy, 1e-12 * a.energy);
    Vector3d net = Vector3d::Zero();
    Vector3d moment = Vector3d::Zero();
    for (int i = 0; i < 4; ++i) {
      EXPECT_LT((b.gradient.segment<3>(3 * i) - rotation * a.gradient.segment<3>(3 * i)).norm(),
                1e-10);
      net += a.gradient.segment<3>(3 * i);
      moment += x.segment<3>(3 * i).cross(a.gradient.segment<3>(3 * i));
    }
    EXPECT_LT(net.norm(), 1e-12);
    EXPECT_LT(moment.norm(), 1e-12);
  }
}

TEST(Bending, ModelsAgreeForSmallFolds) {
  // Folding the rest shape about its edge: |K x| = 2 |e| sin(fold/2), so the
  // energies differ by a factor (2 sin(fold/2) / fold)^2 -> 1.
  const HingeRest rest = unit_hinge_rest();
  for (const double fold : {0.3, 0.1, 0.01}) {
    const Vector12 x = folded_hinge(fold);
    const double shell = bending(BendingModel::discrete_shell, 1.0, rest, x, Want::energy).energy;
    const double quadratic = bending(BendingModel::quadratic, 1.0, rest, x, Want::energy).energy;
    const double ratio = 2.0 * std::sin(fold / 2) / fold;
    EXPECT_NEAR(quadratic / shell, ratio * ratio, 1e-10);
  }
}

TEST(DiscreteShell, CollapsedHingeContributesNothing) {
  const HingeRest rest = unit_hinge_rest();
  Vector12 x = folded_hinge(0.5);
  x.segment<3>(6) = Vector3d(0.5, 0.0, 0.0); // x2 on the edge
  const Result<12> r = bending(BendingModel::discrete_shell, 1.0, rest, x, Want::hessian);
  EXPECT_EQ(r.energy, 0.0);
  EXPECT_TRUE(r.gradient.isZero(0.0));
  EXPECT_TRUE(r.hessian.isZero(0.0));
  x.segment<3>(3) = Vector3d::Zero(); // edge of zero length
  EXPECT_TRUE(
      bending(BendingModel::discrete_shell, 1.0, rest, x, Want::hessian).hessian.allFinite());
}

// --- cylinder calibration ---------------------------------------------------------

struct FlatMesh {
  std::vector<Vector2d> points;
  std::vector<std::array<int, 3>> triangles; // counter-clockwise
  double area = 0.0;
};

// Equilateral triangles of side 1/n filling a rhombus of side 1.
FlatMesh equilateral_mesh(int n) {
  FlatMesh mesh;
  const double a = 1.0 / n;
  const auto id = [n](int i, int j) { return j * (n + 1) + i; };
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i) {
      mesh.points.emplace_back(a * (i + 0.5 * j), a * j * std::sqrt(3.0) / 2);
    }
  }
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      mesh.triangles.push_back({id(i, j), id(i + 1, j), id(i, j + 1)});
      mesh.triangles.push_back({id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  }
  mesh.area = std::sqrt(3.0) / 2;
  return mesh;
}

// The unit square in n x n squares, each cut along its (1, 1) diagonal.
FlatMesh right_triangle_mesh(int n) {
  FlatMesh mesh;
  const double a = 1.0 / n;
  const auto id = [n](int i, int j) { return j * (n + 1) + i; };
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i)
      mesh.points.emplace_back(a * i, a * j);
  }
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      mesh.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      mesh.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  }
  mesh.area = 1.0;
  return mesh;
}

// Total bending energy (k_b = 1) of the mesh bent isometrically onto a
// cylinder of radius R curving along the direction (cos phi, sin phi),
// relative to the continuum value A / (2 R^2).
double cylinder_ratio(const FlatMesh& mesh, BendingModel model, double radius, double phi) {
  const Vector2d curving(std::cos(phi), std::sin(phi));
  const Vector2d axis(-std::sin(phi), std::cos(phi));
  std::vector<Vector3d> bent;
  for (const Vector2d& p : mesh.points) {
    const double s = p.dot(curving);
    const double t = p.dot(axis);
    bent.push_back(radius * std::sin(s / radius) * Vector3d(curving.x(), curving.y(), 0.0) +
                   t * Vector3d(axis.x(), axis.y(), 0.0) +
                   radius * (1.0 - std::cos(s / radius)) * Vector3d::UnitZ());
  }
  // Directed edge (p, q) -> opposite corner; an interior edge appears in both
  // directions.
  std::map<std::pair<int, int>, int> opposite;
  for (const auto& t : mesh.triangles) {
    for (std::size_t c = 0; c < 3; ++c)
      opposite[{t[c], t[(c + 1) % 3]}] = t[(c + 2) % 3];
  }
  double energy = 0.0;
  for (const auto& [edge, r] : opposite) {
    const auto [p, q] = edge;
    if (p > q) continue;
    const auto other = opposite.find({q, p});
    if (other == opposite.end()) continue;
    const int s = other->second;
    const std::array<int, 4> corner{p, q, r, s};
    const auto uv = [&](int i) { return mesh.points[static_cast<std::size_t>(i)]; };
    const HingeRest rest = hinge_rest({uv(p), uv(q), uv(r)}, {uv(q), uv(p), uv(s)});
    Vector12 x;
    for (int i = 0; i < 4; ++i)
      x.segment<3>(3 * i) = bent[static_cast<std::size_t>(corner[static_cast<std::size_t>(i)])];
    energy += bending(model, 1.0, rest, x, Want::energy).energy;
  }
  return energy / (mesh.area / (2.0 * radius * radius));
}

constexpr double radius = 0.5;
const std::vector<int> refinements{12, 24, 48, 96};

// Ratios on the refinements, printed for the record.
std::vector<double> ratios(const std::string& label, FlatMesh (*make)(int), BendingModel model,
                           double phi) {
  std::vector<double> r;
  std::cout << label << ", " << name(model) << ", phi = " << phi << ":";
  for (const int n : refinements) {
    r.push_back(cylinder_ratio(make(n), model, radius, phi));
    std::cout << " n=" << n << ": " << r.back();
  }
  std::cout << "\n";
  return r;
}

TEST(BendingCalibration, EquilateralMeshOnACylinderStoresHalfKbAOverRSquared) {
  for (const BendingModel model : both_models) {
    for (const double phi : {0.0, 0.4, pi / 2, 2.0}) {
      SCOPED_TRACE(name(model) + ", phi " + std::to_string(phi));
      const std::vector<double> r = ratios("equilateral", equilateral_mesh, model, phi);
      // The missing hinges along the boundary cost O(1/n).
      EXPECT_NEAR(r.back(), 1.0, 0.03);
      for (std::size_t i = 1; i < r.size(); ++i) {
        EXPECT_LT(std::abs(r[i] - 1.0), 0.6 * std::abs(r[i - 1] - 1.0));
      }
    }
  }
}

TEST(BendingCalibration, RightTriangleMeshFactorDependsOnDirection) {
  for (const BendingModel model : both_models) {
    for (const double phi : {0.0, pi / 2, -pi / 4, pi / 4, 0.3}) {
      SCOPED_TRACE(name(model) + ", phi " + std::to_string(phi));
      const std::vector<double> r = ratios("right-triangle", right_triangle_mesh, model, phi);
      const double expected = 1.0 + std::sin(2 * phi) + std::pow(std::sin(2 * phi), 2);
      EXPECT_NEAR(r.back() / expected, 1.0, 0.03);
    }
  }
}

} // namespace
} // namespace sartor::element
