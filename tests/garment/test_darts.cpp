// Darts (docs/pattern-format.md#darts): declared in the pattern, validated,
// sewn leg to leg before TAGCON's matching, and meshed so that both legs of
// a dart get the same vertices along their equal lengths.

#include "common/error.hpp"
#include "contact/mannequin.hpp"
#include "contact/mesh_shape.hpp"
#include "garment/garment_mesh.hpp"
#include "garment/tagcon.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace sartor::garment {
namespace {

const std::string samples = SARTOR_PATTERN_SAMPLES_DIR;

Construction build(const Pattern& pattern) {
  static const auto shape = contact::make_mannequin_shape();
  const BodyDistance distance = [](const Eigen::Vector3d& p, Eigen::Vector3d* gradient) {
    const auto q = shape->query(p);
    if (gradient) *gradient = q.normal;
    return q.distance;
  };
  return construct(pattern, default_mannequin(), distance);
}

// A square panel 0.4 m wide with one dart in its top edge, apex at (0.2,
// 0.25): legs from (0.22, 0.4) down to the apex and up to (0.18, 0.4).
// `legs` and the apex height are what the error tests vary.
std::string dart_panel(const std::string& legs, double apex_y = 0.25, double out_x = 0.18) {
  const std::string apex = "[0.2, " + std::to_string(apex_y) + "]";
  const std::string out = "[" + std::to_string(out_x) + ", 0.4]";
  return R"({"format": "sartor-pattern", "version": 1, "panels": [{
    "id": "p", "fabric": "silk", "tag": {"cylinder": "torso", "side": "front"},
    "grain": {"angle_deg": 90},
    "outline": [
      {"id": "bottom", "type": "straight", "points": [[0, 0], [0.4, 0]]},
      {"id": "right", "type": "straight", "points": [[0.4, 0], [0.4, 0.4]]},
      {"id": "top_r", "type": "straight", "points": [[0.4, 0.4], [0.22, 0.4]]},
      {"id": "leg_in", "type": "straight", "points": [[0.22, 0.4], )" +
         apex + R"(]},
      {"id": "leg_out", "type": "straight", "points": [)" +
         apex + ", " + out + R"(]},
      {"id": "top_l", "type": "straight", "points": [)" +
         out + R"(, [0, 0.4]]},
      {"id": "left", "type": "straight", "points": [[0, 0.4], [0, 0]]}],
    "darts": [{"id": "d", "legs": )" +
         legs + "}]}]}";
}

TEST(Darts, ReadInCounterClockwiseOrderWhicheverWayTheFileNamesTheLegs) {
  for (const std::string legs : {R"(["leg_in", "leg_out"])", R"(["leg_out", "leg_in"])"}) {
    const Pattern pattern = parse_pattern(dart_panel(legs), "dart.json");
    ASSERT_EQ(pattern.panels[0].darts.size(), 1u);
    EXPECT_EQ(pattern.panels[0].darts[0].first_leg, "leg_in");
    EXPECT_EQ(pattern.panels[0].darts[0].second_leg, "leg_out");
  }
}

void expect_error(const std::string& text, const std::string& fragment) {
  try {
    parse_pattern(text, "dart.json");
    ADD_FAILURE() << "no error; expected one containing: " << fragment;
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find(fragment), std::string::npos) << error.what();
    EXPECT_NE(std::string(error.what()).find("dart.json: panels[0].darts[0]"), std::string::npos)
        << error.what();
  }
}

TEST(Darts, BadDartsAreErrorsNamingTheDart) {
  expect_error(dart_panel(R"(["leg_in", "top_l"])"), "are not consecutive lines");
  expect_error(dart_panel(R"(["leg_in", "nowhere"])"), "'nowhere' is not an outline line");
  expect_error(dart_panel(R"(["leg_in"])"), "'legs' must name two outline lines");
  // The apex above the top edge: the legs meet at a convex corner.
  expect_error(dart_panel(R"(["leg_in", "leg_out"])", 0.55), "meet at a convex corner");
  // One leg 0.15 m, the other sqrt(0.15^2 + 0.06^2) = 0.1616 m: 7% longer.
  expect_error(dart_panel(R"(["leg_in", "leg_out"])", 0.25, 0.14), "the legs differ in length");
}

// The sample skirt with two waist darts per panel: every leg is sewn to its
// partner, apex to apex, and nothing else; the side seams are still found.
TEST(Darts, SkirtDartsAreSewnLegToLegWithEqualLengths) {
  const Pattern pattern = read_pattern(samples + "/skirt_darts.json");
  const Construction construction = build(pattern);
  const GarmentMesh garment = build_garment_mesh(construction, PanelMeshOptions{});
  // Each leg runs 0.02 m across and 0.12 m down (the file's coordinates).
  const double leg = std::hypot(0.02, 0.12);
  int darts = 0, sides = 0;
  for (std::size_t s = 0; s < construction.seams.size(); ++s) {
    const FoundSeam& found = construction.seams[s];
    const LineGeometry& a = construction.lines[std::size_t(found.line_a)];
    const LineGeometry& b = construction.lines[std::size_t(found.line_b)];
    if (found.kind != SeamKind::dart) {
      EXPECT_EQ(a.id.find("dart"), std::string::npos) << a.id << " sewn to " << b.id;
      EXPECT_EQ(b.id.find("dart"), std::string::npos) << b.id << " sewn to " << a.id;
      sides += a.id.find("side") != std::string::npos && b.id.find("side") != std::string::npos;
      continue;
    }
    ++darts;
    EXPECT_EQ(a.panel, b.panel);
    EXPECT_EQ(a.id.substr(0, a.id.size() - 3), b.id.substr(0, b.id.size() - 4)) << a.id << b.id;
    EXPECT_NEAR(a.length, leg, 1e-9);
    EXPECT_NEAR(b.length, leg, 1e-9);
    const Seam& seam = garment.seams[s];
    EXPECT_TRUE(seam.reverse);
    ASSERT_EQ(seam.a.size(), seam.b.size());
    EXPECT_GE(seam.a.size(), 3u);
    EXPECT_EQ(seam.a.back(), seam.b.front()); // the apex is one vertex
    // Paired from the waist (a's start with b's end) to the apex, the
    // vertices lie at the same height on the placed panel.
    for (std::size_t i = 0; i < seam.a.size(); ++i) {
      const auto& pa = garment.mesh.positions[std::size_t(seam.a[i])];
      const auto& pb = garment.mesh.positions[std::size_t(seam.b[seam.b.size() - 1 - i])];
      EXPECT_NEAR(pa.z(), pb.z(), 1e-3) << a.id << " vertex " << i;
    }
  }
  EXPECT_EQ(darts, 4);
  EXPECT_EQ(sides, 2);
  for (const UnseamedLine& line : construction.unseamed)
    EXPECT_EQ(construction.lines[std::size_t(line.line)].id.find("dart"), std::string::npos);
}

} // namespace
} // namespace sartor::garment
