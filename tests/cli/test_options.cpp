// A command's own option values (sartor::Options::set_default, set, clear)
// live in its copy of the options, over or under what the user gave; the
// options database keeps what the user gave.

#include "app/cli.hpp"

#include <gtest/gtest.h>
#include <petscsys.h>

#include <string>

namespace {

const sartor::CommandSpec& spec() {
  static const sartor::CommandSpec command{"probe",
                                           "options of a test",
                                           "probe [options]",
                                           "",
                                           {{"density", "KG_M2", "0.2", "areal density"},
                                            {"seams-file", "FILE", "", "seams"},
                                            {"settle", "", "", "a flag"},
                                            {"time-end", "SECONDS", "1", "end time"}}};
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

} // namespace
