// Pre-folding and the pleat generator (docs/pleats.md): the geometry of a
// pre-folded panel and of generated pleats, checked against distances,
// angles and counts computed here.

#include "garment/pattern.hpp"
#include "garment/pleats.hpp"
#include "garment/prefold.hpp"
#include "mesh/panel_mesher.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace sartor::garment {
namespace {

// A 0.2 m square panel with a vertical creased fold line at x = 0.08.
std::string square_with_fold(const std::string& crease) {
  return R"({"format": "sartor-pattern", "version": 1, "panels": [{
    "id": "square", "fabric": "cotton_twill",
    "tag": {"cylinder": "torso", "side": "front"}, "grain": {"angle_deg": 90},
    "outline": [
      {"id": "bottom_l", "type": "straight", "points": [[0, 0], [0.08, 0]]},
      {"id": "bottom_r", "type": "straight", "points": [[0.08, 0], [0.2, 0]]},
      {"id": "right", "type": "straight", "points": [[0.2, 0], [0.2, 0.2]]},
      {"id": "top_r", "type": "straight", "points": [[0.2, 0.2], [0.08, 0.2]]},
      {"id": "top_l", "type": "straight", "points": [[0.08, 0.2], [0, 0.2]]},
      {"id": "left", "type": "straight", "points": [[0, 0.2], [0, 0]]}],
    "interior": [{"id": "fold", "kind": "fold", "type": "straight",
                  "points": [[0.08, 0], [0.08, 0.2]], "crease": )" +
         crease + "}]}]}";
}

PanelMesh mesh_of(const Panel& panel, double edge_length) {
  PanelMeshOptions options;
  options.edge_length = edge_length;
  return mesh_panel(panel, options);
}

TEST(Prefold, SquareFoldIsARigidRotationOfItsWarpingRegion) {
  const double angle = 70.0 * M_PI / 180.0;
  const Pattern pattern = parse_pattern(
      square_with_fold(R"({"side": "right", "angle_deg": 70, "toward": "outside"})"), "square");
  const PanelMesh meshed = mesh_of(pattern.panels[0], 0.02);
  const auto folds = meshed_folds(pattern.panels[0], meshed, true);
  ASSERT_EQ(folds.size(), 1u);
  const auto folded = prefold(meshed.mesh, folds);
  const auto& flat = meshed.mesh.positions;
  std::vector<bool> warped(flat.size(), false);
  for (int v : warping_region(meshed.mesh, folds[0]))
    warped[std::size_t(v)] = true;
  int moved = 0;
  for (std::size_t v = 0; v < flat.size(); ++v) {
    const double x = flat[v].x();
    // The warping region is every vertex right of the line, and only those.
    EXPECT_EQ(warped[v], x > 0.08 + 1e-9) << "vertex " << v << " at x = " << x;
    if (!warped[v]) {
      EXPECT_LT((folded[v] - flat[v]).norm(), 1e-15);
      continue;
    }
    ++moved;
    // A turn about the line x = 0.08 (along y): the offset from the line
    // keeps its length and turns by the angle, towards +z (outside).
    const Eigen::Vector2d arm(x - 0.08, 0.0);
    const Eigen::Vector2d turned(folded[v].x() - 0.08, folded[v].z());
    EXPECT_NEAR(folded[v].y(), flat[v].y(), 1e-12);
    EXPECT_NEAR(turned.norm(), arm.norm(), 1e-12);
    EXPECT_NEAR(std::atan2(turned.y(), turned.x()), angle, 1e-9);
  }
  EXPECT_GT(moved, 20);
  // Distances within the region and across the line are kept.
  for (std::size_t a = 0; a < flat.size(); a += 7)
    for (std::size_t b = 0; b < flat.size(); b += 5)
      if (warped[a] == warped[b]) {
        EXPECT_NEAR((folded[a] - folded[b]).norm(), (flat[a] - flat[b]).norm(), 1e-12);
      }
}

TEST(Prefold, CreaseEdgesLieOnTheFoldLineWithTheSignedRestAngle) {
  for (const bool outside : {true, false}) {
    const Pattern pattern = parse_pattern(
        square_with_fold(std::string(R"({"side": "left", "angle_deg": 120, "toward": ")") +
                         (outside ? "outside" : "inside") + "\"}"),
        "square");
    const PanelMesh meshed = mesh_of(pattern.panels[0], 0.02);
    const auto folds = meshed_folds(pattern.panels[0], meshed, true);
    const auto edges = crease_edges(folds, 100);
    ASSERT_GE(edges.size(), 10u);
    double length = 0.0;
    for (const auto& edge : edges) {
      const auto& a = meshed.mesh.positions[std::size_t(edge.a - 100)];
      const auto& b = meshed.mesh.positions[std::size_t(edge.b - 100)];
      EXPECT_NEAR(a.x(), 0.08, 1e-12);
      EXPECT_NEAR(b.x(), 0.08, 1e-12);
      length += (a - b).norm();
      // Turned towards the triangles' normal side (outside here): a valley
      // seen from there, a negative dihedral angle (element/bending.hpp).
      EXPECT_NEAR(edge.rest_angle, (outside ? -1.0 : 1.0) * 120.0 * M_PI / 180.0, 1e-12);
    }
    EXPECT_NEAR(length, 0.2, 1e-12);
  }
}

// A 0.6 x 0.5 m rectangle with straight side lines top and bottom.
std::string pleated_rectangle(const std::string& type, int slashes, const std::string& sew) {
  return R"({"format": "sartor-pattern", "version": 1, "panels": [{
    "id": "sheet", "fabric": "cotton_twill",
    "tag": {"cylinder": "torso", "side": "front"}, "grain": {"angle_deg": 90},
    "outline": [
      {"id": "hem", "type": "straight", "points": [[0, 0], [0.6, 0]]},
      {"id": "right", "type": "straight", "points": [[0.6, 0], [0.6, 0.5]]},
      {"id": "waist", "type": "straight", "points": [[0.6, 0.5], [0, 0.5]]},
      {"id": "left", "type": "straight", "points": [[0, 0.5], [0, 0]]}]}],
    "pleats": [{"id": "p", "panel": "sheet", "side_lines": ["waist", "hem"],
      "stationary": "left", "type": ")" +
         type + R"(", "slash_lines": )" + std::to_string(slashes) +
         R"(, "depth": 0.03, "out_fold_deg": 170, "in_fold_deg": 150, "sew": ")" + sew + R"("}]})";
}

TEST(Pleats, GeneratorMakesThePleatsStitchesAndCreasesAsked) {
  struct Case {
    std::string type;
    int creases_per_pleat;
    double width; // of the insert, depths
  };
  for (const Case& c : {Case{"knife", 2, 2.0}, Case{"box", 4, 4.0}, Case{"inverted_box", 4, 4.0}}) {
    for (const std::string sew : {"first", "both"}) {
      const int slashes = 3;
      const double depth = 0.03;
      const Pattern pattern = parse_pattern(pleated_rectangle(c.type, slashes, sew), "sheet");
      const Panel& panel = pattern.panels[0];
      // Spread: the panel grew by one insert per slash line.
      EXPECT_NEAR(panel.area(1e-9), 0.5 * (0.6 + slashes * c.width * depth), 1e-12) << c.type;
      // Pleats counted from the creases: crease lines parallel to the left
      // side, in groups one insert wide (knife: one depth between its two
      // creases, box types: four), more than an insert between groups.
      std::vector<double> xs;
      for (const auto& line : panel.interior) {
        ASSERT_TRUE(line.crease) << line.id;
        EXPECT_NEAR(line.curve.start().x(), line.curve.end().x(), 1e-12);
        xs.push_back(line.curve.start().x());
      }
      std::sort(xs.begin(), xs.end());
      std::vector<std::vector<double>> pleats{{xs.front()}};
      for (std::size_t i = 1; i < xs.size(); ++i) {
        if (xs[i] - xs[i - 1] > c.width * depth + 1e-9) pleats.emplace_back();
        pleats.back().push_back(xs[i]);
      }
      EXPECT_EQ(int(pleats.size()), slashes) << c.type;
      for (const auto& creases : pleats) {
        EXPECT_EQ(int(creases.size()), c.creases_per_pleat) << c.type;
        EXPECT_NEAR(creases.back() - creases.front(),
                    (c.creases_per_pleat == 2 ? 1.0 : 4.0) * depth, 1e-12);
      }
      // Stitches: per pleat and sewn side line, each pair of folded-onto
      // each other insert segments, of equal length (one depth).
      const int sewn_sides = sew == "both" ? 2 : 1;
      EXPECT_EQ(int(pattern.stitches.size()), slashes * sewn_sides * c.creases_per_pleat / 2)
          << c.type;
      const auto length_of = [&](const std::string& id) {
        for (const auto& line : panel.outline)
          if (line.id == id) return line.curve.length();
        ADD_FAILURE() << "no line " << id;
        return 0.0;
      };
      for (const auto& stitch : pattern.stitches) {
        EXPECT_TRUE(stitch.reverse);
        EXPECT_NEAR(length_of(stitch.line_a), depth, 1e-12);
        EXPECT_NEAR(length_of(stitch.line_b), depth, 1e-12);
      }
      // Rest angles: out-folds are ridges seen from outside (> 0 with the
      // triangles facing outside), in-folds valleys; their sizes as asked.
      const PanelMesh meshed = mesh_of(panel, 0.03);
      int out = 0, in = 0;
      for (const auto& fold : meshed_folds(panel, meshed, true)) {
        const bool is_out = fold.line.find("_out") != std::string::npos;
        (is_out ? out : in)++;
        EXPECT_NEAR(fold.rest_angle, is_out ? 170.0 * M_PI / 180 : -150.0 * M_PI / 180, 1e-12)
            << fold.line;
      }
      EXPECT_EQ(out + in, slashes * c.creases_per_pleat);
      EXPECT_EQ(out, in) << c.type;
    }
  }
}

TEST(Pleats, PrefoldedKnifePleatsReturnTheRestOfThePanelParallel) {
  // Equal in- and out-fold angles: each pleat's two turns cancel, so the
  // panel beyond the pleats is the flat panel moved, not turned: its
  // vertices keep their distances from the stationary panel's plane equal.
  std::string text = pleated_rectangle("knife", 2, "first");
  text.replace(text.find("\"in_fold_deg\": 150"), 18, "\"in_fold_deg\": 170");
  const Pattern pattern = parse_pattern(text, "sheet");
  const Panel& panel = pattern.panels[0];
  const PanelMesh meshed = mesh_of(panel, 0.03);
  const auto folds = meshed_folds(panel, meshed, true);
  const auto folded = prefold(meshed.mesh, folds);
  // The right side line (beyond every pleat): x > 0.6 + ... in the spread panel.
  const double right = 0.6 + 2 * 2 * 0.03;
  std::vector<double> z;
  double shift = 0.0;
  for (std::size_t v = 0; v < folded.size(); ++v) {
    if (std::abs(meshed.mesh.positions[v].x() - right) > 1e-9) continue;
    z.push_back(folded[v].z());
    shift = folded[v].x() - right;
  }
  ASSERT_GE(z.size(), 5u);
  for (double zv : z)
    EXPECT_NEAR(zv, z.front(), 1e-12);
  // Per pleat, in the xz plane from the out-fold: the far side starts at
  // d (cos 170, -sin 170) + (its distance s beyond the in-fold) (1, 0),
  // where flat it was at d + s: it comes back by d (1 - cos 170 deg).
  const double per_pleat = 0.03 * (1 - std::cos(170.0 * M_PI / 180));
  EXPECT_NEAR(shift, -2 * per_pleat, 1e-12);
  // Below the stationary plane (the out-folds turn towards the inside, -z).
  EXPECT_LT(z.front(), 0.0);
  EXPECT_NEAR(z.front(), -2 * 0.03 * std::sin(170.0 * M_PI / 180), 1e-12);
}

TEST(Pleats, BadSpecificationsNameTheEntry) {
  const auto error_of = [](const std::string& text) {
    try {
      parse_pattern(text, "sheet.json");
    } catch (const std::exception& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(error_of(pleated_rectangle("pinch", 2, "first"))
                .find("sheet.json: pleats[0].type: unknown pleat type 'pinch'"),
            std::string::npos);
  std::string stationary_side = pleated_rectangle("knife", 2, "first");
  stationary_side.replace(stationary_side.find("\"stationary\": \"left\""), 20,
                          "\"stationary\": \"hem\"");
  EXPECT_NE(error_of(stationary_side).find("the stationary line must not be a side line"),
            std::string::npos);
  // A pleat needs a depth.
  std::string flat = pleated_rectangle("knife", 2, "first");
  flat.replace(flat.find("\"depth\": 0.03"), 13, "\"depth\": 0");
  EXPECT_NE(error_of(flat).find("pleats[0].depth: must lie in (0,"), std::string::npos);
  // A pressed crease is no softer than the fabric.
  std::string soft = pleated_rectangle("knife", 2, "first");
  soft.replace(soft.find("\"sew\""), 5, "\"pressed\": 0.5, \"sew\"");
  EXPECT_NE(error_of(soft).find("pleats[0].pressed: must lie in ("), std::string::npos);
}

TEST(Pleats, PressedCreasesCarryTheirStiffnessToTheMesh) {
  std::string text = pleated_rectangle("box", 2, "first");
  text.replace(text.find("\"sew\""), 5, "\"pressed\": 30, \"sew\"");
  const Pattern pattern = parse_pattern(text, "sheet");
  const PanelMesh meshed = mesh_of(pattern.panels[0], 0.03);
  const auto folds = meshed_folds(pattern.panels[0], meshed, true);
  ASSERT_EQ(folds.size(), 8u); // four creases a box pleat
  for (const CreaseEdge& edge : crease_edges(folds, 0))
    EXPECT_EQ(edge.stiffness_factor, 30.0);
}

} // namespace
} // namespace sartor::garment
