// The cloth case's modules name their options with their prefix; the names
// before the prefix stay as aliases (src/app/cli.hpp, with_module_prefix).
// Either name reads the same option; the command line's wins over a case
// file's under the other name; two files that set both differently are an
// error; messages name the option as it was given.

#include "app/cli.hpp"
#include "app/cloth_case.hpp"
#include "app/commands.hpp"
#include "common/error.hpp"

#include <gtest/gtest.h>
#include <petscsys.h>

#include <map>
#include <set>
#include <string>
#include <vector>

namespace {

const sartor::CommandSpec& spec() {
  static const sartor::CommandSpec command{
      "probe", "options of a test", "probe [options]", "", [] {
        std::vector<sartor::OptionSpec> options = sartor::with_module_prefix(
            {{"density", "KG_M2", "0.2", "areal density"},
             {"material-psd", "", "", "a flag already under the prefix"},
             {"body", "SPEC", "", "a body", true},
             {"analysis", "KIND", "static", "the selector"},
             {"seams-file", "FILE", "", "seams"}},
            {"material"}, {{"analysis", "analysis"}, {"seams-file", "seam-file"}});
        return options;
      }()};
  return command;
}

// The user's options of one test, taken out again after it.
class Database : public ::testing::Test {
protected:
  void set(const char* key, const char* value) {
    ASSERT_EQ(PetscOptionsSetValue(nullptr, key, value), 0);
    keys_.push_back(key);
  }
  void TearDown() override {
    for (const char* key : keys_)
      PetscOptionsClearValue(nullptr, key);
  }

private:
  std::vector<const char*> keys_;
};

TEST(ModulePrefix, NamesAnOptionOutsideItsPrefixesAndKeepsTheOldNameAsAlias) {
  const auto& options = spec().options;
  ASSERT_EQ(options.size(), 5u);
  EXPECT_EQ(options[0].name, "material-density");
  EXPECT_EQ(options[0].alias, "density");
  EXPECT_EQ(options[1].name, "material-psd");
  EXPECT_TRUE(options[1].alias.empty());
  EXPECT_EQ(options[2].name, "material-body");
  EXPECT_EQ(options[3].name, "analysis"); // renamed to itself: no alias
  EXPECT_TRUE(options[3].alias.empty());
  EXPECT_EQ(options[4].name, "seam-file");
  EXPECT_EQ(options[4].alias, "seams-file");
  EXPECT_EQ(sartor::alias_entry(options[2], "material-body7"), "body7");
  EXPECT_EQ(sartor::alias_entry(options[2], "body7"), "body7");
  EXPECT_EQ(sartor::alias_entry(options[1], "material-psd"), "");
}

TEST_F(Database, EitherNameReadsTheOption) {
  set("-density", "0.3");
  set("-material_body4", "sphere");
  const sartor::Options options(spec());
  EXPECT_EQ(options.text("material-density"), "0.3");
  EXPECT_EQ(options.text("density"), "0.3");
  EXPECT_TRUE(options.is_set("body4"));
  EXPECT_EQ(options.name_given("material-density"), "density");
  EXPECT_EQ(options.name_given("body4"), "material-body4");
  EXPECT_EQ(options.other_name("density"), "material-density");
  EXPECT_EQ(options.other_name("material-body4"), "body4");
  const auto entries = options.indexed("body");
  ASSERT_EQ(entries.size(), 1u);
  EXPECT_EQ(entries[0].first, "material-body4");
  // The run's metadata names options by their own names.
  std::map<std::string, std::string> effective;
  for (const auto& [name, value] : options.effective())
    effective[name] = value;
  EXPECT_EQ(effective.at("material-density"), "0.3");
  EXPECT_EQ(effective.at("material-body4"), "sphere");
  EXPECT_EQ(effective.count("density"), 0u);
}

TEST_F(Database, CommandDefaultsAndReplacementsTakeEitherName) {
  set("-density", "0.3");
  sartor::Options options(spec());
  options.set_default("material-density", "0.25"); // the user's alias counts as given
  EXPECT_EQ(options.text("density"), "0.3");
  options.set("density", "0.4");
  EXPECT_EQ(options.text("material-density"), "0.4");
  options.set_default("seams-file", "own.json");
  EXPECT_EQ(options.text("seam-file"), "own.json");
  const auto echoed = options.command_defaults();
  ASSERT_EQ(echoed.size(), 1u);
  EXPECT_EQ(echoed[0].first, "-seam_file");
}

TEST_F(Database, TheCommandLineWinsOverACaseFileUnderTheOtherName) {
  set("-density", "0.3");           // from the case file
  set("-material_density", "0.35"); // from the command line
  const sartor::Options options(spec(), {"material-density"});
  EXPECT_EQ(options.text("density"), "0.35");
  EXPECT_EQ(options.name_given("density"), "material-density");
  const sartor::Options reversed(spec(), {"density"});
  EXPECT_EQ(reversed.text("material-density"), "0.3");
  EXPECT_EQ(reversed.name_given("material-density"), "density");
}

TEST_F(Database, TwoFilesGivingBothNamesDifferentValuesAreAnError) {
  set("-density", "0.3");
  set("-material_density", "0.35");
  const sartor::Options options(spec());
  try {
    options.text("density");
    FAIL() << "no error";
  } catch (const sartor::InputError& error) {
    EXPECT_NE(std::string(error.what()).find("option --material-density is given twice"),
              std::string::npos)
        << error.what();
  }
}

TEST_F(Database, BothNamesWithTheSameValueAreOneOption) {
  set("-density", "0.3");
  set("-material_density", "0.3");
  const sartor::Options options(spec());
  EXPECT_DOUBLE_EQ(options.real("density"), 0.3);
}

TEST_F(Database, MessagesNameTheOptionAsGiven) {
  set("-density", "heavy");
  const sartor::Options options(spec());
  try {
    options.real("material-density");
    FAIL() << "no error";
  } catch (const sartor::InputError& error) {
    EXPECT_EQ(std::string(error.what()), "option --density: 'heavy' is not a finite number");
  }
}

TEST(ModulePrefix, TheCommandLineTakesBothNamesAndRecordsWhichItGave) {
  const auto parsed = sartor::parse_command_line(
      spec(), "probe", {"--density", "0.3", "--material-body2", "sphere", "-seam_file", "s.json"});
  const std::vector<std::string> expected{"probe",  "-density",   "0.3",   "-material_body2",
                                          "sphere", "-seam_file", "s.json"};
  EXPECT_EQ(parsed.petsc_arguments, expected);
  EXPECT_EQ(parsed.given_names, (std::set<std::string>{"density", "material-body2", "seam-file"}));
  try {
    sartor::parse_command_line(spec(), "probe", {"--densty", "1"});
    FAIL() << "no error";
  } catch (const sartor::InputError& error) {
    EXPECT_NE(std::string(error.what()).find("did you mean --density?"), std::string::npos)
        << error.what();
  }
  const std::string help = sartor::help_text(spec());
  EXPECT_NE(help.find("--material-density KG_M2"), std::string::npos) << help;
  EXPECT_NE(help.find("or --density"), std::string::npos) << help;
  EXPECT_NE(help.find("or --body[N]"), std::string::npos) << help;
}

// Every command's options: no name or alias answers for two options, and
// every cloth-case option but the analysis selector carries a module prefix.
TEST(ModulePrefix, NoCommandHasTwoOptionsAnsweringToOneName) {
  for (const auto* command :
       {&sartor::creep_command(), &sartor::fit_command(), &sartor::synth_command(),
        &sartor::validate_command(), &sartor::fabrics_command(), &sartor::run_command(),
        &sartor::converge_command(), &sartor::pattern_command(), &sartor::body_command(),
        &sartor::construct_command(), &sartor::drape_command(), &sartor::edit_command(),
        &sartor::import_command(), &sartor::wrap_command(), &sartor::drag_command()}) {
    std::set<std::string> names;
    for (const sartor::OptionSpec& option : command->options) {
      EXPECT_TRUE(names.insert(option.name).second) << command->name << ": --" << option.name;
      if (!option.alias.empty()) {
        EXPECT_TRUE(names.insert(option.alias).second) << command->name << ": --" << option.alias;
      }
    }
  }
  const std::set<std::string> prefixes{"mesh",    "material", "load",   "pin",
                                       "contact", "seam",     "sewing", "static",
                                       "dynamic", "time",     "creep",  "certificate"};
  for (const sartor::OptionSpec& option : sartor::case_option_specs()) {
    if (option.name == "analysis") continue;
    const std::string prefix = option.name.substr(0, option.name.find('-'));
    EXPECT_TRUE(prefixes.count(prefix)) << "--" << option.name;
  }
}

} // namespace
