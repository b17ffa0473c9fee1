// Unit tests of fabrics: the Table 5.1 presets, the fabric specification
// strings, and YAML fabric files (fixtures in tests/material/data/).

#include "material/fabric.hpp"

#include "common/error.hpp"

#include <gtest/gtest.h>

#include <initializer_list>
#include <string>
#include <vector>

#ifndef SARTOR_TEST_DATA_DIR
#error "SARTOR_TEST_DATA_DIR must name tests/material/data"
#endif

namespace sartor {
namespace {

std::string data(const std::string& name) {
  return std::string(SARTOR_TEST_DATA_DIR) + "/" + name;
}

::testing::AssertionResult contains(const std::string& text, const std::string& part) {
  if (text.find(part) != std::string::npos) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "'" << text << "' does not contain '" << part << "'";
}

// `text` starts with "FILE:LINE: " for one of `lines`.
::testing::AssertionResult at_file_line(const std::string& text, const std::string& file,
                                        std::initializer_list<long> lines) {
  for (const long line : lines) {
    if (text.rfind(file + ":" + std::to_string(line) + ": ", 0) == 0) {
      return ::testing::AssertionSuccess();
    }
  }
  return ::testing::AssertionFailure()
         << "'" << text << "' does not start with " << file << ":LINE: for the expected lines";
}

template <class Call>
std::string input_error(Call&& call) {
  try {
    call();
  } catch (const InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no InputError thrown";
  return "";
}

void expect_creep(const CreepParameters& got, const CreepParameters& expected) {
  EXPECT_EQ(got.creep_modulus, expected.creep_modulus);
  EXPECT_EQ(got.alpha, expected.alpha);
  EXPECT_EQ(got.lambda_load, expected.lambda_load);
  EXPECT_EQ(got.lambda_unload, expected.lambda_unload);
}

// --- Table 5.1 presets -------------------------------------------------------------

TEST(FabricPresets, TenThesisParameterSets) {
  struct Row {
    const char* name;
    CreepParameters warp;
    CreepParameters weft;
  };
  // Thesis Table 5.1: E (N/m), alpha, lambda_l (1/s), lambda_u (1/s).
  const std::vector<Row> table = {
      {"cotton_twill", {32600, 0.897, 0.0886, 0.00200}, {14100, 0.873, 0.0275, 0.00243}},
      {"silk", {54000, 0.742, 0.0572, 0.00157}, {21600, 0.794, 0.311, 0.00190}},
      {"denim", {25600, 0.667, 0.0331, 0.0147}, {42700, 0.728, 0.0540, 0.00310}},
      {"nylon", {49600, 0.729, 0.0594, 0.00534}, {30800, 0.705, 0.0376, 0.0598}},
      {"polyester", {80400, 0.674, 0.00508, 0.00197}, {10700, 0.645, 0.0227, 0.00870}},
  };
  const auto& presets = fabric_presets();
  ASSERT_EQ(presets.size(), table.size());
  for (std::size_t i = 0; i < table.size(); ++i) {
    SCOPED_TRACE(table[i].name);
    EXPECT_STREQ(presets[i].name, table[i].name);
    expect_creep(presets[i].warp, table[i].warp);
    expect_creep(presets[i].weft, table[i].weft);
  }
}

TEST(FabricPresets, SpotCheckCottonTwillWarpAndPolyesterWeft) {
  const Fabric cotton = preset_fabric("cotton_twill");
  const CreepParameters& warp = cotton.in(Direction::warp).creep;
  EXPECT_EQ(warp.creep_modulus, 32600.0);
  EXPECT_EQ(warp.alpha, 0.897);
  EXPECT_EQ(warp.lambda_load, 0.0886);
  EXPECT_EQ(warp.lambda_unload, 0.002);
  EXPECT_EQ(preset_fabric("polyester").in(Direction::weft).creep.creep_modulus, 10700.0);
}

TEST(FabricPresets, PresetFabricsHaveBothDirectionsAndLinearElasticity) {
  for (const auto& preset : fabric_presets()) {
    SCOPED_TRACE(preset.name);
    const Fabric fabric = preset_fabric(preset.name);
    EXPECT_EQ(fabric.name, preset.name);
    EXPECT_TRUE(contains(fabric.source, "Table 5.1"));
    ASSERT_TRUE(fabric.has(Direction::warp));
    ASSERT_TRUE(fabric.has(Direction::weft));
    expect_creep(fabric.in(Direction::warp).creep, preset.warp);
    expect_creep(fabric.in(Direction::weft).creep, preset.weft);
    for (const Direction d : {Direction::warp, Direction::weft}) {
      const DirectionalMaterial& m = fabric.in(d);
      EXPECT_TRUE(m.elastic.is_linear());
      EXPECT_EQ(m.elastic.initial_modulus(),
                preset_elastic_to_creep_modulus * m.creep.creep_modulus);
    }
  }
}

TEST(FabricPresets, DesignDocumentLoadAndSaturatedCreep) {
  // DESIGN.md: a 20 kg load on an 8 cm wide strip is about 2450 N/m, and
  // cotton-twill warp saturates at a creep of about 7.5 %.
  const double tension = 20.0 * 9.80665 / 0.08;
  EXPECT_NEAR(tension, 2451.7, 0.05);
  // The fabric is kept: `in` returns a reference into it.
  const Fabric cotton_twill = preset_fabric("cotton_twill");
  const CreepParameters& warp = cotton_twill.in(Direction::warp).creep;
  EXPECT_NEAR(saturation_strain(warp, tension), 0.0752, 5e-5);
  EXPECT_NEAR(saturation_strain(warp, tension), tension / 32600.0, 1e-12 * tension / 32600.0);
}

// --- specifications -------------------------------------------------------------------

TEST(FabricResolve, AllGivesTenChoicesInTableOrder) {
  const auto choices = resolve_fabrics("all");
  ASSERT_EQ(choices.size(), 10u);
  std::size_t i = 0;
  for (const auto& preset : fabric_presets()) {
    EXPECT_EQ(choices[i].label(), std::string(preset.name) + ":warp");
    expect_creep(choices[i].material().creep, preset.warp);
    ++i;
    EXPECT_EQ(choices[i].label(), std::string(preset.name) + ":weft");
    expect_creep(choices[i].material().creep, preset.weft);
    ++i;
  }
}

TEST(FabricResolve, FabricNameGivesBothDirections) {
  const auto choices = resolve_fabrics("silk");
  ASSERT_EQ(choices.size(), 2u);
  EXPECT_EQ(choices[0].label(), "silk:warp");
  EXPECT_EQ(choices[1].label(), "silk:weft");
  EXPECT_EQ(choices[0].material().creep.creep_modulus, 54000.0);
  EXPECT_EQ(choices[1].material().creep.creep_modulus, 21600.0);
}

TEST(FabricResolve, FabricAndDirectionGivesOneChoice) {
  const auto choices = resolve_fabrics("silk:weft");
  ASSERT_EQ(choices.size(), 1u);
  EXPECT_EQ(choices[0].direction, Direction::weft);
  EXPECT_EQ(choices[0].label(), "silk:weft");
  expect_creep(choices[0].material().creep, {21600, 0.794, 0.311, 0.00190});
}

TEST(FabricResolve, UnknownFabricListsPresets) {
  const std::string what = input_error([] { resolve_fabrics("wool:warp"); });
  EXPECT_TRUE(contains(what, "'wool'"));
  for (const auto& preset : fabric_presets())
    EXPECT_TRUE(contains(what, preset.name));
}

TEST(FabricResolve, UnknownDirectionListsDirections) {
  const std::string what = input_error([] { resolve_fabrics("silk:bias"); });
  EXPECT_TRUE(contains(what, "'bias'"));
  EXPECT_TRUE(contains(what, "warp"));
  EXPECT_TRUE(contains(what, "weft"));
  EXPECT_EQ(parse_direction("warp", "x"), Direction::warp);
  EXPECT_EQ(parse_direction("weft", "x"), Direction::weft);
  EXPECT_TRUE(contains(input_error([] { parse_direction("Warp", "ctx"); }), "ctx"));
  EXPECT_STREQ(name_of(Direction::warp), "warp");
  EXPECT_STREQ(name_of(Direction::weft), "weft");
}

// --- YAML fabric files -----------------------------------------------------------------

TEST(FabricFile, ReadsElasticModulusAndDefault) {
  const Fabric fabric = load_fabric_file(data("fabric_modulus.yaml"));
  EXPECT_EQ(fabric.name, "test_twill");
  EXPECT_EQ(fabric.source, "unit-test fixture");
  ASSERT_TRUE(fabric.has(Direction::warp));
  ASSERT_TRUE(fabric.has(Direction::weft));
  expect_creep(fabric.in(Direction::warp).creep, {30000, 0.8, 0.05, 0.004});
  expect_creep(fabric.in(Direction::weft).creep, {12000, 0.5, 0.02, 0.003});
  EXPECT_TRUE(fabric.in(Direction::warp).elastic.is_linear());
  EXPECT_EQ(fabric.in(Direction::warp).elastic.initial_modulus(), 75000.0);
  EXPECT_EQ(fabric.in(Direction::weft).elastic.initial_modulus(),
            preset_elastic_to_creep_modulus * 12000.0);
}

TEST(FabricFile, ReadsElasticCurves) {
  const Fabric fabric = load_fabric_file(data("fabric_curve.yaml"));
  EXPECT_EQ(fabric.name, "curved");
  EXPECT_EQ(fabric.source, data("fabric_curve.yaml")); // no source key: the path
  const TensionCurve& warp = fabric.in(Direction::warp).elastic;
  ASSERT_EQ(warp.points().size(), 4u); // the origin is implied
  EXPECT_NEAR(warp.tension(0.01), 300.0, 1e-12);
  EXPECT_NEAR(warp.tension(0.02), 900.0, 1e-12);
  EXPECT_NEAR(warp.tension(0.06), 6000.0, 1e-12);
  EXPECT_NEAR(warp.stiffness(0.05), 1.5e5, 1e-6);
  const TensionCurve& weft = fabric.in(Direction::weft).elastic;
  ASSERT_EQ(weft.points().size(), 2u); // the origin was given
  EXPECT_NEAR(weft.initial_modulus(), 20000.0, 1e-9);
  expect_creep(fabric.in(Direction::weft).creep, {15000, 0.6, 0.01, 0.001});
}

TEST(FabricFile, OneDirectionOnly) {
  const std::string path = data("fabric_weft_only.yaml");
  const Fabric fabric = load_fabric_file(path);
  EXPECT_EQ(fabric.name, "fabric_weft_only"); // the file stem
  EXPECT_FALSE(fabric.has(Direction::warp));
  ASSERT_TRUE(fabric.has(Direction::weft));
  expect_creep(fabric.in(Direction::weft).creep, {10700, 0.645, 0.0227, 0.00870});
  EXPECT_TRUE(contains(input_error([&] { fabric.in(Direction::warp); }), "no warp"));

  const auto both = resolve_fabrics(path);
  ASSERT_EQ(both.size(), 1u);
  EXPECT_EQ(both[0].label(), "fabric_weft_only:weft");
  const auto weft = resolve_fabrics(path + ":weft");
  ASSERT_EQ(weft.size(), 1u);
  EXPECT_EQ(weft[0].direction, Direction::weft);
  EXPECT_TRUE(contains(input_error([&] { resolve_fabrics(path + ":warp"); }), "no warp"));
}

TEST(FabricFile, ResolveReadsFileWithDirection) {
  const auto choices = resolve_fabrics(data("fabric_modulus.yaml") + ":warp");
  ASSERT_EQ(choices.size(), 1u);
  EXPECT_EQ(choices[0].label(), "test_twill:warp");
  EXPECT_EQ(choices[0].material().elastic.initial_modulus(), 75000.0);
}

TEST(FabricFileErrors, UnknownKeyGivesFileAndLine) {
  const std::string path = data("bad_unknown_key.yaml");
  const std::string what = input_error([&] { load_fabric_file(path); });
  EXPECT_TRUE(at_file_line(what, path, {5}));
  EXPECT_TRUE(contains(what, "'lamda_load'"));
  EXPECT_TRUE(contains(what, "lambda_load")); // lists the valid keys
}

TEST(FabricFileErrors, UnknownTopLevelKeyGivesFileAndLine) {
  const std::string path = data("bad_unknown_top_key.yaml");
  const std::string what = input_error([&] { load_fabric_file(path); });
  EXPECT_TRUE(at_file_line(what, path, {2}));
  EXPECT_TRUE(contains(what, "'colour'"));
}

TEST(FabricFileErrors, MissingCreepModulusGivesFileAndLine) {
  const std::string path = data("bad_missing_e.yaml");
  const std::string what = input_error([&] { load_fabric_file(path); });
  EXPECT_TRUE(at_file_line(what, path, {2, 3})); // the weft section
  EXPECT_TRUE(contains(what, "missing 'E'"));
  EXPECT_TRUE(contains(what, "no_modulus:weft"));
}

TEST(FabricFileErrors, AlphaOutOfRangeGivesFileAndLine) {
  const std::string path = data("bad_alpha.yaml");
  const std::string what = input_error([&] { load_fabric_file(path); });
  EXPECT_TRUE(at_file_line(what, path, {2, 3, 4})); // the warp section or the alpha line
  EXPECT_TRUE(contains(what, "alpha"));
  EXPECT_TRUE(contains(what, "1.5"));
  EXPECT_TRUE(contains(what, "too_permanent:warp"));
}

TEST(FabricFileErrors, NonNumericValueGivesFileAndLine) {
  const std::string path = data("bad_non_numeric.yaml");
  const std::string what = input_error([&] { load_fabric_file(path); });
  EXPECT_TRUE(at_file_line(what, path, {5}));
  EXPECT_TRUE(contains(what, "'lambda_load' must be a number"));
  EXPECT_TRUE(contains(what, "'fast'"));
}

TEST(FabricFileErrors, BothElasticModulusAndCurveGivesFileAndLine) {
  const std::string path = data("bad_both_elastic.yaml");
  const std::string what = input_error([&] { load_fabric_file(path); });
  EXPECT_TRUE(at_file_line(what, path, {2, 3, 7, 8}));
  EXPECT_TRUE(contains(what, "elastic_modulus"));
  EXPECT_TRUE(contains(what, "elastic_curve"));
}

TEST(FabricFileErrors, InvalidElasticCurveGivesFileAndLine) {
  const std::string path = data("bad_curve.yaml");
  const std::string what = input_error([&] { load_fabric_file(path); });
  EXPECT_TRUE(at_file_line(what, path, {2, 3, 7}));
  EXPECT_TRUE(contains(what, "tension 200"));
}

TEST(FabricFileErrors, FileWithoutDirectionsOrMissingFile) {
  const std::string path = data("bad_no_direction.yaml");
  EXPECT_TRUE(at_file_line(input_error([&] { load_fabric_file(path); }), path, {1}));
  const std::string missing = data("no_such_fabric.yaml");
  const std::string what = input_error([&] { resolve_fabrics(missing); });
  EXPECT_TRUE(contains(what, missing));
  EXPECT_TRUE(contains(what, "cannot open"));
}

} // namespace
} // namespace sartor
