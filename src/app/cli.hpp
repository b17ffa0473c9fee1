#pragma once
// Command-line plumbing shared by the `sartor` commands.
//
// Application options are written `--name value` (or `--name=value`); they are
// stored in the PETSc options database as `-name value` (dashes inside a name
// become underscores), so a case can set them in a YAML options file
// (`-options_file_yaml case.yaml`, key `name: value`) next to any PETSc option
// (`-tao_monitor`, `-log_view`, ...). Values are read back here, checked, and
// rejected with a message naming the option when they make no sense.
//
// The cloth case's modules name their options with their own prefix
// (`--material-warp-modulus`, `--contact-body`), as PETSc's objects do
// (`-snes_`, `-ksp_`), so that a YAML case may group them (`material:` with
// `warp_modulus: 5000` under it); the short names of earlier releases
// (`--warp-modulus`) stay as aliases (OptionSpec::alias, with_module_prefix).

#include <petscsys.h>

#include <functional>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace sartor {

struct OptionSpec {
  std::string name;       // long name without dashes, e.g. "load-duration"
  std::string value_name; // e.g. "SECONDS"; empty for a flag
  std::string fallback;   // default value as text; empty: no default
  std::string help;       // one line, with units
  // An indexed list: `name`, `name2`, `name3`, ... up to `name99` (gaps
  // allowed), read in that order by Options::indexed. The first has no number.
  bool indexed = false;
  // The option's other name, which it answers to as well (the name before
  // its module's prefix: "warp-modulus" of "material-warp-modulus"); for an
  // indexed list its numbered entries too ("body2" of "contact-body2").
  std::string alias = {};

  bool answers_to(const std::string& some_name) const {
    return some_name == name || (!alias.empty() && some_name == alias);
  }
};

// A module's options under its prefix. An option whose name starts with
// none of `prefixes` (each without its dash; the first is the module's own)
// takes the name `renamed` gives it, else the first prefix, a dash and its
// name; its former name becomes its alias. `renamed` may keep a name
// ("analysis", the case's selector, belongs to no module).
std::vector<OptionSpec> with_module_prefix(std::vector<OptionSpec> options,
                                           const std::vector<std::string>& prefixes,
                                           const std::map<std::string, std::string>& renamed = {});

struct CommandSpec {
  std::string name;
  std::string summary;     // one line for `sartor --help`
  std::string usage;       // e.g. "sartor fit DATA.csv [options]"
  std::string description; // paragraphs printed by --help before the options
  std::vector<OptionSpec> options;
  std::size_t positionals = 0; // required positional arguments
  // The first positional argument is a YAML options file (a case), read
  // before the command line so that command-line options override it.
  bool positional_is_options_file = false;
  // PETSc arguments read before the command line's (which override them),
  // named by the positional arguments, e.g. {"-options_file", FILE}; none
  // when empty (`sartor edit DRAPE_DIR`: the drape's petsc_options.txt).
  std::function<std::vector<std::string>(const std::vector<std::string>& positionals)>
      options_from_positionals = {};
};

// The names an option is given by: its own, and for an indexed list its
// numbered entries too ("body", "body2", ... "body99").
std::vector<std::string> option_entries(const OptionSpec& option);
// The alias of one of those entries ("body2" of "contact-body2"); empty
// without an alias.
std::string alias_entry(const OptionSpec& option, const std::string& entry);

// The options database's key of option `name`: "-" with its dashes as
// underscores ("bending-model" is "-bending_model").
std::string database_key(const std::string& name);

// The command line of one command, split into what is ours and what PETSc gets.
struct ParsedCommandLine {
  std::vector<std::string> positionals;
  std::vector<std::string> petsc_arguments; // argv for PetscInitialize, program name first
  bool help = false;
  // The command's options the command line gave (as `--name` or `-name`),
  // each by the name it was given: they win over the other name of the same
  // option in a case file.
  std::set<std::string> given_names = {};
};

// Throws InputError for an unknown `--option` (with a suggestion) or a missing value.
ParsedCommandLine parse_command_line(const CommandSpec& spec, const std::string& program,
                                     const std::vector<std::string>& arguments);

std::string help_text(const CommandSpec& spec);

// Typed access to a command's options after PetscInitialize. Every getter
// throws InputError naming the option when the value is malformed.
class Options {
public:
  // `command_line`: the names the command line gave (ParsedCommandLine).
  explicit Options(const CommandSpec& spec, std::set<std::string> command_line = {})
      : spec_(spec), command_line_(std::move(command_line)) {}

  bool is_set(const std::string& name) const;
  std::string text(const std::string& name) const;
  double real(const std::string& name) const;
  double positive_real(const std::string& name) const;
  double nonnegative_real(const std::string& name) const;
  long integer(const std::string& name) const;
  bool flag(const std::string& name) const;
  // The entries of an indexed list option (OptionSpec::indexed) as
  // (option name, value), in index order: --body, --body2, --body5, ...
  // Entries are named as given (an alias's entries by the alias).
  std::vector<std::pair<std::string, std::string>> indexed(const std::string& name) const;
  // The name option entry `name` was given by (its own or its alias), for
  // messages; its own name when it was not given.
  std::string name_given(const std::string& name) const;
  // The other name of an option entry: its alias's entry for its own name,
  // its own for the alias's; empty for an entry without one, or a name the
  // command does not declare.
  std::string other_name(const std::string& name) const;
  // An integer in [minimum, maximum]; the message names the option and the range.
  long integer_in(const std::string& name, long minimum, long maximum) const;
  // Options whose help is scoped to some of the `kinds` of `selector`
  // ("dynamic: ...", "dynamic, creep: ...", or "...; creep: ..." further on) do
  // nothing for another kind: giving one is an error, not silently ignored.
  void reject_inapplicable(const std::string& selector, const std::set<std::string>& kinds) const;
  // The options as given (or defaulted), by their own names, for the run's metadata.
  std::vector<std::pair<std::string, std::string>> effective() const;

  // A command's own default for an option it hands on, where the user gave
  // none: it counts as given (is_set), as a default of the database did.
  void set_default(const std::string& name, const std::string& value);
  // A value in place of the user's, or none (as if never given); the user's
  // is still marked used, so that it is not reported as unused.
  void set(const std::string& name, const std::string& value);
  void clear(const std::string& name);
  // The defaults set_default gave, as database entries (`-key`, value),
  // for petsc_options.txt: re-running the command sets them again, and
  // the file lists every option in effect.
  std::vector<std::pair<std::string, std::string>> command_defaults() const;

private:
  const OptionSpec& find(const std::string& name) const;
  // The entry's own name ("contact-body2" of "body2").
  std::string own_name(const std::string& name) const;
  // The database's value (nullptr for a flag without one) under the entry's
  // name or its alias, the command line's where both are set; false when
  // the user gave none. Marks the option used.
  bool given(const std::string& name, const char** value) const;
  const CommandSpec& spec_;
  std::set<std::string> command_line_;
  std::map<std::string, std::optional<std::string>> replaced_; // set and clear
  std::map<std::string, std::string> defaults_;                // set_default
};

} // namespace sartor
