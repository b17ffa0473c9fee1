// The pattern reader: the samples, every class of validation error, outline
// orientation, units, Bezier flattening and arc length, sheet layout, SVG.

#include "common/error.hpp"
#include "garment/pattern.hpp"
#include "garment/pattern_svg.hpp"
#include "pattern_fixtures.hpp"

#include <unistd.h>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <functional>

namespace sartor::garment {
namespace {

using Eigen::Vector2d;
using nlohmann::json;
using testing::parse;
using testing::pattern_of;
using testing::square_panel;
using testing::straight;

const std::string samples = SARTOR_PATTERN_SAMPLES_DIR;

// The message of the InputError that parsing `document` throws.
std::string error_of(const json& document) {
  try {
    parse(document);
  } catch (const InputError& error) {
    return error.what();
  }
  return "(no error)";
}

TEST(PatternSamples, SkirtHasTwoTorsoPanels) {
  const Pattern skirt = read_pattern(samples + "/skirt.json");
  ASSERT_EQ(skirt.panels.size(), 2u);
  EXPECT_EQ(skirt.packs.size(), 2u); // implicit single-panel packs
  EXPECT_TRUE(skirt.packs[0].implicit);
  EXPECT_EQ(skirt.panels[0].tag, (PanelTag{Cylinder::torso, Side::front, 0}));
  EXPECT_EQ(skirt.panels[1].tag, (PanelTag{Cylinder::torso, Side::back, 0}));
  EXPECT_EQ(skirt.panels[0].interior.size(), 1u);
  for (const auto& panel : skirt.panels) {
    EXPECT_FALSE(panel.reversed);
    const double area = panel.area(1e-7);
    EXPECT_GT(area, 0.25); // about 0.6 m long, 0.36 to 0.6 m wide
    EXPECT_LT(area, 0.32);
  }
  // Grain from two points: vertical, origin at the first point.
  EXPECT_NEAR(skirt.panels[1].grain.warp.y(), 1.0, 1e-15);
  EXPECT_NEAR(skirt.panels[1].grain.origin.x(), 0.30, 1e-15);
}

TEST(PatternSamples, SkirtHasSloperParameters) {
  const Pattern skirt = read_pattern(samples + "/skirt.json");
  ASSERT_EQ(skirt.parameters.size(), 2u);
  const SloperParameter& length = skirt.parameters[0];
  EXPECT_EQ(length.id, "skirt_length");
  ASSERT_EQ(length.moves.size(), 3u);
  EXPECT_EQ(length.moves[2].line, "sb_hem");
  EXPECT_EQ(length.moves[2].corner, ParameterMove::Corner::both);
  EXPECT_EQ(length.moves[2].per_unit, Vector2d(0, -1));
  const SloperParameter& width = skirt.parameters[1];
  EXPECT_EQ(width.moves[0].corner, ParameterMove::Corner::start);
  EXPECT_EQ(width.moves[1].corner, ParameterMove::Corner::end);
  EXPECT_EQ(width.moves[3].per_unit, Vector2d(0.5, 0));
}

TEST(PatternSamples, TshirtHasTagsPacksAndLayers) {
  const Pattern shirt = read_pattern(samples + "/tshirt.json");
  ASSERT_EQ(shirt.panels.size(), 8u);
  EXPECT_EQ(shirt.packs.size(), 7u); // front pack of two, six single-panel packs
  EXPECT_EQ(shirt.packs[0].id, "front");
  EXPECT_FALSE(shirt.packs[0].implicit);
  EXPECT_EQ(shirt.packs[0].members.size(), 2u);
  EXPECT_EQ(shirt.pack_of(1), 0); // front_r
  const Panel* pocket = shirt.find_panel("pocket");
  ASSERT_NE(pocket, nullptr);
  EXPECT_EQ(pocket->tag.layer, 1);
  EXPECT_EQ(pocket->fabric, "denim");
  EXPECT_EQ(shirt.find_panel("sleeve_r_back")->tag.cylinder, Cylinder::arm_r);
  EXPECT_EQ(shirt.find_panel("front_l")->interior.at(0).kind, InteriorLine::Kind::t_seam);
}

// ---------------------------------------------------- validation errors ----

struct ErrorCase {
  const char* name;
  std::function<void(json&)> breakage;
  std::vector<std::string> expected; // substrings of the message
};

void PrintTo(const ErrorCase& error_case, std::ostream* out) {
  *out << error_case.name;
}

class PatternErrors : public ::testing::TestWithParam<ErrorCase> {};

TEST_P(PatternErrors, SayWhereAndWhat) {
  json document = pattern_of({square_panel("a", "a_"), square_panel("b", "b_", 0.4, 0.5)});
  GetParam().breakage(document);
  const std::string message = error_of(document);
  EXPECT_EQ(message.rfind("test.json: ", 0), 0u) << message;
  for (const auto& expected : GetParam().expected)
    EXPECT_NE(message.find(expected), std::string::npos) << "missing '" << expected << "' in\n"
                                                         << message;
}

const std::vector<ErrorCase> error_cases = {
    {"NotAnObject", [](json& d) { d = "panels"; }, {"expected an object, got string"}},
    {"WrongFormat", [](json& d) { d["format"] = "dxf"; }, {"format: expected \"sartor-pattern\""}},
    {"FutureVersion", [](json& d) { d["version"] = 2; }, {"version: unsupported version 2"}},
    {"UnknownUnits", [](json& d) { d["units"] = "in"; }, {"units: unknown units 'in'"}},
    {"NegativeTolerance", [](json& d) { d["tolerance"] = -1; }, {"tolerance: must be > 0"}},
    {"UnknownKey",
     [](json& d) { d["panels"][0]["fabirc"] = "silk"; },
     {"panels[0]: unknown key 'fabirc'", "fabric"}},
    {"MissingGrain",
     [](json& d) { d["panels"][1].erase("grain"); },
     {"panels[1]: missing field 'grain'"}},
    {"MissingOutline",
     [](json& d) { d["panels"][0].erase("outline"); },
     {"panels[0]: missing field 'outline'"}},
    {"PointNotNumber",
     [](json& d) { d["panels"][0]["outline"][2]["points"][0][1] = "x"; },
     {"panels[0].outline[2].points[0][1]: expected a number, got string"}},
    {"PointOfThree",
     [](json& d) {
       d["panels"][0]["outline"][1]["points"][1] = {1, 2, 3};
     },
     {"panels[0].outline[1].points[1]: expected a point [x, y], got 3 numbers"}},
    {"OutlineNotArray",
     [](json& d) { d["panels"][0]["outline"] = 3; },
     {"panels[0].outline: expected an array, got number"}},
    {"LayerNotInteger",
     [](json& d) { d["panels"][0]["tag"]["layer"] = 0.5; },
     {"panels[0].tag.layer: expected an integer, got 0.5"}},
    {"BezierWithThreePoints",
     [](json& d) {
       d["panels"][0]["outline"][0] = {
           {"id", "a_bottom"}, {"type", "bezier"}, {"points", {{0, 0}, {0.2, -0.1}, {0.4, 0}}}};
     },
     {"panels[0].outline[0].points: a bezier curve takes 4 points, got 3"}},
    {"UnknownCurveType",
     [](json& d) { d["panels"][0]["outline"][0]["type"] = "arc"; },
     {"panels[0].outline[0].type: unknown curve type 'arc'"}},
    {"ZeroLengthLine",
     [](json& d) { d["panels"][0]["outline"].push_back(straight("a_dot", 0, 0, 0, 0)); },
     {"panels[0].outline[4]: the straight has zero length"}},
    {"ZeroLengthGrain",
     [](json& d) {
       d["panels"][0]["grain"] = {{"from", {0.1, 0.1}}, {"to", {0.1, 0.1}}};
     },
     {"panels[0].grain: the grain line has zero length"}},
    {"GrainTwice",
     [](json& d) {
       d["panels"][0]["grain"] = {{"from", {0.1, 0.1}}, {"to", {0.1, 0.2}}, {"angle_deg", 90}};
     },
     {"panels[0].grain: give the grain line either"}},
    {"Unclosed",
     [](json& d) {
       d["panels"][1]["outline"][2]["points"][1] = {0.502, 0.4};
     },
     {"panels[1].outline[2]: the outline is not closed", "'b_top' ends at (0.502, 0.4)",
      "'b_left' starts at (0.5, 0.4)"}},
    {"SelfIntersecting",
     [](json& d) {
       d["panels"][0]["outline"] = {straight("x1", 0, 0, 0.4, 0.4),
                                    straight("x2", 0.4, 0.4, 0.4, 0),
                                    straight("x3", 0.4, 0, 0, 0.4), straight("x4", 0, 0.4, 0, 0)};
     },
     {"panels[0].outline: the outline intersects itself near (0.2, 0.2)",
      "panels[0].outline[0] ('x1') meets panels[0].outline[2] ('x3')"}},
    {"FoldsBack",
     [](json& d) {
       d["panels"][0]["outline"] = {straight("f1", 0, 0, 0.4, 0), straight("f2", 0.4, 0, 0.2, 0),
                                    straight("f3", 0.2, 0, 0.2, 0.3),
                                    straight("f4", 0.2, 0.3, 0, 0)};
     },
     {"the outline folds back on itself at (0.4, 0)"}},
    {"DuplicatePanelId",
     [](json& d) { d["panels"][1]["id"] = "a"; },
     {"panels[1].id: duplicate panel id 'a'"}},
    {"DuplicateLineId",
     [](json& d) { d["panels"][1]["outline"][3]["id"] = "a_top"; },
     {"panels[1].outline[3].id: duplicate line id 'a_top'"}},
    {"EmptyId",
     [](json& d) { d["panels"][1]["outline"][3]["id"] = ""; },
     {"panels[1].outline[3].id: an id must not be empty"}},
    {"UnknownCylinder",
     [](json& d) { d["panels"][0]["tag"]["cylinder"] = "tail"; },
     {"panels[0].tag.cylinder: unknown cylinder 'tail'", "torso, arm_l, arm_r"}},
    {"UnknownSide",
     [](json& d) { d["panels"][0]["tag"]["side"] = "left"; },
     {"panels[0].tag.side: unknown side 'left' (expected front or back)"}},
    {"UnknownFabric",
     [](json& d) { d["panels"][1]["fabric"] = "velvet"; },
     {"panels[1].fabric: unknown fabric 'velvet'", "cotton_twill"}},
    {"MissingFabricFile",
     [](json& d) { d["panels"][1]["fabric"] = "nowhere.yaml"; },
     {"panels[1].fabric: fabric file", "does not exist"}},
    {"PackMixesTags",
     [](json& d) {
       d["panels"][1]["tag"]["side"] = "back";
       d["packs"] = {{{"id", "p"}, {"panels", {{{"panel", "a"}}, {{"panel", "b"}}}}}};
     },
     {"packs[0].panels[1].panel: pack 'p' mixes tags",
      "panel 'b' is (torso, back, 0) but panel 'a' is (torso, front, 0)"}},
    {"PackMixesLayers",
     [](json& d) {
       d["panels"][1]["tag"]["layer"] = 1;
       d["packs"] = {{{"id", "p"}, {"panels", {{{"panel", "a"}}, {{"panel", "b"}}}}}};
     },
     {"pack 'p' mixes tags"}},
    {"PanelInTwoPacks",
     [](json& d) {
       d["packs"] = {{{"id", "p"}, {"panels", {{{"panel", "a"}}}}},
                     {{"id", "q"}, {"panels", {{{"panel", "a"}}}}}};
     },
     {"packs[1].panels[0].panel: panel 'a' is already in pack 'p'"}},
    {"PackOfUnknownPanel",
     [](json& d) {
       d["packs"] = {{{"id", "p"}, {"panels", {{{"panel", "zz"}}}}}};
     },
     {"packs[0].panels[0].panel: unknown panel 'zz'"}},
    {"InteriorLeavesPanel",
     [](json& d) {
       d["panels"][0]["interior"] = {{{"id", "fold"},
                                      {"kind", "fold"},
                                      {"type", "straight"},
                                      {"points", {{0.1, 0.1}, {0.6, 0.1}}}}};
     },
     {"panels[0].interior[0]: interior line 'fold' meets the outline at (0.4, 0.1)",
      "not a corner"}},
    {"InteriorOutside",
     [](json& d) {
       d["panels"][0]["interior"] = {{{"id", "fold"},
                                      {"kind", "fold"},
                                      {"type", "straight"},
                                      {"points", {{0.5, 0.1}, {0.6, 0.1}}}}};
     },
     {"panels[0].interior[0]: interior line 'fold' leaves the panel"}},
    {"InteriorKind",
     [](json& d) {
       d["panels"][0]["interior"] = {{{"id", "fold"},
                                      {"kind", "dart"},
                                      {"type", "straight"},
                                      {"points", {{0.1, 0.1}, {0.2, 0.1}}}}};
     },
     {"panels[0].interior[0].kind: unknown interior line kind 'dart'"}},
    {"ParameterNotArray",
     [](json& d) {
       d["parameters"] = {{"id", "length"}};
     },
     {"parameters: expected an array, got object"}},
    {"ParameterWithoutId",
     [](json& d) {
       d["parameters"] = {{{"moves", json::array()}}};
     },
     {"parameters[0]: a parameter needs a non-empty string 'id'"}},
    {"ParameterUnknownLine",
     [](json& d) {
       d["parameters"] = {
           {{"id", "length"}, {"moves", {{{"line", "a_hem"}, {"per_unit", {0, -1}}}}}}};
     },
     {"parameters[0].moves[0].line: 'a_hem' is not an outline line of the pattern"}},
    {"ParameterDuplicateId",
     [](json& d) {
       const json move = {{"line", "a_bottom"}, {"per_unit", {0, -1}}};
       d["parameters"] = {{{"id", "length"}, {"moves", {move}}},
                          {{"id", "length"}, {"moves", {move}}}};
     },
     {"parameters[1].id: duplicate parameter id 'length'"}},
    {"ParameterPerUnitTooLarge",
     [](json& d) {
       d["parameters"] = {
           {{"id", "length"}, {"moves", {{{"line", "a_bottom"}, {"per_unit", {0, -100}}}}}}};
     },
     {"parameters[0].moves[0].per_unit: a move of 100 m per m: at most 10"}},
    {"ParameterBadCorner",
     [](json& d) {
       d["parameters"] = {
           {{"id", "length"},
            {"moves", {{{"line", "a_bottom"}, {"corner", "middle"}, {"per_unit", {0, -1}}}}}}};
     },
     {"parameters[0].moves[0].corner: expected \"start\" or \"end\""}},
    {"ParameterMovesACornerTwoWays",
     [](json& d) {
       d["parameters"] = {{{"id", "length"},
                           {"moves",
                            {{{"line", "a_bottom"}, {"per_unit", {0, -1}}},
                             {{"line", "a_right"}, {"per_unit", {1, 0}}}}}}};
     },
     {"parameters[0].moves[1]: moves the corner it shares with an earlier move of this "
      "parameter differently"}},
};

INSTANTIATE_TEST_SUITE_P(Pattern, PatternErrors, ::testing::ValuesIn(error_cases),
                         [](const auto& test) { return std::string(test.param.name); });

TEST(PatternFiles, MalformedJsonSaysWhere) {
  try {
    parse_pattern("{\n  \"format\": \"sartor-pattern\",\n  \"version\" 1\n}", "bad.json");
    FAIL() << "no error";
  } catch (const InputError& error) {
    const std::string message = error.what();
    EXPECT_EQ(message.rfind("bad.json: not valid JSON: ", 0), 0u) << message;
    EXPECT_NE(message.find("line 3"), std::string::npos) << message;
  }
}

TEST(PatternFiles, MissingFileIsAnInputError) {
  EXPECT_THROW(read_pattern("/nonexistent/pattern.json"), InputError);
}

// ------------------------------------------------------ normalisation ----

TEST(PatternOrientation, ClockwiseOutlineTurnsCounterClockwise) {
  json document = pattern_of({square_panel("a", "a_")});
  json& outline = document["panels"][0]["outline"];
  // Clockwise: left edge up, top right, right edge down, bottom left.
  outline = {straight("up", 0, 0, 0, 0.4), straight("over", 0, 0.4, 0.4, 0.4),
             straight("down", 0.4, 0.4, 0.4, 0), straight("back", 0.4, 0, 0, 0)};
  const Pattern pattern = parse(document);
  const Panel& panel = pattern.panels[0];
  EXPECT_TRUE(panel.reversed);
  EXPECT_NEAR(panel.area(1e-9), 0.16, 1e-15);
  ASSERT_EQ(panel.outline.size(), 4u);
  EXPECT_EQ(panel.outline[0].id, "back"); // order reversed ...
  EXPECT_TRUE(panel.outline[0].reversed);
  EXPECT_EQ(panel.outline[0].curve.start(), Vector2d(0, 0)); // ... and each line turned round
  EXPECT_EQ(panel.outline[0].curve.end(), Vector2d(0.4, 0));
  EXPECT_EQ(panel.outline[3].id, "up");
  EXPECT_EQ(panel.outline[3].curve.end(), Vector2d(0, 0));
}

TEST(PatternUnits, CentimetresBecomeMetres) {
  json document = pattern_of({square_panel("a", "a_", 40)});
  document["units"] = "cm";
  const Pattern pattern = parse(document);
  EXPECT_NEAR(pattern.panels[0].area(1e-9), 0.16, 1e-14);
  EXPECT_NEAR(pattern.panels[0].outline[1].curve.length(), 0.4, 1e-15);
}

// The corners (and control points) a move of a line moves, by outline
// index: corner i starts line i, so line 3 of 4 ends at corner 0.
TEST(PatternOutline, MovedOutlinePointsAreTheLinesCornersOrItsControlPoint) {
  const Pattern pattern =
      parse(pattern_of({square_panel("a", "a_"), square_panel("b", "b_", 0.4, 0.5)}));
  const auto indices = [&](const std::string& line, LineCorners corners, int control = 0) {
    std::vector<std::array<std::size_t, 3>> found;
    for (const OutlinePoint& p : moved_outline_points(pattern, line, corners, control))
      found.push_back({p.panel, p.index, std::size_t(p.control)});
    return found;
  };
  using Points = std::vector<std::array<std::size_t, 3>>;
  EXPECT_EQ(indices("a_right", LineCorners::both), (Points{{0, 1, 0}, {0, 2, 0}}));
  EXPECT_EQ(indices("a_right", LineCorners::start), (Points{{0, 1, 0}}));
  EXPECT_EQ(indices("a_right", LineCorners::end), (Points{{0, 2, 0}}));
  EXPECT_EQ(indices("b_left", LineCorners::both), (Points{{1, 3, 0}, {1, 0, 0}}));
  EXPECT_EQ(indices("b_top", LineCorners::both, 2), (Points{{1, 2, 2}}));
  EXPECT_TRUE(indices("no_such_line", LineCorners::both).empty());
}

TEST(PatternOutline, SmallGapIsClosedExactly) {
  json document = pattern_of({square_panel("a", "a_")});
  document["panels"][0]["outline"][1]["points"][0] = {0.4 + 1e-7, 0};
  const Pattern pattern = parse(document);
  EXPECT_EQ(pattern.panels[0].outline[1].curve.start(), pattern.panels[0].outline[0].curve.end());
}

TEST(PatternInterior, LineMayEndAtCorners) {
  json document = pattern_of({square_panel("a", "a_")});
  document["panels"][0]["interior"] = {{{"id", "diagonal"},
                                        {"kind", "fold"},
                                        {"type", "straight"},
                                        {"points", {{0, 0}, {0.4, 0.4 + 1e-7}}}}};
  const Pattern pattern = parse(document);
  EXPECT_EQ(pattern.panels[0].interior[0].curve.end(), Vector2d(0.4, 0.4)); // snapped
}

// ------------------------------------------------------------- curves ----

Curve quarter_circle(double radius) {
  const double k = 0.5522847498307936 * radius; // the usual cubic approximation
  Curve curve;
  curve.kind = Curve::Kind::bezier;
  curve.points = {{radius, 0}, {radius, k}, {k, radius}, {0, radius}};
  return curve;
}

TEST(BezierFlattening, StaysWithinTolerance) {
  const Curve curve = quarter_circle(0.3);
  for (double tolerance : {1e-3, 1e-5, 1e-7}) {
    std::vector<double> t;
    const auto points = curve.flatten(tolerance, &t);
    ASSERT_EQ(points.size(), t.size());
    EXPECT_EQ(points.front(), curve.start());
    EXPECT_EQ(points.back(), curve.end());
    double worst = 0;
    for (std::size_t k = 0; k + 1 < points.size(); ++k) {
      EXPECT_LT(t[k], t[k + 1]);
      const Vector2d a = points[k], b = points[k + 1];
      for (int s = 1; s < 16; ++s) {
        const Vector2d p = curve.at(t[k] + (t[k + 1] - t[k]) * s / 16.0);
        const double along = std::clamp((p - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0);
        worst = std::max(worst, (p - (a + along * (b - a))).norm());
      }
    }
    EXPECT_LE(worst, tolerance) << "tolerance " << tolerance;
    EXPECT_GT(worst, 0.05 * tolerance) << "flattened far finer than asked"; // not wasteful
  }
}

TEST(BezierFlattening, LengthAgreesWithFinePolyline) {
  const Curve curve = quarter_circle(0.3);
  const auto points = curve.flatten(1e-9);
  double polyline = 0;
  for (std::size_t k = 0; k + 1 < points.size(); ++k)
    polyline += (points[k + 1] - points[k]).norm();
  EXPECT_NEAR(curve.length(), polyline, 1e-8);
  // The cubic is within 0.03 % of the circle's radius: its length too.
  EXPECT_NEAR(curve.length(), 0.3 * M_PI / 2, 3e-4 * 0.3);
}

TEST(BezierFlattening, EqualArcLengthSplit) {
  const Curve curve = quarter_circle(0.3);
  const auto fine = curve.flatten(1e-10);
  std::vector<double> arc{0};
  for (std::size_t k = 0; k + 1 < fine.size(); ++k)
    arc.push_back(arc.back() + (fine[k + 1] - fine[k]).norm());
  // Arc length of a point on the curve, by projection onto the fine polyline.
  const auto arc_at = [&](const Vector2d& p) {
    double best = 1e9, s = 0;
    for (std::size_t k = 0; k + 1 < fine.size(); ++k) {
      const Vector2d d = fine[k + 1] - fine[k];
      const double f = std::clamp((p - fine[k]).dot(d) / d.squaredNorm(), 0.0, 1.0);
      const double distance = (p - fine[k] - f * d).norm();
      if (distance < best) {
        best = distance;
        s = arc[k] + f * d.norm();
      }
    }
    return s;
  };
  const int pieces = 7;
  std::vector<double> parameters;
  const auto points = curve.split_equal_arc_length(pieces, &parameters);
  ASSERT_EQ(points.size(), std::size_t(pieces + 1));
  ASSERT_EQ(parameters.size(), points.size());
  for (int i = 0; i <= pieces; ++i) {
    EXPECT_NEAR(arc_at(points[i]), arc.back() * i / pieces, 1e-8) << "point " << i;
    // The curve's own point at the reported parameter, by de Casteljau.
    const double t = parameters[std::size_t(i)];
    std::vector<Vector2d> level = curve.points;
    for (std::size_t n = level.size() - 1; n > 0; --n)
      for (std::size_t k = 0; k < n; ++k)
        level[k] = (1 - t) * level[k] + t * level[k + 1];
    EXPECT_LT((level[0] - points[i]).norm(), 1e-15) << "point " << i;
  }
}

TEST(PolylineCurve, SplitAndLength) {
  Curve curve;
  curve.kind = Curve::Kind::polyline;
  curve.points = {{0, 0}, {0.3, 0}, {0.3, 0.1}};
  EXPECT_NEAR(curve.length(), 0.4, 1e-15);
  std::vector<double> parameters;
  const auto points = curve.split_equal_arc_length(4, &parameters);
  EXPECT_NEAR((points[3] - Vector2d(0.3, 0)).norm(), 0, 1e-15);
  EXPECT_NEAR((points[2] - Vector2d(0.2, 0)).norm(), 0, 1e-15);
  // t: the segment's index plus the fraction along it, over the segments.
  EXPECT_NEAR(parameters[2], (0.0 + 2.0 / 3.0) / 2.0, 1e-15);
  EXPECT_NEAR(parameters[3], 0.5, 1e-15);
  EXPECT_EQ(parameters[4], 1.0);
}

// ------------------------------------------------------- layout, SVG ----

TEST(SheetLayout, PacksSideBySideMembersAsPlaced) {
  const Pattern shirt = read_pattern(samples + "/tshirt.json");
  const auto layout = sheet_layout(shirt, 0.05);
  // front_l and front_r keep their relative placement (sharing the centre line) ...
  const Vector2d left = layout[0].apply(shirt.panels[0].outline[0].curve.start());
  const Vector2d right = layout[1].apply(Vector2d(0, 0));
  EXPECT_NEAR((left - right).norm(), 0, 1e-12);
  // ... and no two packs overlap.
  std::vector<Eigen::AlignedBox2d> boxes(shirt.packs.size());
  for (std::size_t p = 0; p < shirt.packs.size(); ++p)
    for (const auto& member : shirt.packs[p].members)
      for (const auto& q : shirt.panels[member.panel].outline_polygon(1e-5))
        boxes[p].extend(layout[member.panel].apply(q));
  for (std::size_t p = 0; p + 1 < boxes.size(); ++p)
    EXPECT_NEAR(boxes[p + 1].min().x() - boxes[p].max().x(), 0.05, 1e-12);
}

TEST(PatternSvg, WellFormedWithEveryId) {
  const Pattern shirt = read_pattern(samples + "/tshirt.json");
  const std::string svg = pattern_svg(shirt);
  EXPECT_EQ(svg.rfind("<?xml", 0), 0u);
  EXPECT_NE(svg.find("</svg>\n"), std::string::npos);
  std::size_t groups = 0;
  for (std::size_t at = svg.find("<g "); at != std::string::npos; at = svg.find("<g ", at + 1))
    ++groups;
  EXPECT_EQ(groups, shirt.panels.size());
  for (const auto& panel : shirt.panels) {
    EXPECT_NE(svg.find(">" + panel.id + "<"), std::string::npos) << panel.id;
    for (const auto& line : panel.outline)
      EXPECT_NE(svg.find(">" + line.id + "<"), std::string::npos) << line.id;
  }
  EXPECT_NE(svg.find("class=\"interior\""), std::string::npos);
  EXPECT_NE(svg.find("(torso, front, 1)"), std::string::npos);
  // Every element opened is closed (a structural check without a parser) ...
  std::size_t opened = 0, closed = 0;
  for (std::size_t i = 0; i + 1 < svg.size(); ++i) {
    if (svg[i] == '<' && svg[i + 1] != '/' && svg[i + 1] != '?') ++opened;
    if ((svg[i] == '<' && svg[i + 1] == '/') || (svg[i] == '/' && svg[i + 1] == '>')) ++closed;
  }
  EXPECT_EQ(opened, closed);
  // ... and xmllint, where installed, agrees.
  if (std::system("command -v xmllint > /dev/null 2>&1") == 0) {
    const std::string path =
        ::testing::TempDir() + "/sartor_pattern_test_" + std::to_string(::getpid()) + ".svg";
    write_pattern_svg(path, shirt);
    EXPECT_EQ(std::system(("xmllint --noout " + path).c_str()), 0);
    std::remove(path.c_str());
  }
}

TEST(PatternTags, YSeamSecondaryTagIsReadAndDrawn) {
  json document = pattern_of({square_panel("a", "a_")});
  document["panels"][0]["outline"][2]["y_seam"] = true;
  const Pattern pattern = parse(document);
  EXPECT_TRUE(pattern.panels[0].outline[2].y_seam);
  EXPECT_FALSE(pattern.panels[0].outline[1].y_seam);
  EXPECT_NE(pattern_svg(pattern).find("class=\"yseam\""), std::string::npos);
  document["panels"][0]["outline"][2]["y_seam"] = "yes";
  EXPECT_NE(error_of(document).find("panels[0].outline[2].y_seam: expected true or false"),
            std::string::npos);
}

TEST(PatternSvg, EscapesMarkupInIds) {
  json document = pattern_of({square_panel("a<&>\"b", "a_")});
  const std::string svg = pattern_svg(parse(document));
  EXPECT_NE(svg.find("a&lt;&amp;&gt;&quot;b"), std::string::npos);
  EXPECT_EQ(svg.find("a<&>"), std::string::npos);
}

} // namespace
} // namespace sartor::garment
