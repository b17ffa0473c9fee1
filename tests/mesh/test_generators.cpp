// Generated meshes: counts, areas (material and 3D), placement, the band's
// seam, the cap's geodesic mapping, refinement, and argument checks.

#include "mesh/generators.hpp"

#include "common/error.hpp"
#include "mesh/triangle_mesh.hpp"

#include "mesh_checks.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <set>
#include <string>
#include <tuple>
#include <vector>

namespace sartor {
namespace {

using mesh::BandLength;
using mesh::RectanglePattern;
using test::material_area;
using test::surface_area;
using test::total_material_area;

constexpr double pi = 3.14159265358979323846;

void expect_positive_material_areas(const TriangleMesh& m) {
  for (std::size_t t = 0; t < m.triangle_count(); ++t)
    EXPECT_GT(material_area(m, t), 0.0) << t;
}

void expect_no_duplicate_positions(const TriangleMesh& m) {
  std::set<std::tuple<double, double, double>> seen;
  for (const auto& p : m.positions) {
    // Rounded to 1e-12 so that nearly equal positions count as equal.
    const auto key = std::make_tuple(std::round(p.x() * 1e12), std::round(p.y() * 1e12),
                                     std::round(p.z() * 1e12));
    EXPECT_TRUE(seen.insert(key).second) << p.transpose();
  }
}

// Every corner's uv is the (x, y) of its vertex, and z = 0.
void expect_flat_with_uv_equal_xy(const TriangleMesh& m) {
  for (std::size_t t = 0; t < m.triangle_count(); ++t) {
    for (std::size_t c = 0; c < 3; ++c) {
      const Eigen::Vector3d& p = test::corner_position(m, t, c);
      EXPECT_EQ(p.z(), 0.0);
      EXPECT_EQ(m.material_uv[t][c], p.head<2>());
    }
  }
}

class Rectangle : public ::testing::TestWithParam<RectanglePattern> {};

TEST_P(Rectangle, CountsAreaAndPlacement) {
  const double width = 1.5;
  const double height = 0.7;
  for (const auto& [nx, ny] : {std::pair{1, 1}, std::pair{5, 3}, std::pair{16, 9}}) {
    const auto m = mesh::rectangle(width, height, nx, ny, GetParam());
    EXPECT_NO_THROW(validate(m, "rectangle"));
    EXPECT_EQ(m.vertex_count(), static_cast<std::size_t>((nx + 1) * (ny + 1)));
    EXPECT_EQ(m.triangle_count(), static_cast<std::size_t>(2 * nx * ny));
    EXPECT_TRUE(m.material_ids.empty());
    EXPECT_NEAR(total_material_area(m), width * height, 1e-15 * width * height * nx * ny);
    expect_positive_material_areas(m);
    expect_flat_with_uv_equal_xy(m);
    for (std::size_t t = 0; t < m.triangle_count(); ++t)
      EXPECT_GT(test::area_normal(m, t).z(), 0.0);
    EXPECT_EQ(m.positions.front(), Eigen::Vector3d(0, 0, 0));
    EXPECT_EQ(m.positions.back(), Eigen::Vector3d(width, height, 0));
    EXPECT_EQ(m.positions[static_cast<std::size_t>(nx)], Eigen::Vector3d(width, 0, 0));
  }
}

INSTANTIATE_TEST_SUITE_P(Patterns, Rectangle,
                         ::testing::Values(RectanglePattern::alternating, RectanglePattern::right,
                                           RectanglePattern::perturbed));

// The set of edges as pairs of positions, to compare meshes geometrically.
std::set<std::pair<std::pair<double, double>, std::pair<double, double>>>
edge_set(const TriangleMesh& m, bool mirror_x, bool mirror_y, double width, double height) {
  std::set<std::pair<std::pair<double, double>, std::pair<double, double>>> edges;
  for (const auto& tri : m.triangles) {
    for (std::size_t c = 0; c < 3; ++c) {
      auto point = [&](int v) {
        const Eigen::Vector3d& p = m.positions[static_cast<std::size_t>(v)];
        return std::pair{mirror_x ? width - p.x() : p.x(), mirror_y ? height - p.y() : p.y()};
      };
      auto a = point(tri[c]);
      auto b = point(tri[(c + 1) % 3]);
      if (b < a) std::swap(a, b);
      edges.insert({a, b});
    }
  }
  return edges;
}

TEST(Rectangle, AlternatingIsMirrorSymmetricRightIsNot) {
  // Spacings that are powers of two keep the mirrored coordinates exact.
  const auto alternating = mesh::rectangle(4.0, 2.0, 8, 4, RectanglePattern::alternating);
  const auto edges = edge_set(alternating, false, false, 4.0, 2.0);
  EXPECT_EQ(edge_set(alternating, true, false, 4.0, 2.0), edges);
  EXPECT_EQ(edge_set(alternating, false, true, 4.0, 2.0), edges);
  const auto right = mesh::rectangle(4.0, 2.0, 8, 4, RectanglePattern::right);
  EXPECT_NE(edge_set(right, true, false, 4.0, 2.0), edge_set(right, false, false, 4.0, 2.0));
  // Right: every diagonal rises (dx dy > 0).
  for (const auto& [a, b] : edge_set(right, false, false, 4.0, 2.0))
    EXPECT_GE((b.first - a.first) * (b.second - a.second), 0.0);
}

TEST(Rectangle, PerturbedMovesOnlyInteriorVerticesWithinAQuarterSpacing) {
  const int nx = 10;
  const int ny = 6;
  const double hx = 2.0 / nx;
  const double hy = 1.0 / ny;
  const auto perturbed = mesh::rectangle(2.0, 1.0, nx, ny, RectanglePattern::perturbed);
  const auto regular = mesh::rectangle(2.0, 1.0, nx, ny, RectanglePattern::alternating);
  EXPECT_EQ(perturbed.triangles, regular.triangles);
  double largest = 0.0;
  for (int j = 0; j <= ny; ++j) {
    for (int i = 0; i <= nx; ++i) {
      const auto v = static_cast<std::size_t>(j * (nx + 1) + i);
      const Eigen::Vector3d d = perturbed.positions[v] - regular.positions[v];
      const double scaled = std::hypot(d.x() / (0.25 * hx), d.y() / (0.25 * hy));
      if (i == 0 || j == 0 || i == nx || j == ny) {
        EXPECT_EQ(d.norm(), 0.0) << i << " " << j;
      } else {
        EXPECT_LE(scaled, 1.0 + 1e-12);
        EXPECT_EQ(d.z(), 0.0);
      }
      largest = std::max(largest, scaled);
    }
  }
  EXPECT_GT(largest, 0.5); // truly unstructured
  // The same mesh every time (fixed seed).
  EXPECT_EQ(mesh::rectangle(2.0, 1.0, nx, ny, RectanglePattern::perturbed).positions,
            perturbed.positions);
  // No triangle anywhere near folding.
  for (std::size_t t = 0; t < perturbed.triangle_count(); ++t)
    EXPECT_GT(material_area(perturbed, t), 0.05 * hx * hy) << t;
}

TEST(Rectangle, PatternNames) {
  EXPECT_EQ(mesh::rectangle_pattern("alternating"), RectanglePattern::alternating);
  EXPECT_EQ(mesh::rectangle_pattern("right"), RectanglePattern::right);
  EXPECT_EQ(mesh::rectangle_pattern("perturbed"), RectanglePattern::perturbed);
  EXPECT_THROW((void)mesh::rectangle_pattern("zigzag"), InputError);
}

TEST(Disk, CountsBoundaryAndTriangleShapes) {
  const double radius = 0.3;
  for (const int rings : {1, 2, 3, 8}) {
    const auto m = mesh::disk(radius, rings);
    EXPECT_EQ(m.vertex_count(), static_cast<std::size_t>(1 + 3 * rings * (rings + 1)));
    EXPECT_EQ(m.triangle_count(), static_cast<std::size_t>(6 * rings * rings));
    EXPECT_EQ(m.positions[0], Eigen::Vector3d::Zero());
    expect_positive_material_areas(m);
    expect_flat_with_uv_equal_xy(m);
    expect_no_duplicate_positions(m);
    const auto rim = boundary_vertices(m);
    EXPECT_EQ(rim.size(), static_cast<std::size_t>(6 * rings));
    for (const int v : rim)
      EXPECT_NEAR(m.positions[static_cast<std::size_t>(v)].norm(), radius, 1e-15);
    // Nearly equal triangles.
    double smallest = std::numeric_limits<double>::infinity();
    double largest = 0.0;
    for (std::size_t t = 0; t < m.triangle_count(); ++t) {
      smallest = std::min(smallest, material_area(m, t));
      largest = std::max(largest, material_area(m, t));
    }
    EXPECT_LT(largest / smallest, 2.0) << rings;
  }
}

TEST(Disk, AreaIsTheInscribedPolygonsAndConvergesToPiRSquared) {
  const double radius = 0.3;
  double previous_error = std::numeric_limits<double>::infinity();
  for (const int rings : {1, 2, 4, 8, 16, 32}) {
    const double area = total_material_area(mesh::disk(radius, rings));
    const int n = 6 * rings;
    EXPECT_NEAR(area, 0.5 * n * radius * radius * std::sin(2 * pi / n), 1e-14);
    const double error = pi * radius * radius - area;
    EXPECT_GT(error, 0.0);
    if (rings > 1) {
      EXPECT_NEAR(previous_error / error, 4.0, 0.2) << rings; // second order
    }
    previous_error = error;
  }
  EXPECT_LT(previous_error / (pi * radius * radius), 2e-4);
}

TEST(CylinderBand, CountsSeamAndAreas) {
  const double radius = 0.4;
  const double height = 0.9;
  for (const auto& [n, rows] : {std::pair{3, 1}, std::pair{7, 3}, std::pair{32, 5}}) {
    const auto m = mesh::cylinder_band(radius, height, n, rows);
    const double circumference = 2 * pi * radius;
    EXPECT_EQ(m.vertex_count(), static_cast<std::size_t>(n * (rows + 1)));
    EXPECT_EQ(m.triangle_count(), static_cast<std::size_t>(2 * n * rows));
    expect_no_duplicate_positions(m);
    EXPECT_NEAR(total_material_area(m), circumference * height, 1e-15 * n * rows);
    // Each flat triangle spans chords where its uv spans arcs.
    const double chord_over_arc = std::sin(pi / n) / (pi / n);
    int seam_corners = 0;
    for (std::size_t t = 0; t < m.triangle_count(); ++t) {
      EXPECT_GT(material_area(m, t), 0.0);
      EXPECT_NEAR(surface_area(m, t) / material_area(m, t), chord_over_arc, 1e-12);
      // Outward normals.
      const Eigen::Vector3d centroid =
          (test::corner_position(m, t, 0) + test::corner_position(m, t, 1) +
           test::corner_position(m, t, 2)) /
          3.0;
      EXPECT_GT(test::area_normal(m, t).head<2>().dot(centroid.head<2>()), 0.0);
      double u_min = std::numeric_limits<double>::infinity();
      double u_max = -std::numeric_limits<double>::infinity();
      for (std::size_t c = 0; c < 3; ++c) {
        const Eigen::Vector3d& p = test::corner_position(m, t, c);
        const Eigen::Vector2d& uv = m.material_uv[t][c];
        EXPECT_EQ(uv.y(), p.z());
        EXPECT_NEAR(p.head<2>().norm(), radius, 1e-15);
        EXPECT_GE(uv.x(), 0.0);
        EXPECT_LE(uv.x(), circumference);
        u_min = std::min(u_min, uv.x());
        u_max = std::max(u_max, uv.x());
        // u is the arc length to the vertex, taken on this triangle's side.
        const double angle = std::atan2(p.y(), p.x());
        const double expected = radius * (angle < -1e-12 ? angle + 2 * pi : std::abs(angle));
        if (std::abs(uv.x() - circumference) < 1e-12 && std::abs(angle) < 1e-12) {
          ++seam_corners;
        } else {
          EXPECT_NEAR(uv.x(), expected, 1e-14);
        }
      }
      EXPECT_NEAR(u_max - u_min, circumference / n, 1e-14); // no triangle spans the seam
    }
    // The last column's triangles close the tube: 3 seam corners per row.
    EXPECT_EQ(seam_corners, 3 * rows);
    EXPECT_EQ(boundary_vertices(m).size(), static_cast<std::size_t>(2 * n));
  }
}

TEST(CylinderBand, ChordLengthIsExactlyAtRest) {
  const double radius = 0.4;
  const int n = 9;
  const auto m = mesh::cylinder_band(radius, 0.5, n, 2, BandLength::chord);
  EXPECT_NEAR(total_material_area(m), n * 2 * radius * std::sin(pi / n) * 0.5, 1e-15);
  for (std::size_t t = 0; t < m.triangle_count(); ++t) {
    // Isometric: every edge as long in 3D as in uv.
    for (std::size_t c = 0; c < 3; ++c) {
      const double length3d =
          (test::corner_position(m, t, (c + 1) % 3) - test::corner_position(m, t, c)).norm();
      const double length_uv = (m.material_uv[t][(c + 1) % 3] - m.material_uv[t][c]).norm();
      EXPECT_NEAR(length3d, length_uv, 1e-15);
    }
    EXPECT_NEAR(surface_area(m, t), material_area(m, t), 1e-15);
  }
}

TEST(SphereCap, PositionsOnTheSphereAndUvIsTheFlatDisk) {
  const double sphere = 0.25;
  const double cap = 1.2;
  for (const int rings : {1, 3, 6}) {
    const auto m = mesh::sphere_cap(sphere, cap, rings);
    const auto flat = mesh::disk(sphere * cap, rings);
    EXPECT_EQ(m.triangles, flat.triangles);
    EXPECT_EQ(m.material_uv, flat.material_uv);
    EXPECT_EQ(total_material_area(m), total_material_area(flat));
    EXPECT_EQ(m.positions[0], Eigen::Vector3d(0, 0, sphere));
    for (std::size_t t = 0; t < m.triangle_count(); ++t) {
      EXPECT_GT(material_area(m, t), 0.0);
      const Eigen::Vector3d centroid =
          (test::corner_position(m, t, 0) + test::corner_position(m, t, 1) +
           test::corner_position(m, t, 2)) /
          3.0;
      EXPECT_GT(test::area_normal(m, t).dot(centroid), 0.0); // outward
      for (std::size_t c = 0; c < 3; ++c) {
        const Eigen::Vector3d& p = test::corner_position(m, t, c);
        EXPECT_NEAR(p.norm(), sphere, 1e-15);
        // Geodesic distance from the pole = distance from the disk centre.
        const double polar = std::atan2(p.head<2>().norm(), p.z());
        EXPECT_NEAR(sphere * polar, m.material_uv[t][c].norm(), 1e-15);
        // Same azimuth.
        if (p.head<2>().norm() > 0.0) {
          EXPECT_NEAR(p.head<2>().normalized().dot(m.material_uv[t][c].normalized()), 1.0, 1e-14);
        }
      }
    }
    for (const int v : boundary_vertices(m))
      EXPECT_NEAR(m.positions[static_cast<std::size_t>(v)].z(), sphere * std::cos(cap), 1e-15);
  }
  // The 3D area approaches the spherical cap's 2 pi R^2 (1 - cos a).
  const auto fine = mesh::sphere_cap(sphere, cap, 40);
  double area = 0.0;
  for (std::size_t t = 0; t < fine.triangle_count(); ++t)
    area += surface_area(fine, t);
  EXPECT_NEAR(area / (2 * pi * sphere * sphere * (1 - std::cos(cap))), 1.0, 2e-3);
}

TEST(Refine, QuadruplesTrianglesAndKeepsMaterialArea) {
  auto rect = mesh::rectangle(1.0, 0.5, 3, 2, RectanglePattern::perturbed);
  rect.material_ids.assign(rect.triangle_count(), 0);
  for (std::size_t t = 0; t < rect.triangle_count(); ++t)
    rect.material_ids[t] = static_cast<int>(t % 3);
  const std::vector<TriangleMesh> meshes{rect, mesh::disk(1.0, 3), mesh::sphere_cap(1.0, 0.8, 2),
                                         mesh::cylinder_band(0.3, 0.2, 5, 2)};
  for (const auto& coarse : meshes) {
    const auto fine = mesh::refine(coarse);
    EXPECT_NO_THROW(validate(fine, "refined"));
    // One new vertex per edge; the boundaries here are closed loops, with as
    // many edges as vertices.
    const std::size_t edges = interior_edges(coarse).size() + boundary_vertices(coarse).size();
    EXPECT_EQ(fine.triangle_count(), 4 * coarse.triangle_count());
    EXPECT_EQ(fine.vertex_count(), coarse.vertex_count() + edges);
    EXPECT_NEAR(total_material_area(fine), total_material_area(coarse),
                1e-15 * static_cast<double>(fine.triangle_count()));
    for (std::size_t t = 0; t < coarse.triangle_count(); ++t) {
      for (std::size_t k = 0; k < 4; ++k)
        EXPECT_NEAR(material_area(fine, 4 * t + k), material_area(coarse, t) / 4, 1e-15);
      for (std::size_t c = 0; c < 3; ++c) {
        // Corner children keep the corner's vertex and uv.
        EXPECT_EQ(fine.triangles[4 * t + c][c], coarse.triangles[t][c]);
        EXPECT_EQ(fine.material_uv[4 * t + c][c], coarse.material_uv[t][c]);
      }
    }
    // Old vertices keep their places; new ones are edge midpoints.
    for (std::size_t v = 0; v < coarse.vertex_count(); ++v)
      EXPECT_EQ(fine.positions[v], coarse.positions[v]);
    expect_no_duplicate_positions(fine);
    if (coarse.material_ids.empty()) {
      EXPECT_TRUE(fine.material_ids.empty());
    } else {
      for (std::size_t t = 0; t < fine.triangle_count(); ++t)
        EXPECT_EQ(fine.material_ids[t], coarse.material_ids[t / 4]);
    }
    EXPECT_EQ(interior_edges(fine).size(),
              2 * interior_edges(coarse).size() + 3 * coarse.triangle_count());
  }
}

TEST(Refine, RefinedBandKeepsItsSeam) {
  const double radius = 0.3;
  const auto fine = mesh::refine(mesh::cylinder_band(radius, 0.2, 4, 1));
  EXPECT_EQ(fine.vertex_count(), 8u + 16); // + midpoints: bottom, top, vertical, diagonal
  int seam_hinges = 0;
  for (const Hinge& h : interior_edges(fine)) {
    const auto u = [&](std::size_t k, std::size_t i) {
      return fine
          .material_uv[static_cast<std::size_t>(h.triangles[k])]
                      [static_cast<std::size_t>(h.corners[k][i])]
          .x();
    };
    if (u(0, 0) != u(1, 1)) {
      ++seam_hinges;
      EXPECT_NEAR(std::abs(u(0, 0) - u(1, 1)), 2 * pi * radius, 1e-15);
    }
  }
  EXPECT_EQ(seam_hinges, 2); // the seam edge, split in two
}

TEST(Annulus, RefinedVerticesStayOnCirclesAndTheSlitStaysOpen) {
  const double inner = 6.0, outer = 10.0, lift = 1e-3;
  const int rings = 2, segments = 8;
  for (const int refinements : {0, 1, 2}) {
    const auto m = mesh::annulus(inner, outer, rings, segments, 0.0, 2 * pi,
                                 RectanglePattern::perturbed, refinements, lift);
    const int n = 1 << refinements;
    EXPECT_EQ(m.vertex_count(), static_cast<std::size_t>((rings * n + 1) * (segments * n + 1)));
    EXPECT_EQ(m.triangle_count(), static_cast<std::size_t>(2 * rings * segments * n * n));
    expect_positive_material_areas(m);
    int on_inner = 0, on_outer = 0, at_slit_start = 0, at_slit_end = 0;
    for (const auto& p : m.positions) {
      const double r = p.head<2>().norm();
      EXPECT_GE(r, inner - 1e-12);
      EXPECT_LE(r, outer + 1e-12);
      on_inner += std::abs(r - inner) < 1e-12;
      on_outer += std::abs(r - outer) < 1e-12;
      // The helix: z grows with the angle from 0 to `lift` across the slit.
      const double angle = std::atan2(p.y(), p.x());
      if (std::abs(p.y()) < 1e-12 && p.x() > 0.0) {
        (p.z() < 0.5 * lift ? at_slit_start : at_slit_end) += 1;
      } else {
        EXPECT_NEAR(p.z(), lift * (angle < 0.0 ? angle + 2 * pi : angle) / (2 * pi), 1e-12);
      }
    }
    // Refined in the polar parameters: every boundary vertex on its circle.
    EXPECT_EQ(on_inner, segments * n + 1);
    EXPECT_EQ(on_outer, segments * n + 1);
    // Two edges of rings * n + 1 vertices each on the slit, never joined.
    EXPECT_EQ(at_slit_start, rings * n + 1);
    EXPECT_EQ(at_slit_end, rings * n + 1);
    EXPECT_EQ(boundary_vertices(m).size(),
              static_cast<std::size_t>(2 * (segments * n + rings * n)));
  }
  // Perturbed, with a sector beyond the slit: the grid line at angle 0 stays
  // straight (beside the loaded edge at 2 pi).
  for (const int refinements : {0, 1}) {
    const auto m = mesh::annulus(inner, outer, rings, 33, -pi / 16, 2 * pi,
                                 RectanglePattern::perturbed, refinements, lift);
    int on_positive_x_axis = 0;
    for (const auto& p : m.positions)
      on_positive_x_axis += std::abs(p.y()) < 1e-12 && p.x() > 0.0;
    EXPECT_EQ(on_positive_x_axis, 2 * (rings * (1 << refinements) + 1));
  }
  // The area converges to the annulus' at second order (chords of the circles).
  const auto error = [&](int refinements) {
    return pi * (outer * outer - inner * inner) -
           total_material_area(mesh::annulus(inner, outer, rings, segments, 0.0, 2 * pi,
                                             RectanglePattern::alternating, refinements));
  };
  EXPECT_NEAR(error(2) / error(3), 4.0, 0.05);
}

TEST(Generators, RejectBadArgumentsNamingTheParameter) {
  const std::vector<std::pair<std::function<void()>, std::string>> cases{
      {[] { mesh::rectangle(0.0, 1.0, 2, 2); }, "rectangle: width must be a positive"},
      {[] { mesh::rectangle(1.0, std::numeric_limits<double>::quiet_NaN(), 2, 2); },
       "rectangle: height must be a positive"},
      {[] { mesh::rectangle(1.0, 1.0, 0, 2); }, "rectangle: nx must be at least 1, got 0"},
      {[] { mesh::rectangle(1.0, 1.0, 2, -3); }, "rectangle: ny must be at least 1, got -3"},
      {[] { mesh::rectangle(1.0, 1.0, 100000, 100000); }, "more than the mesh's indices"},
      {[] { mesh::disk(-1.0, 2); }, "disk: radius must be a positive"},
      {[] { mesh::disk(1.0, 0); }, "disk: rings must be at least 1"},
      {[] { mesh::cylinder_band(std::numeric_limits<double>::infinity(), 1.0, 8, 2); },
       "cylinder_band: radius must be"},
      {[] { mesh::cylinder_band(1.0, 0.0, 8, 2); }, "cylinder_band: height must be"},
      {[] { mesh::cylinder_band(1.0, 1.0, 2, 2); }, "cylinder_band: segments must be at least 3"},
      {[] { mesh::cylinder_band(1.0, 1.0, 8, 0); }, "cylinder_band: rows must be at least 1"},
      {[] { mesh::sphere_cap(0.0, 1.0, 2); }, "sphere_cap: sphere_radius must be"},
      {[] { mesh::sphere_cap(1.0, pi, 2); }, "sphere_cap: cap_angle must lie strictly between"},
      {[] { mesh::sphere_cap(1.0, 0.0, 2); }, "sphere_cap: cap_angle"},
      {[] { mesh::sphere_cap(1.0, 1.0, 0); }, "sphere_cap: rings must be at least 1"},
      {[] { mesh::annulus(0.0, 1.0, 2, 8, 0.0, 1.0); }, "annulus: inner_radius must be a positive"},
      {[] { mesh::annulus(1.0, 1.0, 2, 8, 0.0, 1.0); }, "annulus: outer_radius must be"},
      {[] { mesh::annulus(1.0, 2.0, 2, 8, 1.0, 1.0); }, "annulus: the angles must be"},
      {[] { mesh::annulus(1.0, 2.0, 2, 8, 0.0, 13.0); }, "annulus: the angles must be"},
      {[] { mesh::annulus(1.0, 2.0, 2, 8, -2.0, -1.0, RectanglePattern::right, 0, 1.0); },
       "annulus: lift must be finite, and 0 unless end_angle > 0"},
      {[] { mesh::annulus(1.0, 2.0, 0, 8, 0.0, 1.0); }, "annulus: rings must be at least 1"},
      {[] {
         mesh::refine(TriangleMesh{{}, {{0, 1, 2}}, {}, {}, {}});
       },
       "refine: the mesh has 1"},
  };
  for (const auto& [call, expected] : cases) {
    try {
      call();
      ADD_FAILURE() << "no error; expected: " << expected;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
    }
  }
}

} // namespace
} // namespace sartor
