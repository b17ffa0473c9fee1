// User seams and tags (garment/seam_overrides.hpp): a seams file retags
// panels before TAGCON, replaces TAGCON's seams of the lines it names,
// removes those it unseams, keeps the rest, and never touches a dart.

#include "common/error.hpp"
#include "contact/mannequin.hpp"
#include "contact/mesh_shape.hpp"
#include "garment/garment_mesh.hpp"
#include "garment/seam_overrides.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <set>
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

// "a+b" per seam, the pair in a fixed order.
std::set<std::string> seam_names(const Construction& c) {
  std::set<std::string> names;
  for (const FoundSeam& seam : c.seams) {
    std::string a = c.lines[std::size_t(seam.line_a)].id, b = c.lines[std::size_t(seam.line_b)].id;
    if (b < a) std::swap(a, b);
    names.insert(a + "+" + b);
  }
  return names;
}

TEST(SeamOverrides, UserSeamsReplaceTagconsOfTheirLinesAndKeepTheRest) {
  const Pattern pattern = read_pattern(samples + "/skirt.json");
  Construction construction = build(pattern);
  ASSERT_EQ(seam_names(construction),
            (std::set<std::string>{"sb_side_l+sf_side_r", "sb_side_r+sf_side_l"}));
  // Sew the front's right side to the back's right side instead (a user
  // correcting a seam), with the orientation given; unseam nothing else.
  const SeamOverrides overrides = parse_seam_overrides(
      R"({"seams": [{"a": "sf_side_r", "b": "sb_side_r", "reverse": true, "certainty": 0.5}]})",
      "user.json");
  apply_seam_overrides(construction, overrides);
  // Both TAGCON seams named a line of the user's seam: both go.
  EXPECT_EQ(seam_names(construction), (std::set<std::string>{"sb_side_r+sf_side_r"}));
  ASSERT_EQ(construction.seams.size(), 1u);
  EXPECT_EQ(construction.seams[0].kind, SeamKind::user);
  EXPECT_TRUE(construction.seams[0].reverse);
  EXPECT_DOUBLE_EQ(construction.seams[0].certainty, 0.5);
  std::set<std::string> unseamed;
  for (const UnseamedLine& line : construction.unseamed)
    unseamed.insert(construction.lines[std::size_t(line.line)].id);
  EXPECT_TRUE(unseamed.count("sf_side_l"));
  EXPECT_TRUE(unseamed.count("sb_side_l"));
  EXPECT_FALSE(unseamed.count("sf_side_r"));
  // The garment mesh sews what the construction now says.
  const GarmentMesh garment = build_garment_mesh(construction, PanelMeshOptions{});
  ASSERT_EQ(garment.seams.size(), 1u);
  EXPECT_EQ(garment.seams[0].a, garment.line_vertices.at("sf_side_r"));
}

TEST(SeamOverrides, UnseamAndReplaceTagconAndTags) {
  Pattern pattern = read_pattern(samples + "/skirt.json");
  {
    Construction construction = build(pattern);
    apply_seam_overrides(construction, parse_seam_overrides(R"({"unseam": ["sb_side_l"]})", "u"));
    EXPECT_EQ(seam_names(construction), (std::set<std::string>{"sb_side_r+sf_side_l"}));
  }
  {
    Construction construction = build(pattern);
    apply_seam_overrides(construction, parse_seam_overrides(R"({"replace_tagcon": true, "seams": [
                           {"a": "sf_hem_l", "b": "sb_hem"}]})",
                                                            "r"));
    EXPECT_EQ(seam_names(construction), (std::set<std::string>{"sb_hem+sf_hem_l"}));
  }
  const SeamOverrides tags = parse_seam_overrides(
      R"({"tags": {"skirt_front": {"cylinder": "torso", "side": "back", "layer": 1}}})", "t");
  apply_tag_overrides(pattern, tags);
  EXPECT_EQ(pattern.panels[0].tag, (PanelTag{Cylinder::torso, Side::back, 1}));
  EXPECT_EQ(pattern.panels[1].tag, (PanelTag{Cylinder::torso, Side::back, 0}));
}

TEST(SeamOverrides, DartsStaySewn) {
  const Pattern pattern = read_pattern(samples + "/skirt_darts.json");
  Construction construction = build(pattern);
  apply_seam_overrides(construction, parse_seam_overrides(R"({"replace_tagcon": true})", "r"));
  EXPECT_EQ(construction.seams.size(), 4u);
  for (const FoundSeam& seam : construction.seams)
    EXPECT_EQ(seam.kind, SeamKind::dart);
  EXPECT_THROW(apply_seam_overrides(construction,
                                    parse_seam_overrides(R"({"unseam": ["sf_dart_r_in"]})", "d")),
               InputError);
}

void expect_error(const std::string& text, const std::string& fragment) {
  const Pattern pattern = read_pattern(samples + "/skirt.json");
  try {
    Pattern retagged = pattern;
    const SeamOverrides overrides = parse_seam_overrides(text, "user.json");
    apply_tag_overrides(retagged, overrides);
    Construction construction = build(retagged);
    apply_seam_overrides(construction, overrides);
    ADD_FAILURE() << "no error; expected one containing: " << fragment;
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find(fragment), std::string::npos) << error.what();
  }
}

TEST(SeamOverrides, BadFilesAreErrorsNamingFileAndPlace) {
  expect_error(R"({"seams": [{"a": [1, 2], "b": "sb_hem"}]})",
               "user.json: seams[0].a: names mesh vertices");
  expect_error(R"({"seams": [{"a": "sf_hem_l", "b": "nowhere"}]})",
               "user.json: seams[0].b: no line 'nowhere'");
  expect_error(R"({"seams": [{"a": "sb_hem", "b": "sb_hem"}]})", "sews line 'sb_hem' to itself");
  expect_error(R"({"seams": [{"a": "sb_hem", "b": "sf_hem_l", "stitch": 3}]})",
               "user.json: seams[0]: unknown key 'stitch'");
  expect_error(R"({"seams": [{"a": "sb_hem", "b": "sf_hem_l", "certainty": 2}]})",
               "seams[0].certainty: must be a number in (0, 1]");
  expect_error(R"({"tags": {"sleeve": {"cylinder": "torso", "side": "back"}}})",
               "user.json: tags.sleeve: no panel or pack 'sleeve'");
  expect_error(R"({"tags": {"skirt_back": {"cylinder": "tail", "side": "back"}}})",
               "tags.skirt_back.cylinder: unknown cylinder 'tail'");
  expect_error(R"({"sewn": []})", "user.json: unknown key 'sewn'");
}

} // namespace
} // namespace sartor::garment
