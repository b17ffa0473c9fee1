// Panel meshing: triangle quality, area, material (u, v) along the grain,
// constrained interior lines, and the vertex lists of seam lines.

#include "common/error.hpp"
#include "garment/pattern.hpp"
#include "mesh/panel_mesher.hpp"
#include "pattern_fixtures.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <set>

namespace sartor {
namespace {

using Eigen::Vector2d;
using garment::testing::parse;
using garment::testing::pattern_of;
using garment::testing::square_panel;

const std::string samples = SARTOR_PATTERN_SAMPLES_DIR;

Vector2d xy(const TriangleMesh& mesh, int v) {
  return mesh.positions[v].head<2>();
}

std::set<std::pair<int, int>> edges_of(const TriangleMesh& mesh) {
  std::set<std::pair<int, int>> edges;
  for (const auto& t : mesh.triangles)
    for (int c = 0; c < 3; ++c)
      edges.insert(std::minmax(t[c], t[(c + 1) % 3]));
  return edges;
}

// Vertices along a line: consecutive ones joined by mesh edges, on the line
// (within `tolerance` of its flattening), moving forward.
void expect_line_path(const PanelMesh& result, const garment::Curve& curve, const MeshedLine& line,
                      double tolerance) {
  const auto edges = edges_of(result.mesh);
  const auto fine = curve.flatten(1e-9);
  ASSERT_GE(line.vertices.size(), 2u) << line.id;
  EXPECT_NEAR((xy(result.mesh, line.vertices.front()) - curve.start()).norm(), 0, 1e-12) << line.id;
  EXPECT_NEAR((xy(result.mesh, line.vertices.back()) - curve.end()).norm(), 0, 1e-12) << line.id;
  double previous = -1;
  for (std::size_t k = 0; k < line.vertices.size(); ++k) {
    const Vector2d p = xy(result.mesh, line.vertices[k]);
    double best = 1e9, along = 0, arc = 0;
    for (std::size_t s = 0; s + 1 < fine.size(); ++s) {
      const Vector2d d = fine[s + 1] - fine[s];
      const double f = std::clamp((p - fine[s]).dot(d) / d.squaredNorm(), 0.0, 1.0);
      const double distance = (p - fine[s] - f * d).norm();
      if (distance < best) {
        best = distance;
        along = arc + f * d.norm();
      }
      arc += d.norm();
    }
    EXPECT_LT(best, tolerance) << line.id << " vertex " << k;
    EXPECT_GT(along, previous) << line.id << " vertex " << k << " is out of order";
    previous = along;
    if (k > 0) {
      EXPECT_TRUE(edges.count(std::minmax(line.vertices[k - 1], line.vertices[k])))
          << line.id << ": vertices " << k - 1 << " and " << k << " are not joined by an edge";
    }
  }
}

double polygon_area(const std::vector<Vector2d>& polygon) {
  double twice = 0;
  for (std::size_t i = 0; i < polygon.size(); ++i)
    twice += polygon[i].x() * polygon[(i + 1) % polygon.size()].y() -
             polygon[i].y() * polygon[(i + 1) % polygon.size()].x();
  return 0.5 * twice;
}

TEST(PanelMesher, SquareQualityAreaAndSeamLines) {
  nlohmann::json document = pattern_of({square_panel("a", "a_")});
  document["panels"][0]["interior"] = {{{"id", "fold"},
                                        {"kind", "fold"},
                                        {"type", "straight"},
                                        {"points", {{0.05, 0.13}, {0.33, 0.29}}}}};
  const garment::Pattern pattern = parse(document);
  PanelMeshOptions options;
  options.edge_length = 0.05;
  options.min_angle_deg = 30;
  options.pieces["a_bottom"] = 13; // as a seam pairing would force it
  const PanelMesh result = mesh_panel(pattern.panels[0], options);

  EXPECT_GE(result.min_angle_deg, 30 - 1e-9); // no input angle below 30 degrees
  EXPECT_NEAR(result.area, 0.16, 1e-14);
  EXPECT_NEAR(result.boundary_area, 0.16, 1e-14);
  for (const auto& t : result.mesh.triangles)
    for (int c = 0; c < 3; ++c)
      EXPECT_LE((result.mesh.positions[t[c]] - result.mesh.positions[t[(c + 1) % 3]]).norm(),
                options.edge_length * (1 + 1e-9));

  ASSERT_EQ(result.lines.size(), 5u);
  const MeshedLine& bottom = result.lines[0];
  EXPECT_EQ(bottom.id, "a_bottom");
  EXPECT_TRUE(bottom.forced);
  EXPECT_FALSE(bottom.split_by_mesher);
  ASSERT_EQ(bottom.vertices.size(), 14u);
  for (std::size_t k = 0; k < bottom.vertices.size(); ++k)
    EXPECT_NEAR((xy(result.mesh, bottom.vertices[k]) - Vector2d(0.4 * double(k) / 13.0, 0)).norm(),
                0, 1e-15);
  // Unforced lines: equal pieces no longer than the edge length.
  for (std::size_t l = 1; l < 4; ++l) {
    const MeshedLine& line = result.lines[l];
    EXPECT_FALSE(line.split_by_mesher) << line.id;
    EXPECT_EQ(line.vertices.size(), std::size_t(line.pieces) + 1) << line.id;
    EXPECT_GE(line.pieces, 8) << line.id;
    const double piece = 0.4 / line.pieces;
    for (std::size_t k = 0; k + 1 < line.vertices.size(); ++k)
      EXPECT_NEAR(
          (xy(result.mesh, line.vertices[k + 1]) - xy(result.mesh, line.vertices[k])).norm(), piece,
          1e-15);
  }
  // Consecutive lines share their corner vertex; the outline comes first, in order.
  for (std::size_t l = 0; l < 4; ++l)
    EXPECT_EQ(result.lines[l].vertices.back(), result.lines[(l + 1) % 4].vertices.front());
  EXPECT_EQ(result.lines[0].vertices.front(), 0);
  for (std::size_t l = 0; l < 4; ++l)
    expect_line_path(result, pattern.panels[0].outline[l].curve, result.lines[l], 1e-12);
  // The interior line is made of mesh edges.
  EXPECT_TRUE(result.lines[4].interior);
  expect_line_path(result, pattern.panels[0].interior[0].curve, result.lines[4], 1e-12);
}

TEST(PanelMesher, MaterialCoordinatesFollowARotatedGrainLine) {
  nlohmann::json document = pattern_of({square_panel("a", "a_", 0.3)});
  document["panels"][0]["grain"] = {{"from", {0.1, 0.05}},
                                    {"to", {0.1 + std::cos(0.5), 0.05 + std::sin(0.5)}}};
  const garment::Pattern pattern = parse(document);
  PanelMeshOptions options;
  options.edge_length = 0.04;
  const PanelMesh result = mesh_panel(pattern.panels[0], options);
  const Vector2d warp(std::cos(0.5), std::sin(0.5)), weft(-std::sin(0.5), std::cos(0.5));
  for (std::size_t t = 0; t < result.mesh.triangle_count(); ++t) {
    const auto& triangle = result.mesh.triangles[t];
    const auto& uv = result.mesh.material_uv[t];
    for (int c = 0; c < 3; ++c) {
      const Vector2d p = xy(result.mesh, triangle[c]) - Vector2d(0.1, 0.05);
      EXPECT_NEAR(uv[c].x(), p.dot(warp), 1e-15); // u along the warp
      EXPECT_NEAR(uv[c].y(), p.dot(weft), 1e-15); // v along the weft
    }
    // Same orientation in (u, v) as in (x, y): counter-clockwise.
    const Vector2d du = uv[1] - uv[0], dv = uv[2] - uv[0];
    EXPECT_GT(du.x() * dv.y() - du.y() * dv.x(), 0);
  }
  EXPECT_NEAR(result.area, 0.09, 1e-14);
}

TEST(PanelMesher, SamplePanelsMeetTheCriteria) {
  for (const char* file : {"/skirt.json", "/tshirt.json"}) {
    const garment::Pattern pattern = garment::read_pattern(samples + file);
    for (const auto& panel : pattern.panels) {
      PanelMeshOptions options;
      options.edge_length = 0.03;
      options.min_angle_deg = 28;
      const PanelMesh result = mesh_panel(panel, options);
      EXPECT_GE(result.min_angle_regular_deg, 28 - 1e-9) << panel.id;
      // The mesh covers exactly the polygon through its boundary vertices ...
      EXPECT_NEAR(result.area, result.boundary_area, 1e-12) << panel.id;
      // ... which is the outline up to the segments between chords and curves
      // (about b^3 curvature / 12 per piece of length b; convergence below).
      const double outline = polygon_area(panel.outline_polygon(1e-9));
      EXPECT_NEAR(result.area, outline, 1e-3 * outline) << panel.id;
      for (std::size_t l = 0; l < panel.outline.size(); ++l) {
        EXPECT_FALSE(result.lines[l].split_by_mesher) << panel.id << " " << result.lines[l].id;
        expect_line_path(result, panel.outline[l].curve, result.lines[l], 1e-8);
      }
      for (std::size_t l = 0; l < panel.interior.size(); ++l)
        expect_line_path(result, panel.interior[l].curve, result.lines[panel.outline.size() + l],
                         1e-12);
    }
  }
}

TEST(PanelMesher, AreaConvergesToTheOutlineAtSecondOrder) {
  const garment::Pattern shirt = garment::read_pattern(samples + "/tshirt.json");
  const garment::Panel& back = *shirt.find_panel("back");
  const double outline = polygon_area(back.outline_polygon(1e-10));
  std::vector<double> errors;
  for (double edge_length : {0.04, 0.02}) {
    PanelMeshOptions options;
    options.edge_length = edge_length;
    errors.push_back(std::abs(mesh_panel(back, options).area - outline));
  }
  EXPECT_GT(errors[0] / errors[1], 3.0); // pieces halve: the chord error quarters
  EXPECT_LT(errors[0] / errors[1], 5.5);
}

TEST(PanelMesher, ForcedCountsAreKeptOnCurvedLines) {
  const garment::Pattern shirt = garment::read_pattern(samples + "/tshirt.json");
  const garment::Panel& back = *shirt.find_panel("back");
  PanelMeshOptions options;
  options.edge_length = 0.03;
  options.pieces["bk_armhole_r"] = 11;
  options.pieces["bk_neck"] = 9;
  const PanelMesh result = mesh_panel(back, options);
  for (const auto& line : result.lines) {
    if (line.id == "bk_armhole_r" || line.id == "bk_neck") {
      EXPECT_TRUE(line.forced);
      EXPECT_EQ(line.vertices.size(), std::size_t(line.pieces) + 1) << line.id;
      EXPECT_EQ(line.pieces, line.id == "bk_neck" ? 9 : 11);
    }
  }
}

TEST(PanelMesher, RejectsBadOptions) {
  const garment::Pattern pattern = parse(pattern_of({square_panel("a", "a_")}));
  PanelMeshOptions options;
  options.edge_length = 0;
  EXPECT_THROW(mesh_panel(pattern.panels[0], options), InputError);
  options.edge_length = 0.05;
  options.min_angle_deg = 40;
  EXPECT_THROW(mesh_panel(pattern.panels[0], options), InputError);
  options.min_angle_deg = 25;
  options.pieces["a_top"] = 0;
  EXPECT_THROW(mesh_panel(pattern.panels[0], options), InputError);
}

TEST(PanelMesher, PiecesFor) {
  const double longest = boundary_piece_fraction * 0.05;
  EXPECT_EQ(pieces_for(8 * longest, 0.05), 8);
  EXPECT_EQ(pieces_for(8.01 * longest, 0.05), 9);
  EXPECT_EQ(pieces_for(0.01, 0.05), 1);
}

} // namespace
} // namespace sartor
