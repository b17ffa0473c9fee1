// Remeshing after a pattern edit: triangle quality against closed forms,
// Delaunay smoothing checked by an independent in-circle determinant on
// every edge (and against the known Delaunay triangulation of a sheared
// lattice), the edges it must never flip, and barycentric location and
// transfer: affine fields exact, outside points on the nearest triangle,
// groups kept apart, refined triangles traced to their parents.

#include "mesh/remesh.hpp"

#include "common/error.hpp"
#include "mesh/generators.hpp"
#include "mesh/triangle_mesh.hpp"

#include "mesh_checks.hpp"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <limits>
#include <map>
#include <random>
#include <set>
#include <string>
#include <vector>

namespace sartor {
namespace {

using mesh::RectanglePattern;
using test::material_area;
using test::total_material_area;
using UV = std::array<Eigen::Vector2d, 3>;

constexpr double pi = 3.14159265358979323846;

// ---- Mesh builders --------------------------------------------------------

// Triangles on points of the (u, v) plane, one uv per vertex; the placement
// is a curved sheet (u, v, u v) so that "positions unchanged" means something.
TriangleMesh planar_mesh(const std::vector<Eigen::Vector2d>& points,
                         const std::vector<std::array<int, 3>>& triangles) {
  TriangleMesh mesh;
  for (const Eigen::Vector2d& p : points)
    mesh.positions.emplace_back(p.x(), p.y(), p.x() * p.y());
  mesh.triangles = triangles;
  for (const auto& corners : triangles)
    mesh.material_uv.push_back({points[std::size_t(corners[0])], points[std::size_t(corners[1])],
                                points[std::size_t(corners[2])]});
  return mesh;
}

// A convex quad split along its long diagonal 0-1: the kite (0, 0), (4, 0),
// (2, 1), (2, -1), whose short diagonal is 2-3.
TriangleMesh long_diagonal_kite() {
  return planar_mesh({{0, 0}, {4, 0}, {2, 1}, {2, -1}}, {{0, 1, 2}, {1, 0, 3}});
}

double signed_area(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  return 0.5 * ((b - a).x() * (c - a).y() - (b - a).y() * (c - a).x());
}

// A regular polygon of `corners` on the unit circle, fanned from corner 0,
// with random points inside inserted naively (each splits the triangle that
// holds it into three): a valid triangulation full of slivers.
TriangleMesh naive_triangulation(int corners, int inside, unsigned seed) {
  std::vector<Eigen::Vector2d> points;
  points.reserve(std::size_t(corners) + std::size_t(inside));
  for (int k = 0; k < corners; ++k)
    points.emplace_back(std::cos(2 * pi * k / corners), std::sin(2 * pi * k / corners));
  std::vector<std::array<int, 3>> triangles;
  for (int k = 1; k + 1 < corners; ++k)
    triangles.push_back({0, k, k + 1});
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> coordinate(-0.9, 0.9);
  while (int(points.size()) < corners + inside) {
    const Eigen::Vector2d p(coordinate(random), coordinate(random));
    for (std::size_t t = 0; t < triangles.size(); ++t) {
      const auto [a, b, c] = triangles[t];
      const auto& pa = points[std::size_t(a)];
      const auto& pb = points[std::size_t(b)];
      const auto& pc = points[std::size_t(c)];
      const double least =
          std::min({signed_area(pa, pb, p), signed_area(pb, pc, p), signed_area(pc, pa, p)});
      if (least <= 1e-6) continue; // outside, or too near a side to split cleanly
      const int added = int(points.size());
      points.push_back(p);
      triangles[t] = {a, b, added};
      triangles.push_back({b, c, added});
      triangles.push_back({c, a, added});
      break;
    }
  }
  return planar_mesh(points, triangles);
}

// An nx by ny grid of unit cells, each split along a random diagonal, whose
// rest shape a pattern edit sheared: u = i + shear j, v = j (the placement
// stays the unsheared grid). With shear 0.5 every cell's short diagonal is
// (i + 1, j)-(i, j + 1), and the triangles it makes are acute.
TriangleMesh sheared_grid(int nx, int ny, double shear, unsigned seed) {
  TriangleMesh mesh;
  std::vector<Eigen::Vector2d> uv;
  for (int j = 0; j <= ny; ++j) {
    for (int i = 0; i <= nx; ++i) {
      mesh.positions.emplace_back(i, j, 0.0);
      uv.emplace_back(i + shear * j, j);
    }
  }
  const auto vertex = [&](int i, int j) { return j * (nx + 1) + i; };
  const auto add = [&](int a, int b, int c) {
    mesh.triangles.push_back({a, b, c});
    mesh.material_uv.push_back({uv[std::size_t(a)], uv[std::size_t(b)], uv[std::size_t(c)]});
  };
  std::mt19937 random(seed);
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      const int p00 = vertex(i, j), p10 = vertex(i + 1, j);
      const int p11 = vertex(i + 1, j + 1), p01 = vertex(i, j + 1);
      if (random() % 2 == 0) {
        add(p00, p10, p11);
        add(p00, p11, p01);
      } else {
        add(p00, p10, p01);
        add(p10, p11, p01);
      }
    }
  }
  return mesh;
}

// ---- Independent checks ---------------------------------------------------

// The in-circle determinant: positive when d lies inside the circle through
// the counter-clockwise a, b, c.
double in_circle(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c,
                 const Eigen::Vector2d& d) {
  Eigen::Matrix3d m;
  for (int r = 0; r < 3; ++r) {
    const Eigen::Vector2d e = (r == 0 ? a : r == 1 ? b : c) - d;
    m.row(r) << e.x(), e.y(), e.squaredNorm();
  }
  return m.determinant();
}

// No edge's far vertex lies inside the other triangle's circumcircle
// (relative to the quad's size^4, beyond round-off).
void expect_delaunay(const TriangleMesh& mesh) {
  for (const Hinge& hinge : interior_edges(mesh)) {
    const auto& first = mesh.material_uv[std::size_t(hinge.triangles[0])];
    const auto& second = mesh.material_uv[std::size_t(hinge.triangles[1])];
    const Eigen::Vector2d& a = first[std::size_t(hinge.corners[0][0])];
    const Eigen::Vector2d& b = first[std::size_t(hinge.corners[0][1])];
    const Eigen::Vector2d& c = first[std::size_t(hinge.corners[0][2])];
    const Eigen::Vector2d& d = second[std::size_t(hinge.corners[1][2])];
    const double size = std::max({(b - a).norm(), (c - a).norm(), (d - a).norm()});
    EXPECT_LE(in_circle(a, b, c, d), 1e-10 * std::pow(size, 4))
        << "edge " << hinge.vertices[0] << "-" << hinge.vertices[1];
  }
}

bool has_edge(const TriangleMesh& mesh, int a, int b) {
  const auto edges = mesh_edges(mesh);
  return std::binary_search(edges.begin(), edges.end(),
                            std::array<int, 2>{std::min(a, b), std::max(a, b)});
}

// What a flip must keep: validity, counter-clockwise (u, v), the placement,
// the outline, every vertex in use, material ids and area, the creases.
void expect_sound_flips(const TriangleMesh& before, const TriangleMesh& after) {
  EXPECT_NO_THROW(validate(after, "after smoothing"));
  ASSERT_EQ(after.triangle_count(), before.triangle_count());
  for (std::size_t t = 0; t < after.triangle_count(); ++t)
    EXPECT_GT(material_area(after, t), 0.0) << "triangle " << t;
  EXPECT_EQ(after.positions, before.positions);
  EXPECT_EQ(boundary_edges(after), boundary_edges(before));
  std::set<int> used;
  for (const auto& corners : after.triangles)
    used.insert(corners.begin(), corners.end());
  EXPECT_EQ(used.size(), after.vertex_count());
  EXPECT_EQ(after.material_ids, before.material_ids);
  EXPECT_NEAR(total_material_area(after), total_material_area(before),
              1e-12 * total_material_area(before));
  for (const CreaseEdge& crease : before.creases)
    EXPECT_TRUE(has_edge(after, crease.a, crease.b)) << crease.a << "-" << crease.b;
}

// Every corner of a vertex has the vertex's one (u, v) (meshes without seams).
void expect_one_uv_per_vertex(const TriangleMesh& mesh) {
  std::map<int, Eigen::Vector2d> uv;
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    for (std::size_t c = 0; c < 3; ++c) {
      const auto [seen, added] = uv.emplace(mesh.triangles[t][c], mesh.material_uv[t][c]);
      if (!added) {
        EXPECT_EQ(seen->second, mesh.material_uv[t][c]) << "vertex " << seen->first;
      }
    }
  }
}

// ---- Quality --------------------------------------------------------------

TEST(TriangleQuality, EquilateralIsOne) {
  const UV equilateral{Eigen::Vector2d(0, 0), Eigen::Vector2d(2, 0),
                       Eigen::Vector2d(1, std::sqrt(3.0))};
  EXPECT_NEAR(triangle_quality(equilateral), 1.0, 1e-15);
}

// Legs 1: area 1/2, perimeter 2 + sqrt 2, inradius 2A/P = 1/(2 + sqrt 2),
// longest side sqrt 2, so 2r/L = sqrt(2) - 1, times sqrt 3. Scale-free.
TEST(TriangleQuality, RightIsoscelesIsTheClosedForm) {
  const double expected = std::sqrt(3.0) * (std::sqrt(2.0) - 1.0);
  for (const double scale : {1.0, 1e-3, 7.5}) {
    const UV right{Eigen::Vector2d(1, 1), Eigen::Vector2d(1 + scale, 1),
                   Eigen::Vector2d(1, 1 + scale)};
    EXPECT_NEAR(triangle_quality(right), expected, 1e-15) << scale;
  }
  EXPECT_NEAR(worst_quality(mesh::rectangle(1, 1, 4, 4, RectanglePattern::right)), expected, 1e-15);
}

TEST(TriangleQuality, DegenerateAndFoldedAreZero) {
  const UV collinear{Eigen::Vector2d(0, 0), Eigen::Vector2d(1, 1), Eigen::Vector2d(2, 2)};
  const UV repeated{Eigen::Vector2d(0, 0), Eigen::Vector2d(0, 0), Eigen::Vector2d(1, 0)};
  const UV clockwise{Eigen::Vector2d(0, 0), Eigen::Vector2d(0, 1), Eigen::Vector2d(1, 0)};
  EXPECT_EQ(triangle_quality(collinear), 0.0);
  EXPECT_EQ(triangle_quality(repeated), 0.0);
  EXPECT_EQ(triangle_quality(clockwise), 0.0);
}

// ---- Delaunay smoothing -----------------------------------------------------

// Rotated by an angle and spaced 0.1, the squares' corners are not exact
// binary numbers: their facing angles sum to pi up to round-off either way.
TEST(DelaunaySmoothing, LeavesCoCircularGridSquaresAlone) {
  const Eigen::Rotation2Dd rotation(0.3);
  for (const auto pattern : {RectanglePattern::right, RectanglePattern::alternating}) {
    TriangleMesh mesh = mesh::rectangle(1.3, 0.9, 13, 9, pattern);
    for (auto& uv : mesh.material_uv)
      for (Eigen::Vector2d& corner : uv)
        corner = rotation * corner + Eigen::Vector2d(0.1, 0.7);
    const TriangleMesh before = mesh;
    const FlipReport report = delaunay_smoothing(mesh);
    EXPECT_EQ(report.flips, 0);
    EXPECT_EQ(mesh.triangles, before.triangles);
    EXPECT_EQ(report.worst_after, report.worst_before);
  }
}

TEST(DelaunaySmoothing, FlipsALongDiagonalToTheShortOne) {
  TriangleMesh mesh = long_diagonal_kite();
  const TriangleMesh before = mesh;
  const FlipReport report = delaunay_smoothing(mesh);
  EXPECT_EQ(report.flips, 1);
  EXPECT_TRUE(has_edge(mesh, 2, 3));
  EXPECT_FALSE(has_edge(mesh, 0, 1));
  EXPECT_GT(report.worst_after, report.worst_before);
  EXPECT_EQ(report.worst_after, worst_quality(mesh));
  expect_sound_flips(before, mesh);
  expect_one_uv_per_vertex(mesh);
}

TEST(DelaunaySmoothing, MakesANaiveTriangulationDelaunay) {
  for (const unsigned seed : {1u, 2u, 3u}) {
    TriangleMesh mesh = naive_triangulation(16, 60, seed);
    const TriangleMesh before = mesh;
    const FlipReport report = delaunay_smoothing(mesh);
    EXPECT_GT(report.flips, 0);
    EXPECT_GE(report.worst_after, report.worst_before);
    expect_delaunay(mesh);
    expect_sound_flips(before, mesh);
    expect_one_uv_per_vertex(mesh);
    TriangleMesh again = mesh;
    EXPECT_EQ(delaunay_smoothing(again).flips, 0) << "seed " << seed;
  }
}

// The sheared lattice has one Delaunay triangulation: every cell split along
// its short diagonal; exactly the cells that started on the long one flip.
TEST(DelaunaySmoothing, RestoresTheShortDiagonalsOfAShearedGrid) {
  const int nx = 12, ny = 9;
  TriangleMesh mesh = sheared_grid(nx, ny, 0.5, 7);
  const TriangleMesh before = mesh;
  int long_diagonals = 0;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i)
      long_diagonals += has_edge(before, j * (nx + 1) + i, (j + 1) * (nx + 1) + i + 1);
  const FlipReport report = delaunay_smoothing(mesh);
  EXPECT_EQ(report.flips, long_diagonals);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i)
      EXPECT_TRUE(has_edge(mesh, j * (nx + 1) + i + 1, (j + 1) * (nx + 1) + i)) << i << " " << j;
  const UV acute{Eigen::Vector2d(0, 0), Eigen::Vector2d(1, 0), Eigen::Vector2d(0.5, 1)};
  EXPECT_NEAR(report.worst_after, triangle_quality(acute), 1e-14);
  expect_delaunay(mesh);
  expect_sound_flips(before, mesh);
}

TEST(DelaunaySmoothing, NeverFlipsACrease) {
  TriangleMesh mesh = long_diagonal_kite();
  mesh.creases = {{1, 0, 0.5}};
  const TriangleMesh before = mesh;
  EXPECT_EQ(delaunay_smoothing(mesh).flips, 0);
  EXPECT_EQ(mesh.triangles, before.triangles);
}

TEST(DelaunaySmoothing, NeverFlipsBetweenMaterials) {
  TriangleMesh mesh = long_diagonal_kite();
  mesh.material_ids = {0, 1};
  EXPECT_EQ(delaunay_smoothing(mesh).flips, 0);
  mesh.material_ids = {3, 3};
  EXPECT_EQ(delaunay_smoothing(mesh).flips, 1);
  EXPECT_EQ(mesh.material_ids, (std::vector<int>{3, 3}));
}

TEST(DelaunaySmoothing, NeverFlipsAcrossDifferentMaterialCoordinates) {
  TriangleMesh mesh = long_diagonal_kite();
  // The second triangle across a seam: a quad mixing the two sides' (u, v)
  // would still want the flip.
  for (Eigen::Vector2d& uv : mesh.material_uv[1])
    uv.x() += 0.25;
  EXPECT_EQ(delaunay_smoothing(mesh).flips, 0);
}

// Across a closed surface's seam the other diagonal may be an edge already
// (here of a third triangle elsewhere in (u, v)): flipping would give it
// three triangles.
TEST(DelaunaySmoothing, NeverDoublesAnEdge) {
  TriangleMesh mesh = long_diagonal_kite();
  mesh.positions.emplace_back(2.0, 0.0, 1.0);
  mesh.triangles.push_back({2, 3, 4});
  mesh.material_uv.push_back(
      {Eigen::Vector2d(20, 1), Eigen::Vector2d(20, -1), Eigen::Vector2d(22, 0)});
  EXPECT_EQ(delaunay_smoothing(mesh).flips, 0);
}

// An edit that folds a triangle (clockwise in (u, v)) calls for a new mesh:
// no flip, and the worst quality says so.
TEST(DelaunaySmoothing, NeverFlipsAFoldedTriangle) {
  TriangleMesh mesh = planar_mesh({{0, 0}, {1, 0}, {0.5, 1}, {0.5, 0.1}}, {{0, 1, 2}, {1, 0, 3}});
  const FlipReport report = delaunay_smoothing(mesh);
  EXPECT_EQ(report.flips, 0);
  EXPECT_EQ(report.worst_after, 0.0);
}

// An edit shears a closed tube's rest shape: the cells away from the seam
// flip, the seam's edges (u jumps across them) stay.
TEST(DelaunaySmoothing, KeepsTheSeamOfATube) {
  TriangleMesh mesh = mesh::cylinder_band(0.1, 0.2, 8, 4);
  for (auto& uv : mesh.material_uv)
    for (Eigen::Vector2d& corner : uv)
      corner.x() += 2.0 * corner.y();
  const auto seam_edges = [](const TriangleMesh& m) {
    std::set<std::array<int, 2>> seam;
    for (const Hinge& hinge : interior_edges(m)) {
      const auto& first = m.material_uv[std::size_t(hinge.triangles[0])];
      const auto& second = m.material_uv[std::size_t(hinge.triangles[1])];
      // corners[1] holds the second triangle's v1, v0, v3.
      if (first[std::size_t(hinge.corners[0][0])] != second[std::size_t(hinge.corners[1][1])]) {
        seam.insert({std::min(hinge.vertices[0], hinge.vertices[1]),
                     std::max(hinge.vertices[0], hinge.vertices[1])});
      }
    }
    return seam;
  };
  const TriangleMesh before = mesh;
  const FlipReport report = delaunay_smoothing(mesh);
  EXPECT_GT(report.flips, 0);
  EXPECT_GT(report.worst_after, report.worst_before);
  EXPECT_EQ(seam_edges(before).size(), 4u);
  EXPECT_EQ(seam_edges(mesh), seam_edges(before));
  expect_sound_flips(before, mesh);
}

TEST(DelaunaySmoothing, RejectsAnInvalidMesh) {
  TriangleMesh mesh = long_diagonal_kite();
  mesh.material_uv.pop_back();
  EXPECT_THROW(delaunay_smoothing(mesh), InputError);
}

// ---- Location and transfer -------------------------------------------------

// Random points in [low, high]^2, fixed seed.
std::vector<Eigen::Vector2d> random_points(int count, const Eigen::Vector2d& low,
                                           const Eigen::Vector2d& high, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<Eigen::Vector2d> points;
  points.reserve(std::size_t(count));
  for (int k = 0; k < count; ++k)
    points.push_back(low + (high - low).cwiseProduct(Eigen::Vector2d(unit(random), unit(random))));
  return points;
}

Eigen::Vector2d located_point(const TriangleMesh& mesh, const BarycentricLocation& at) {
  const auto& uv = mesh.material_uv[std::size_t(at.triangle)];
  return at.weights[0] * uv[0] + at.weights[1] * uv[1] + at.weights[2] * uv[2];
}

// The placement an affine map of the rest shape: x = A (u, v) + b.
void place_affinely(TriangleMesh& mesh, const Eigen::Matrix<double, 3, 2>& map,
                    const Eigen::Vector3d& shift) {
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t)
    for (std::size_t c = 0; c < 3; ++c)
      mesh.positions[std::size_t(mesh.triangles[t][c])] = map * mesh.material_uv[t][c] + shift;
}

TEST(LocateInMaterial, ReproducesAffineFieldsExactly) {
  TriangleMesh mesh = mesh::rectangle(2.0, 1.0, 20, 10, RectanglePattern::perturbed);
  Eigen::Matrix<double, 3, 2> map;
  map << 0.8, 0.3, -0.2, 1.1, 0.5, -0.4;
  const Eigen::Vector3d shift(0.1, -0.2, 0.3);
  place_affinely(mesh, map, shift);
  const auto points = random_points(2000, {0, 0}, {2, 1}, 11);
  const auto at = locate_in_material(mesh, points, {});
  const auto positions = transfer_positions(mesh, at);
  for (std::size_t k = 0; k < points.size(); ++k) {
    EXPECT_GE(at[k].weights.minCoeff(), -1e-12);
    EXPECT_NEAR(at[k].weights.sum(), 1.0, 1e-15);
    EXPECT_LE((located_point(mesh, at[k]) - points[k]).norm(), 1e-14) << k;
    EXPECT_LE((positions[k] - (map * points[k] + shift)).norm(), 1e-14) << k;
  }
}

// The rectangle's outline is straight, so its nearest point to p is p
// clamped to the rectangle.
TEST(LocateInMaterial, PutsOutsidePointsOnTheNearestTriangle) {
  const TriangleMesh mesh = mesh::rectangle(1.0, 1.0, 8, 8, RectanglePattern::perturbed);
  auto points = random_points(500, {-1, -1}, {2, 2}, 12);
  points.emplace_back(1e3, 0.5);
  points.emplace_back(-40.0, -7.0);
  const auto at = locate_in_material(mesh, points, {});
  for (std::size_t k = 0; k < points.size(); ++k) {
    const Eigen::Vector2d nearest = points[k].cwiseMax(0.0).cwiseMin(1.0);
    EXPECT_LE((located_point(mesh, at[k]) - nearest).norm(), 1e-14) << k;
    EXPECT_GE(at[k].weights.minCoeff(), nearest == points[k] ? -1e-12 : 0.0);
  }
}

double segment_distance(const Eigen::Vector2d& p, const Eigen::Vector2d& a,
                        const Eigen::Vector2d& b) {
  const double s = std::clamp((p - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0);
  return (a + s * (b - a) - p).norm();
}

// Points in a hole lie inside the grid but in no triangle: the nearest
// triangle, by brute force over every side, may be several cells away.
TEST(LocateInMaterial, FindsTheNearestTriangleAcrossAHole) {
  const TriangleMesh square = mesh::rectangle(1.0, 1.0, 10, 10, RectanglePattern::perturbed);
  TriangleMesh mesh = square;
  mesh.triangles.clear();
  mesh.material_uv.clear();
  for (std::size_t t = 0; t < square.triangle_count(); ++t) {
    const auto& uv = square.material_uv[t];
    const Eigen::Vector2d centroid = (uv[0] + uv[1] + uv[2]) / 3.0;
    if ((centroid - Eigen::Vector2d(0.5, 0.5)).lpNorm<Eigen::Infinity>() < 0.3) continue;
    mesh.triangles.push_back(square.triangles[t]);
    mesh.material_uv.push_back(uv);
  }
  const auto points = random_points(300, {0.25, 0.25}, {0.75, 0.75}, 13);
  const auto at = locate_in_material(mesh, points, {});
  for (std::size_t k = 0; k < points.size(); ++k) {
    double nearest = std::numeric_limits<double>::infinity();
    for (const auto& uv : mesh.material_uv)
      for (std::size_t c = 0; c < 3; ++c)
        nearest = std::min(nearest, segment_distance(points[k], uv[c], uv[(c + 1) % 3]));
    EXPECT_NEAR((located_point(mesh, at[k]) - points[k]).norm(), nearest, 1e-14) << k;
  }
}

// Two panels on the same (u, v) square, one placed at z = 0, the other at
// z = 1: each point is found in its own.
TEST(LocateInMaterial, KeepsGroupsApart) {
  TriangleMesh mesh = mesh::rectangle(1.0, 1.0, 4, 4, RectanglePattern::perturbed);
  const TriangleMesh other = mesh::rectangle(1.0, 1.0, 5, 3);
  const int offset = int(mesh.vertex_count());
  mesh.material_ids.assign(mesh.triangle_count(), 0);
  for (const Eigen::Vector3d& p : other.positions)
    mesh.positions.push_back(p + Eigen::Vector3d::UnitZ());
  for (std::size_t t = 0; t < other.triangle_count(); ++t) {
    const auto& corners = other.triangles[t];
    mesh.triangles.push_back({corners[0] + offset, corners[1] + offset, corners[2] + offset});
    mesh.material_uv.push_back(other.material_uv[t]);
    mesh.material_ids.push_back(1);
  }
  const auto points = random_points(400, {0, 0}, {1, 1}, 14);
  std::vector<int> groups;
  for (std::size_t k = 0; k < points.size(); ++k)
    groups.push_back(int(k % 2));
  const auto at = locate_in_material(mesh, points, groups);
  const auto positions = transfer_positions(mesh, at);
  for (std::size_t k = 0; k < points.size(); ++k) {
    EXPECT_EQ(mesh.material_ids[std::size_t(at[k].triangle)], groups[k]) << k;
    EXPECT_NEAR(positions[k].z(), double(groups[k]), 1e-15) << k;
    EXPECT_LE((positions[k].head<2>() - points[k]).norm(), 1e-14) << k;
  }
  EXPECT_THROW(locate_in_material(mesh, {{0.5, 0.5}}, {2}), InputError);
  EXPECT_THROW(locate_in_material(mesh, {{0.5, 0.5}}, {0, 1}), InputError);
  EXPECT_THROW(locate_in_material(mesh, {{std::nan(""), 0.5}}, {}), InputError);
}

// refine() makes children 4 t .. 4 t + 3 of triangle t, each inside it.
TEST(SourceTriangles, TraceRefinedTrianglesToTheirParents) {
  TriangleMesh coarse = mesh::rectangle(1.0, 0.5, 6, 4, RectanglePattern::perturbed);
  for (std::size_t t = 0; t < coarse.triangle_count(); ++t)
    coarse.material_ids.push_back(int(t % 3));
  const TriangleMesh fine = mesh::refine(coarse);
  const std::vector<int> sources = source_triangles(coarse, fine);
  ASSERT_EQ(sources.size(), fine.triangle_count());
  for (std::size_t t = 0; t < sources.size(); ++t)
    EXPECT_EQ(sources[t], int(t / 4)) << t;
}

// After smoothing, each new triangle's centroid lies in the old triangle
// its state comes from.
TEST(SourceTriangles, FollowFlips) {
  TriangleMesh mesh = naive_triangulation(12, 30, 5);
  const TriangleMesh before = mesh;
  ASSERT_GT(delaunay_smoothing(mesh).flips, 0);
  const std::vector<int> sources = source_triangles(before, mesh);
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    const auto& uv = mesh.material_uv[t];
    const Eigen::Vector2d centroid = (uv[0] + uv[1] + uv[2]) / 3.0;
    const auto& old_uv = before.material_uv[std::size_t(sources[t])];
    for (std::size_t c = 0; c < 3; ++c)
      EXPECT_GE(signed_area(old_uv[c], old_uv[(c + 1) % 3], centroid), -1e-15) << t;
  }
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Times for the record (no assertion on them): 40,000 points in 40,044
// triangles, and smoothing a 10,080-triangle grid with random bad diagonals.
TEST(RemeshTiming, LocateAndSmoothLargeMeshes) {
  const TriangleMesh mesh = mesh::rectangle(1.0, 1.0, 141, 142, RectanglePattern::perturbed);
  const auto points = random_points(40000, {-0.01, -0.01}, {1.01, 1.01}, 15);
  auto start = std::chrono::steady_clock::now();
  const auto at = locate_in_material(mesh, points, {});
  const double locate_s = seconds_since(start);
  ASSERT_EQ(at.size(), points.size());
  TriangleMesh grid = sheared_grid(70, 72, 0.5, 16);
  start = std::chrono::steady_clock::now();
  const FlipReport report = delaunay_smoothing(grid);
  const double smoothing_s = seconds_since(start);
  std::cout << "locate " << points.size() << " points in " << mesh.triangle_count()
            << " triangles: " << locate_s << " s; smoothing " << grid.triangle_count()
            << " triangles: " << report.flips << " flips in " << smoothing_s << " s\n";
  RecordProperty("locate_40k_s", std::to_string(locate_s));
  RecordProperty("smoothing_10k_s", std::to_string(smoothing_s));
}

} // namespace
} // namespace sartor
