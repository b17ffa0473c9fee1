// A command's own option values (sartor::Options::set_default, set, clear)
// live in its copy of the options, over or under what the user gave; the
// options database keeps what the user gave.

#include "app/cli.hpp"
#include "common/error.hpp"

#include <gtest/gtest.h>
#include <petscsys.h>

#include <algorithm>
#include <string>
#include <utility>
#include <vector>

namespace {

const sartor::CommandSpec& spec() {
  static const sartor::CommandSpec command{"probe",
                                           "options of a test",
                                           "probe [options]",
                                           "",
                                           {{"density", "KG_M2", "0.2", "areal density"},
                                            {"seams-file", "FILE", "", "seams"},
                                            {"settle", "", "", "a flag"},
                                            {"time-end", "SECONDS", "1", "end time"},
                                            {"body", "SPEC", "", "a body", true}}};
  return command;
}

bool in_database(const char* key) {
  PetscBool set = PETSC_FALSE;
  PetscOptionsHasName(nullptr, nullptr, key, &set);
  return set == PETSC_TRUE;
}

// The user's options of one test, taken out again after it.
class OptionsOverlay : public ::testing::Test {
protected:
  void SetUp() override {
    ASSERT_EQ(PetscOptionsSetValue(nullptr, "-density", "0.3"), 0);
    ASSERT_EQ(PetscOptionsSetValue(nullptr, "-seams_file", "user.json"), 0);
  }
  void TearDown() override {
    for (const char* key : {"-density", "-seams_file"})
      PetscOptionsClearValue(nullptr, key);
  }
};

TEST_F(OptionsOverlay, CommandDefaultsCountAsGivenBelowTheUsersValues) {
  sartor::Options options(spec());
  options.set_default("density", "0.25");
  options.set_default("time-end", "1.5");
  options.set_default("settle", "true");
  EXPECT_EQ(options.text("density"), "0.3"); // the user's
  EXPECT_TRUE(options.is_set("time-end"));
  EXPECT_DOUBLE_EQ(options.real("time-end"), 1.5);
  EXPECT_TRUE(options.flag("settle"));
  // The database holds what the user gave, nothing more.
  EXPECT_FALSE(in_database("-time_end"));
  EXPECT_FALSE(in_database("-settle"));
  const auto echoed = options.command_defaults();
  ASSERT_EQ(echoed.size(), 2u);
  EXPECT_EQ(echoed[0].first, "-settle");
  EXPECT_EQ(echoed[1].first, "-time_end");
  EXPECT_EQ(echoed[1].second, "1.5");
}

TEST_F(OptionsOverlay, SetReplacesTheUsersValueInACopyOnly) {
  const sartor::Options users(spec());
  sartor::Options level = users;
  level.set("seams-file", "level.json");
  level.clear("density");
  EXPECT_EQ(level.text("seams-file"), "level.json");
  EXPECT_FALSE(level.is_set("density"));
  EXPECT_EQ(level.text("density"), "0.2"); // the spec's default
  EXPECT_EQ(users.text("seams-file"), "user.json");
  EXPECT_EQ(users.text("density"), "0.3");
  // Replaced values are not echoed: a re-run replaces them again.
  EXPECT_TRUE(level.command_defaults().empty());
}

TEST_F(OptionsOverlay, AReplacedUserOptionIsStillUsed) {
  sartor::Options options(spec());
  options.set("seams-file", "own.json");
  EXPECT_EQ(options.text("seams-file"), "own.json");
  PetscBool used = PETSC_FALSE;
  ASSERT_EQ(PetscOptionsUsed(nullptr, "seams_file", &used), 0);
  EXPECT_TRUE(used) << "the user's --seams-file would be reported as unused";
}

TEST_F(OptionsOverlay, ADefaultAfterAClearIsTheCommands) {
  sartor::Options options(spec());
  options.clear("time-end");
  options.set_default("time-end", "2");
  EXPECT_EQ(options.text("time-end"), "2");
  options.set_default("time-end", "3"); // given already: the first stays
  EXPECT_EQ(options.text("time-end"), "2");
}

// --body, --body2, ... --body99: the entries given, in index order, gaps
// allowed; the command line knows them all and no other.
TEST(IndexedOption, EntriesComeInIndexOrder) {
  for (const auto& [key, value] :
       {std::pair{"-body12", "twelve"}, {"-body", "one"}, {"-body3", "three"}, {"-body99", "last"}})
    ASSERT_EQ(PetscOptionsSetValue(nullptr, key, value), 0);
  const sartor::Options options(spec());
  const auto entries = options.indexed("body");
  ASSERT_EQ(entries.size(), 4u);
  const std::vector<std::pair<std::string, std::string>> expected{
      {"body", "one"}, {"body3", "three"}, {"body12", "twelve"}, {"body99", "last"}};
  for (std::size_t k = 0; k < expected.size(); ++k)
    EXPECT_EQ(entries[k], expected[k]) << k;
  const auto effective = options.effective();
  EXPECT_EQ(std::count_if(effective.begin(), effective.end(),
                          [](const auto& entry) { return entry.first.rfind("body", 0) == 0; }),
            4);
  for (const char* key : {"-body", "-body3", "-body12", "-body99"})
    PetscOptionsClearValue(nullptr, key);
  EXPECT_THROW(options.indexed("density"), std::logic_error);
}

TEST(IndexedOption, TheCommandLineTakesNumberedEntriesOnly) {
  const auto parsed = sartor::parse_command_line(spec(), "probe", {"--body7", "sphere"});
  ASSERT_EQ(parsed.petsc_arguments.size(), 3u);
  EXPECT_EQ(parsed.petsc_arguments[1], "-body7");
  for (const char* bad : {"--body1", "--body0", "--body07", "--body100", "--bodyx"})
    EXPECT_THROW(sartor::parse_command_line(spec(), "probe", {bad, "sphere"}), sartor::InputError)
        << bad;
  EXPECT_NE(sartor::help_text(spec()).find("--body[N] SPEC"), std::string::npos);
}

} // namespace
