// sartor edit: a garment draped (or a drape resumed from its directory),
// then edited (its outline corners moved), each edit predicted by the design
// sensitivity and GMLS and re-solved warm (app/edit_case.hpp;
// docs/sensitivity.md#sartor-edit).

#include "app/commands.hpp"
#include "app/edit_case.hpp"
#include "common/checksum.hpp"
#include "common/error.hpp"
#include "common/json_input.hpp"
#include "fem/petsc_call.hpp"
#include "garment/pattern.hpp"

#include <petscsys.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

namespace sartor {

namespace {

namespace fs = std::filesystem;

// The options a drape's petsc_options.txt gives: database key
// ("-bending_model") to value (quotes removed; "" for a flag).
std::map<std::string, std::string> read_echoed_options(const std::string& path) {
  std::ifstream file(path);
  if (!file) throw InputError(path + ": cannot open the drape's options");
  std::map<std::string, std::string> options;
  for (std::string line; std::getline(file, line);) {
    if (line.rfind('-', 0) != 0) continue;
    const std::size_t space = line.find(' ');
    std::string value = space == std::string::npos ? "" : line.substr(space + 1);
    if (value.size() >= 2 && value.front() == '"' && value.back() == '"')
      value = value.substr(1, value.size() - 2);
    options[line.substr(0, space)] = value;
  }
  return options;
}

// Two option values that say the same: equal texts, or equal numbers.
bool same_value(const std::string& a, const std::string& b) {
  if (a == b) return true;
  std::istringstream x(a), y(b);
  double u = 0.0, v = 0.0;
  return (x >> u) && x.eof() && (y >> v) && y.eof() && u == v;
}

// The drape a DRAPE_DIR holds, as its summary.json records it.
struct DrapeDirectory {
  std::string directory;
  std::string pattern;                        // the pattern file it was draped from
  double drape_cpu = 0.0;                     // its drape from scratch, CPU s
  std::map<std::string, std::string> options; // its petsc_options.txt
};

nlohmann::json read_drape_summary(const std::string& directory) {
  const std::string path = directory + "/summary.json";
  std::ifstream file(path);
  if (!file) {
    throw InputError(directory + ": not a drape's output directory (no summary.json); give "
                                 "PATTERN.json to drape afresh");
  }
  std::stringstream text;
  text << file.rdbuf();
  return parse_json_input(text.str(), path);
}

DrapeDirectory drape_of_summary(const std::string& directory, const nlohmann::json& summary) {
  const std::string path = directory + "/summary.json";
  const std::string command = summary.value("command", "");
  if (command != "drape" && command != "edit")
    throw InputError(path + ": command: '" + command + "' is not a drape (sartor drape or edit)");
  if (!fs::exists(directory + "/" + drape_state_file) || !summary.contains("pattern_file")) {
    throw InputError(directory + ": no " + drape_state_file +
                     ": the drape was written by an older sartor, or was not a static drape; "
                     "drape it again");
  }
  DrapeDirectory drape;
  drape.directory = directory;
  drape.pattern = summary.at("pattern_file").get<std::string>();
  if (!fs::exists(drape.pattern))
    throw InputError(path + ": pattern_file: " + drape.pattern + " does not exist any more");
  if (file_checksum(drape.pattern) != summary.value("pattern_checksum", "")) {
    throw InputError(drape.pattern + " has changed since it was draped into " + directory +
                     " (its checksum differs from summary.json's pattern_checksum); drape the "
                     "pattern again");
  }
  if (!summary.value("converged", false)) {
    throw InputError(directory + ": the drape did not converge (summary.json: converged), so "
                                 "there is no drape to edit");
  }
  drape.drape_cpu = command == "edit"
                        ? summary.at("edit").at("drape_from_scratch_cpu_s").get<double>()
                        : summary.at("drape").at("cpu_s").get<double>();
  drape.options = read_echoed_options(directory + "/petsc_options.txt");
  return drape;
}

DrapeDirectory read_drape_directory(const std::string& directory) {
  const nlohmann::json summary = read_drape_summary(directory);
  const std::string path = directory + "/summary.json";
  try {
    return drape_of_summary(directory, summary);
  } catch (const nlohmann::json::exception& error) {
    throw InputError(path + ": not a drape's summary (" + error.what() + ")");
  }
}

// `sartor edit DRAPE_DIR`: the drape's options are read before the command line.
std::vector<std::string> drape_directory_options(const std::vector<std::string>& positionals) {
  const std::string& first = positionals.at(0);
  if (!fs::is_directory(first)) return {};
  const std::string path = first + "/petsc_options.txt";
  if (!fs::exists(path)) {
    throw InputError("sartor edit: " + first +
                     ": not a drape's output directory (no petsc_options.txt)");
  }
  return {"-options_file", path};
}

// The options an edit of a resumed drape may set apart from the drape's:
// where and what it writes. Every other drape option is the drape's: a
// different value would edit another garment than the one resumed.
bool may_differ_from_drape(const std::string& name) {
  static const std::set<std::string> free = {"output", "no-plot", "checkpoint",
                                             "checkpoint-interval"};
  return free.count(name) > 0;
}

// A drape option entry's value in the drape resumed, and in this edit.
struct OptionValues {
  std::string drape, edit;
  bool differ = false;
};

OptionValues option_values(const OptionSpec& option, const std::string& name,
                           const std::string* echoed, const Options& options) {
  OptionValues values;
  if (option.value_name.empty()) {
    const bool drape = echoed && *echoed != "false" && *echoed != "0" && *echoed != "no";
    const bool edit = options.flag(name);
    values = {drape ? "true" : "false", edit ? "true" : "false", drape != edit};
  } else {
    values.drape = echoed ? *echoed : option.fallback;
    values.edit = options.text(name);
    values.differ = !same_value(values.drape, values.edit);
  }
  return values;
}

std::string edit_fallback(const std::string& name) {
  for (const OptionSpec& option : edit_command().options)
    if (option.name == name) return option.fallback;
  throw std::logic_error("sartor edit has no option --" + name);
}

// Takes the drape's value of option entry `name` (of `option`) into
// `options` (the edit's own default gives way to the drape's), and refuses
// an edit's value that differs from the drape's.
void keep_drape_value(const DrapeDirectory& drape, const OptionSpec& option,
                      const std::string& name, Options* options) {
  // Drapes echo an option by the name it was given.
  auto found = drape.options.find(database_key(name));
  if (found == drape.options.end() && !option.alias.empty())
    found = drape.options.find(database_key(alias_entry(option, name)));
  const std::string* echoed = found == drape.options.end() ? nullptr : &found->second;
  if (!echoed && edit_fallback(option.name) != option.fallback)
    options->set_default(name, option.fallback);
  if (may_differ_from_drape(option.name)) return;
  const OptionValues values = option_values(option, name, echoed, *options);
  if (!values.differ) return;
  if (option.name == "restart") {
    throw InputError("option --restart: an edit of " + drape.directory + " resumes from its " +
                     drape_state_file);
  }
  throw InputError(
      "option --" + options->name_given(name) + ": " + drape.directory + " was draped with " +
      (values.drape.empty() ? "none" : "'" + values.drape + "'") + ", not '" + values.edit +
      "'; an edit of a drape keeps the drape's options (give PATTERN.json to "
      "drape afresh with others)");
}

// Takes the drape's options into `options` and refuses a drape option this
// edit sets otherwise. Returns the pattern to construct.
std::string resume_drape_directory(const DrapeDirectory& drape,
                                   const ParsedCommandLine& command_line, Options* options) {
  const auto& given = command_line.petsc_arguments;
  const bool output_given = std::find(given.begin(), given.end(), "-output") != given.end();
  for (const OptionSpec& option : drape_command().options) {
    if (option.name == "output") {
      // The drape's own output is not where its edits go.
      if (drape.options.count(database_key("output")) && !output_given) options->clear("output");
      continue;
    }
    for (const std::string& name : option_entries(option))
      keep_drape_value(drape, option, name, options);
  }
  options->set("restart", drape.directory + "/" + drape_state_file);
  const std::string output = options->text("output");
  if (fs::exists(output) && fs::equivalent(output, drape.directory)) {
    throw InputError("option --output: " + output +
                     " is the drape's own directory, whose files the edit would replace; give "
                     "another");
  }
  return drape.pattern;
}

} // namespace

const CommandSpec& edit_command() {
  static const CommandSpec spec{
      "edit",
      "drape a garment, then edit its pattern and follow the drape by sensitivity",
      "sartor edit PATTERN.json|DRAPE_DIR EDITS.yaml [--edit-start auto|gmls|linear|unchanged] "
      "[--edit-anchors fresh|kept] [--gmls-degree 1|2] [--no-edit-retry] [--no-edit-outputs] "
      "[any option of sartor drape]",
      "Drapes PATTERN.json as `sartor drape` does (every drape option applies; the\n"
      "static drape only), then applies the edits of EDITS.yaml in turn (each\n"
      "moves outline corners of the pattern: a whole line, or one end of it; the\n"
      "edits add up; format in docs/sensitivity.md#the-edit-file). An edit with\n"
      "a drag (a point of the drape and where it should go) takes its moves as a\n"
      "direction and applies the amount whose linear response moves the point by\n"
      "the drag's projection on its sensitivity (Sensitive Couture 4.1;\n"
      "docs/sensitivity.md#direct-3d-editing-drags). For each edit:\n"
      "the design sensitivity at the last drape (one factorisation of the exact\n"
      "tangent) gives the linear prediction x + S dp; GMLS over every design\n"
      "solved so far (values and sensitivities) gives another; the re-solve of\n"
      "the drape's last stage starts from one of them (--edit-start) and its\n"
      "certificate is reported as it is (friction and contact checks included:\n"
      "a re-solve that converged is not called certified unless the certificate\n"
      "says so). A re-solve that fails is tried again from the other starts\n"
      "(not with --no-edit-retry); the edit goes on from the first that is\n"
      "certified, else the first that converged, else the first. Prints one\n"
      "line per edit: the lowest point's change, each\n"
      "prediction's largest vertex error against the re-solved drape, the\n"
      "re-solve and the CPU times against the drape from scratch.\n\n"
      "With DRAPE_DIR (the output directory of `sartor drape` or `sartor edit`)\n"
      "in place of the pattern, the drape there is resumed from its final state\n"
      "(DRAPE_DIR/drape_state.h5, at full precision: positions, friction anchors,\n"
      "contact penalty) with the options it was draped with (its\n"
      "petsc_options.txt) and the pattern its summary.json names, which must not\n"
      "have changed since; the edits follow as above, their speed-ups against the\n"
      "CPU time that drape took. A drape option given otherwise is refused\n"
      "(--output, --no-plot, --checkpoint and --checkpoint-interval may differ;\n"
      "PETSc's solver options too).\n\n"
      "Output in DIR: what `sartor drape` writes (the drape before the edits),\n"
      "summary.json with \"edit\" (per edit: errors of the unchanged, linear and\n"
      "GMLS predictions, lowest points, re-solve, its attempts, certificate, CPU seconds and\n"
      "speed-ups against the drape from scratch), and per edit DIR/edit_NN/:\n"
      "pattern.svg and outlines.json (outlines before and after), edit.png (the\n"
      "pattern beside the re-solved drape, coloured by the edit's displacement;\n"
      "not with --no-plot), linear/, gmls/, geometric/ and resolved/\n"
      "(result.h5, result.xmf, final.obj each; not with --no-edit-outputs).\n\n"
      "examples:\n"
      "  sartor edit cases/patterns/skirt.json cases/edit/skirt_hem.yaml "
      "-options_file_yaml cases/garments/skirt_coarse.yaml --output out/edit/skirt\n"
      "  sartor edit cases/patterns/skirt.json cases/edit/skirt_hem_growing.yaml --edit-start "
      "linear\n"
      "  sartor drape cases/patterns/skirt.json --output out/drape/skirt && sartor edit "
      "out/drape/skirt cases/edit/skirt_hem.yaml",
      [] {
        std::vector<OptionSpec> options = drape_command().options;
        for (OptionSpec& option : options) {
          if (option.name == "output") option.fallback = "out/edit";
          if (option.answers_to("bending-model")) {
            option.fallback = "discrete_shell";
            option.help = "patch, discrete_shell or quadratic (hinges); edit keeps the hinges "
                          "(docs/sensitivity.md#bending-models)";
          }
        }
        for (const OptionSpec& option : edit_option_specs())
          options.push_back(option);
        return options;
      }(),
      2,
      false,
      drape_directory_options};
  return spec;
}

int run_edit(const Invocation& invocation) {
  Invocation edit = invocation;
  EditRequest request;
  std::string& pattern = edit.command_line.positionals.at(0);
  if (fs::is_directory(pattern)) {
    const DrapeDirectory drape = read_drape_directory(pattern);
    request.drape = {drape.directory, drape.drape_cpu, 0.0};
    pattern = resume_drape_directory(drape, invocation.command_line, &edit.options);
  } else {
    // The hinges: with the bending patches the sample skirt's hem edit is
    // predicted worse (docs/sensitivity.md#bending-models).
    edit.options.set_default("bending-model", "discrete_shell");
  }
  // The edits are checked against the pattern before anything is solved.
  interior_coordinates_option(edit.options);
  check_edit_kinds(edit.options);
  request.steps =
      read_edit_file(edit.command_line.positionals.at(1), garment::read_pattern(pattern));
  const int status = drape_pattern(edit, &request);
  if (!request.run->ran) throw SolveFailure("the drape did not converge, so no edit was made");
  // The pictures help most when an edit failed.
  if (!edit.options.flag("no-plot")) make_plot("plot_edit.py", edit.options.text("output"));
  if (!request.run->not_converged.empty()) {
    std::string folders;
    for (const std::string& folder : request.run->not_converged)
      folders += (folders.empty() ? "" : ", ") + folder;
    throw SolveFailure("the re-solve of " + folders +
                       " did not converge from any start tried (summary.json: "
                       "edit.steps[].attempts); the edit folders hold the states reached");
  }
  if (!request.run->all_certified) {
    SartorPetscCall(PetscPrintf(PETSC_COMM_WORLD,
                                "sartor edit: not every re-solved drape is certified "
                                "(summary.json: edit.steps[].resolve.certificate)\n"));
  }
  return status;
}

} // namespace sartor
