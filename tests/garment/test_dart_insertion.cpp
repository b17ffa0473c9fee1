// Adding a dart (garment/dart_insertion.hpp): the cut and the V against
// their construction by hand on a square panel (both orientations, metres
// and centimetres), the pieces of a split Bezier against the curve's own
// points, sloper parameters carried to the pieces, and the refusals.

#include "garment/dart_insertion.hpp"

#include "common/error.hpp"
#include "garment/pattern.hpp"
#include "pattern_fixtures.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace sartor::garment {
namespace {

using Eigen::Vector2d;
using nlohmann::json;
using testing::pattern_of;
using testing::square_panel;

Vector2d point(const json& p) {
  return {p.at(0).get<double>(), p.at(1).get<double>()};
}

const json& line_named(const json& document, const std::string& id) {
  for (const auto& line : document["panels"][0]["outline"])
    if (line["id"] == id) return line;
  throw std::logic_error("no line " + id);
}

std::string error_of(const json& document, const DartInsertion& dart) {
  try {
    add_dart(document, "test.json", dart);
  } catch (const InputError& error) {
    return error.what();
  }
  return "(no error)";
}

// The square's top runs from (0.4, 0.4) to (0, 0.4): a dart 0.1 wide at its
// middle has its bases at x = 0.25 and 0.15 and, 0.15 deep, its apex at
// (0.2, 0.25).
TEST(AddDart, CutsTheLineAndSewsAVIntoThePanel) {
  const json with =
      add_dart(pattern_of({square_panel("a", "a_")}), "test.json", {"a_top", 0.5, 0.1, 0.15, ""});
  const std::vector<std::string> ids = {"a_bottom",       "a_right", "a_top_a", "a_top_dart_in",
                                        "a_top_dart_out", "a_top_b", "a_left"};
  ASSERT_EQ(with["panels"][0]["outline"].size(), ids.size());
  for (std::size_t i = 0; i < ids.size(); ++i)
    EXPECT_EQ(with["panels"][0]["outline"][i]["id"], ids[i]);
  const json& in = line_named(with, "a_top_dart_in");
  EXPECT_LT((point(in["points"][0]) - Vector2d(0.25, 0.4)).norm(), 1e-15);
  EXPECT_LT((point(in["points"][1]) - Vector2d(0.2, 0.25)).norm(), 1e-15);
  EXPECT_LT((point(line_named(with, "a_top_dart_out")["points"][1]) - Vector2d(0.15, 0.4)).norm(),
            1e-15);
  EXPECT_LT((point(line_named(with, "a_top_b")["points"][1]) - Vector2d(0, 0.4)).norm(), 1e-15);
  EXPECT_EQ(with["panels"][0]["darts"][0]["id"], "a_top_dart");
  const Pattern pattern = parse_pattern(with.dump(), "with");
  ASSERT_EQ(pattern.panels[0].darts.size(), 1u);
  // The V takes 0.1 x 0.15 / 2 from the square's area.
  EXPECT_NEAR(pattern.panels[0].area(1e-9), 0.16 - 0.0075, 1e-12);
}

TEST(AddDart, PointsIntoAClockwisePanelAndKeepsItsUnits) {
  json document = pattern_of({square_panel("a", "a_")});
  document["units"] = "cm";
  json& outline = document["panels"][0]["outline"];
  json reversed = json::array();
  for (auto line = outline.rbegin(); line != outline.rend(); ++line) {
    json turned = *line;
    turned["points"] = {(*line)["points"][1], (*line)["points"][0]};
    reversed.push_back(turned);
  }
  outline = reversed; // clockwise, 0.4 cm square
  const json with = add_dart(document, "test.json", {"a_top", 0.5, 0.001, 0.0015, "v"});
  // The top now runs from (0, 0.4) to (0.4, 0.4) cm; the apex is inside.
  const json& in = line_named(with, "v_in");
  EXPECT_LT((point(in["points"][0]) - Vector2d(0.15, 0.4)).norm(), 1e-14);
  EXPECT_LT((point(in["points"][1]) - Vector2d(0.2, 0.25)).norm(), 1e-14);
  EXPECT_EQ(parse_pattern(with.dump(), "with").panels[0].darts.size(), 1u);
}

TEST(AddDart, SplitsABezierIntoPiecesOfTheCurve) {
  json document = pattern_of({square_panel("a", "a_")});
  json& top = document["panels"][0]["outline"][2];
  top["type"] = "bezier";
  top["points"] = {{0.4, 0.4}, {0.3, 0.45}, {0.1, 0.42}, {0.0, 0.4}};
  const json with = add_dart(document, "test.json", {"a_top", 0.4, 0.05, 0.1, ""});
  const auto cubic = [](const json& p, double t) {
    Vector2d sum = Vector2d::Zero();
    const double b[4] = {(1 - t) * (1 - t) * (1 - t), 3 * t * (1 - t) * (1 - t),
                         3 * t * t * (1 - t), t * t * t};
    for (int k = 0; k < 4; ++k)
      sum += b[k] * point(p[k]);
    return sum;
  };
  const json& first = line_named(with, "a_top_a")["points"];
  const json& second = line_named(with, "a_top_b")["points"];
  // The pieces end where the dart's legs start and end, and are the curve
  // from 0 to t1 and from t2 to 1: t1 found where the first piece ends.
  const Vector2d base1 = point(first[3]), base2 = point(second[0]);
  double t1 = 0.0, t2 = 0.0, best1 = 1.0, best2 = 1.0;
  for (int k = 0; k <= 100000; ++k) {
    const double t = k / 100000.0;
    const double d1 = (cubic(top["points"], t) - base1).norm();
    const double d2 = (cubic(top["points"], t) - base2).norm();
    if (d1 < best1) best1 = d1, t1 = t;
    if (d2 < best2) best2 = d2, t2 = t;
  }
  for (double s : {0.0, 0.3, 0.7, 1.0}) {
    EXPECT_LT((cubic(first, s) - cubic(top["points"], s * t1)).norm(), 1e-5) << s;
    EXPECT_LT((cubic(second, s) - cubic(top["points"], t2 + s * (1 - t2))).norm(), 1e-5) << s;
  }
  // 0.05 m of the curve cut out around 40 % of its length.
  const Pattern pattern = parse_pattern(with.dump(), "with");
  double cut_start = 0.0, whole = 0.0;
  const Pattern before = parse_pattern(document.dump(), "before");
  for (const auto& line : before.panels[0].outline)
    if (line.id == "a_top") whole = line.curve.length();
  for (const auto& line : pattern.panels[0].outline)
    if (line.id == "a_top_a") cut_start = line.curve.length();
  EXPECT_NEAR(cut_start, 0.4 * whole - 0.025, 1e-8);
}

TEST(AddDart, CarriesSloperParametersToThePieces) {
  json document = pattern_of({square_panel("a", "a_")});
  document["parameters"] = {
      {{"id", "height"}, {"moves", {{{"line", "a_top"}, {"per_unit", {0, 1}}}}}}};
  const json with = add_dart(document, "test.json", {"a_top", 0.5, 0.1, 0.15, ""});
  const json moves = with["parameters"][0]["moves"];
  ASSERT_EQ(moves.size(), 2u);
  EXPECT_EQ(moves[0]["line"], "a_top_a");
  EXPECT_EQ(moves[0]["corner"], "start");
  EXPECT_EQ(moves[1]["line"], "a_top_b");
  EXPECT_EQ(moves[1]["corner"], "end");
}

TEST(AddDart, RefusesWhatCannotBeADart) {
  const json square = pattern_of({square_panel("a", "a_")});
  EXPECT_NE(error_of(square, {"a_hem", 0.5, 0.1, 0.1, ""})
                .find("test.json: add dart: 'a_hem' is not an outline line"),
            std::string::npos);
  EXPECT_NE(error_of(square, {"a_top", 0.05, 0.2, 0.1, ""}).find("leaves the line"),
            std::string::npos);
  EXPECT_NE(error_of(square, {"a_top", 0.5, 0.0, 0.1, ""}).find("must be > 0"), std::string::npos);
  // Deeper than the panel: the legs leave it.
  EXPECT_NE(error_of(square, {"a_top", 0.5, 0.1, 0.5, ""}).find("with dart 'a_top_dart'"),
            std::string::npos);
}

} // namespace
} // namespace sartor::garment
