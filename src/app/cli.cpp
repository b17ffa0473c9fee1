#include "app/cli.hpp"
#include "fem/petsc_call.hpp"

#include "common/error.hpp"
#include "common/yaml_input.hpp"

#include <algorithm>
#include <climits>
#include <cmath>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>

namespace sartor {

std::string database_key(const std::string& name) {
  std::string key = "-" + name;
  std::replace(key.begin(), key.end(), '-', '_');
  key[0] = '-';
  return key;
}

namespace {

constexpr int largest_list_index = 99;

} // namespace

std::vector<std::string> option_entries(const OptionSpec& option) {
  std::vector<std::string> names{option.name};
  for (int index = 2; option.indexed && index <= largest_list_index; ++index)
    names.push_back(option.name + std::to_string(index));
  return names;
}

std::vector<OptionSpec> with_module_prefix(std::vector<OptionSpec> options,
                                           const std::vector<std::string>& prefixes,
                                           const std::map<std::string, std::string>& renamed) {
  for (OptionSpec& option : options) {
    const bool prefixed = std::any_of(prefixes.begin(), prefixes.end(), [&](const std::string& p) {
      return option.name.rfind(p + "-", 0) == 0;
    });
    if (prefixed) continue;
    const auto rename = renamed.find(option.name);
    const std::string name =
        rename != renamed.end() ? rename->second : prefixes.front() + "-" + option.name;
    if (name == option.name) continue;
    option.alias = option.name;
    option.name = name;
  }
  return options;
}

namespace {

std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j)
    row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t above = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

// The index of `name` in the list option `list` ("body5" of "body" is 5),
// or 0 where it is not one of its numbered entries (2 to 99, no leading 0).
int list_index(const std::string& list, const std::string& name) {
  if (name.size() <= list.size() || name.compare(0, list.size(), list) != 0) return 0;
  const std::string digits = name.substr(list.size());
  if (digits.size() > 2 || digits[0] == '0' ||
      digits.find_first_not_of("0123456789") != std::string::npos)
    return 0;
  const int index = std::stoi(digits);
  return index >= 2 ? index : 0;
}

// The index of `name` among the entries of `option` (1 for its own name or
// alias, 2 to 99 for their numbered entries), 0 where it is none of them.
int entry_index(const OptionSpec& option, const std::string& name) {
  if (option.answers_to(name)) return 1;
  if (!option.indexed) return 0;
  const int own = list_index(option.name, name);
  return own > 0 ? own : option.alias.empty() ? 0 : list_index(option.alias, name);
}

std::string entry_name(const std::string& list, int index) {
  return index == 1 ? list : list + std::to_string(index);
}

const OptionSpec* lookup(const CommandSpec& spec, const std::string& name) {
  for (const auto& option : spec.options) {
    if (option.answers_to(name)) return &option;
  }
  for (const auto& option : spec.options) {
    if (entry_index(option, name) > 0) return &option;
  }
  return nullptr;
}

[[noreturn]] void unknown_option(const CommandSpec& spec, const std::string& name) {
  std::string message = "sartor " + spec.name + ": unknown option --" + name;
  const OptionSpec* closest = nullptr;
  std::size_t best = 3;
  std::string closest_name;
  for (const auto& option : spec.options) {
    for (const std::string& candidate : {option.name, option.alias}) {
      const std::size_t distance = candidate.empty() ? best : edit_distance(name, candidate);
      if (distance < best) {
        best = distance;
        closest = &option;
        closest_name = candidate;
      }
    }
  }
  if (closest) message += " (did you mean --" + closest_name + "?)";
  throw InputError(message + "; see `sartor " + spec.name + " --help`");
}

// PETSc's YAML options are scalars, in mappings for prefixes; it answers a
// list with a traceback.
void reject_lists(const YAML::Node& node, const std::string& path) {
  if (!node.IsMap()) return;
  for (const auto& entry : node) {
    if (entry.second.IsSequence()) {
      throw InputError(path, entry.second.Mark().line + 1,
                       "option '" + entry.first.Scalar() +
                           "': a list is not an option value (write a,b,c)");
    }
    reject_lists(entry.second, path);
  }
}

// PETSc reads a YAML case itself, with a traceback and no line for a syntax
// error, and lets a repeated key win silently: read here first.
// PETSc's YAML reader stops with a traceback on bytes that are not UTF-8.
void reject_non_utf8(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  long line = 1;
  int continuation = 0; // bytes still expected in the current character
  for (char c; in.get(c);) {
    const auto byte = static_cast<unsigned char>(c);
    const bool follows = (byte & 0xC0) == 0x80;
    if (continuation > 0 ? !follows : (follows || byte >= 0xF8 || byte == 0)) {
      throw InputError(path, line, "not UTF-8 text (byte " + std::to_string(byte) + ")");
    }
    continuation = continuation > 0 ? continuation - 1
                   : byte >= 0xF0   ? 3
                   : byte >= 0xE0   ? 2
                   : byte >= 0xC0   ? 1
                                    : 0;
    if (byte == '\n') ++line;
  }
}

void check_case_file(const CommandSpec& spec, const std::string& path) {
  try {
    reject_non_utf8(path);
    reject_lists(load_yaml_input(path, "case file"), path);
  } catch (const InputError& error) {
    throw InputError("sartor " + spec.name + ": " + error.what());
  }
}

} // namespace

std::string alias_entry(const OptionSpec& option, const std::string& entry) {
  const int index = entry_index(option, entry);
  return option.alias.empty() || index == 0 ? "" : entry_name(option.alias, index);
}

ParsedCommandLine parse_command_line(const CommandSpec& spec, const std::string& program,
                                     const std::vector<std::string>& arguments) {
  ParsedCommandLine parsed;
  parsed.petsc_arguments.push_back(program);
  for (std::size_t i = 0; i < arguments.size(); ++i) {
    const std::string& argument = arguments[i];
    if (argument == "--help" || argument == "-h") {
      parsed.help = true;
    } else if (argument.rfind("--", 0) == 0 && argument.size() > 2) {
      std::string name = argument.substr(2);
      std::string value;
      bool has_value = false;
      if (const auto equals = name.find('='); equals != std::string::npos) {
        value = name.substr(equals + 1);
        name = name.substr(0, equals);
        has_value = true;
      }
      const OptionSpec* option = lookup(spec, name);
      if (!option) unknown_option(spec, name);
      if (option->value_name.empty()) {
        if (has_value) {
          throw InputError("sartor " + spec.name + ": option --" + name + " takes no value");
        }
        value = "true";
      } else if (!has_value) {
        if (i + 1 == arguments.size()) {
          throw InputError("sartor " + spec.name + ": option --" + name + " needs a value (" +
                           option->value_name + ")");
        }
        value = arguments[++i];
      }
      parsed.petsc_arguments.push_back(database_key(name));
      parsed.petsc_arguments.push_back(value);
      parsed.given_names.insert(name);
    } else if ((argument == "-options_file_yaml" || argument == "-options_file") &&
               i + 1 < arguments.size() && !std::ifstream(arguments[i + 1])) {
      throw InputError("sartor " + spec.name + ": " + arguments[i + 1] +
                       ": cannot open options file (" + argument + ")");
    } else if (argument == "-options_file_yaml" && i + 1 < arguments.size()) {
      check_case_file(spec, arguments[i + 1]);
      parsed.petsc_arguments.insert(parsed.petsc_arguments.end(), {argument, arguments[++i]});
    } else if (argument.size() > 1 && argument[0] == '-') {
      // A PETSc option; a following word that is not an option is its value.
      parsed.petsc_arguments.push_back(argument);
      std::string name = argument.substr(1);
      std::replace(name.begin(), name.end(), '_', '-');
      if (lookup(spec, name)) parsed.given_names.insert(name);
      if (i + 1 < arguments.size() && arguments[i + 1].rfind('-', 0) != 0) {
        parsed.petsc_arguments.push_back(arguments[++i]);
      }
    } else {
      parsed.positionals.push_back(argument);
    }
  }
  if (!parsed.help && parsed.positionals.size() != spec.positionals) {
    throw InputError("sartor " + spec.name + " takes " + std::to_string(spec.positionals) +
                     " argument(s), got " + std::to_string(parsed.positionals.size()) +
                     "; usage: " + spec.usage);
  }
  if (!parsed.help && spec.positional_is_options_file) {
    const std::string& file = parsed.positionals.front();
    if (!std::ifstream(file)) {
      throw InputError("sartor " + spec.name + ": " + file + ": cannot open case file");
    }
    check_case_file(spec, file);
    parsed.petsc_arguments.insert(parsed.petsc_arguments.begin() + 1, {"-options_file_yaml", file});
  }
  if (!parsed.help && spec.options_from_positionals) {
    const std::vector<std::string> leading = spec.options_from_positionals(parsed.positionals);
    parsed.petsc_arguments.insert(parsed.petsc_arguments.begin() + 1, leading.begin(),
                                  leading.end());
  }
  return parsed;
}

std::string help_text(const CommandSpec& spec) {
  std::ostringstream out;
  out << "usage: " << spec.usage << "\n\n" << spec.description << "\n\noptions:\n";
  for (const auto& option : spec.options) {
    std::string left = "  --" + option.name + (option.indexed ? "[N]" : "");
    if (!option.value_name.empty()) left += " " + option.value_name;
    out << left;
    if (left.size() < 30) {
      out << std::string(30 - left.size(), ' ');
    } else {
      out << "\n" << std::string(30, ' ');
    }
    out << option.help;
    if (!option.fallback.empty()) out << " [" << option.fallback << "]";
    if (option.indexed) {
      out << "\n"
          << std::string(30, ' ') << "a list: --" << option.name << ", --" << option.name
          << "2, ... --" << option.name << largest_list_index;
    }
    if (!option.alias.empty())
      out << "\n"
          << std::string(30, ' ') << "or --" << option.alias << (option.indexed ? "[N]" : "");
    out << "\n";
  }
  out << "  -h, --help                  this text\n\n"
         "Options can also come from a YAML file (-options_file_yaml FILE, keys without\n"
         "dashes, e.g. load_duration: 3600). PETSc options (-log_view, -options_view,\n"
         "-tao_monitor, ...) are accepted as well.\n";
  const bool prefixed = std::any_of(spec.options.begin(), spec.options.end(),
                                    [](const OptionSpec& option) { return !option.alias.empty(); });
  if (prefixed) {
    out << "An option named with its module's prefix may be grouped under it in YAML\n"
           "(material: then warp_modulus: 5000 indented below it); its other name (\"or\")\n"
           "is the same option.\n";
  }
  return out.str();
}

const OptionSpec& Options::find(const std::string& name) const {
  const OptionSpec* option = lookup(spec_, name);
  if (!option) throw std::logic_error("option --" + name + " is not declared");
  return *option;
}

std::string Options::own_name(const std::string& name) const {
  const OptionSpec& option = find(name);
  return entry_name(option.name, entry_index(option, name));
}

namespace {

// An entry's value in the database under `name` (nullptr for a flag without one).
bool database_value(const std::string& name, const char** value) {
  *value = nullptr;
  if (name.empty()) return false;
  PetscBool set = PETSC_FALSE;
  // The value in full: PETSc's string getter would cut it at 4,095 characters.
  SartorPetscCall(PetscOptionsFindPair(nullptr, nullptr, database_key(name).c_str(), value, &set));
  return set == PETSC_TRUE;
}

} // namespace

bool Options::given(const std::string& name, const char** value) const {
  const std::string own = own_name(name);
  const std::string alias = alias_entry(find(name), own);
  const char* by_alias = nullptr;
  const bool own_set = database_value(own, value);
  const bool alias_set = database_value(alias, &by_alias);
  if (!alias_set) return own_set;
  const auto text_of = [](const char* v) { return std::string(v ? v : ""); };
  const bool own_on_command_line = command_line_.count(own) > 0;
  const bool alias_on_command_line = command_line_.count(alias) > 0;
  if (!own_set || (alias_on_command_line && !own_on_command_line)) {
    *value = by_alias;
  } else if (text_of(*value) != text_of(by_alias) && own_on_command_line == alias_on_command_line) {
    throw InputError("option --" + own + " is given twice, as '" + text_of(*value) + "' and as '" +
                     text_of(by_alias) + "' by its other name --" + alias);
  }
  return true;
}

std::string Options::other_name(const std::string& name) const {
  const OptionSpec* option = lookup(spec_, name);
  if (!option) return "";
  const std::string own = own_name(name);
  return own == name ? alias_entry(*option, own) : own;
}

std::string Options::name_given(const std::string& name) const {
  const std::string own = own_name(name);
  const std::string alias = alias_entry(find(name), own);
  const char* value = nullptr;
  if (!database_value(alias, &value)) return own;
  return database_value(own, &value) && !command_line_.count(alias) ? own : alias;
}

bool Options::is_set(const std::string& name) const {
  const char* value = nullptr;
  const bool in_database = given(name, &value);
  const std::string own = own_name(name);
  if (const auto replaced = replaced_.find(own); replaced != replaced_.end())
    return replaced->second.has_value();
  return in_database || defaults_.count(own) > 0;
}

std::string Options::text(const std::string& name) const {
  const OptionSpec& option = find(name);
  const char* value = nullptr;
  const bool in_database = given(name, &value);
  const std::string own = own_name(name);
  if (const auto replaced = replaced_.find(own); replaced != replaced_.end())
    return replaced->second.value_or(option.fallback);
  if (!in_database) {
    const auto command_default = defaults_.find(own);
    return command_default != defaults_.end() ? command_default->second : option.fallback;
  }
  if ((!value || value[0] == '\0') && !option.value_name.empty()) {
    throw InputError("option --" + name_given(name) + " needs a value (" + option.value_name + ")");
  }
  return value ? value : "";
}

void Options::set_default(const std::string& name, const std::string& value) {
  if (is_set(name)) return;
  replaced_.erase(own_name(name));
  defaults_[own_name(name)] = value;
}

void Options::set(const std::string& name, const std::string& value) {
  defaults_.erase(own_name(name));
  replaced_[own_name(name)] = value;
}

void Options::clear(const std::string& name) {
  defaults_.erase(own_name(name));
  replaced_[own_name(name)] = std::nullopt;
}

std::vector<std::pair<std::string, std::string>> Options::command_defaults() const {
  std::vector<std::pair<std::string, std::string>> entries;
  for (const auto& [name, value] : defaults_)
    entries.emplace_back(database_key(name), value);
  return entries;
}

double Options::real(const std::string& name) const {
  const std::string value = text(name);
  try {
    std::size_t used = 0;
    const double number = std::stod(value, &used);
    if (used == value.size() && std::isfinite(number)) return number;
  } catch (const std::exception&) {
  }
  throw InputError("option --" + name_given(name) + ": '" + value + "' is not a finite number");
}

double Options::positive_real(const std::string& name) const {
  const double value = real(name);
  if (value <= 0.0)
    throw InputError("option --" + name_given(name) + ": must be > 0, got " + text(name));
  return value;
}

double Options::nonnegative_real(const std::string& name) const {
  const double value = real(name);
  if (value < 0.0)
    throw InputError("option --" + name_given(name) + ": must be >= 0, got " + text(name));
  return value;
}

long Options::integer(const std::string& name) const {
  return integer_in(name, INT_MIN, INT_MAX);
}

long Options::integer_in(const std::string& name, long minimum, long maximum) const {
  const std::string value = text(name);
  long number = 0;
  try {
    std::size_t used = 0;
    number = std::stol(value, &used);
    if (used != value.size()) throw std::invalid_argument(value);
  } catch (const std::out_of_range&) {
    number = value.find('-') == std::string::npos ? LONG_MAX : LONG_MIN;
  } catch (const std::exception&) {
    throw InputError("option --" + name_given(name) + ": '" + value + "' is not an integer");
  }
  if (number < minimum || number > maximum) {
    throw InputError("option --" + name_given(name) + ": must be between " +
                     std::to_string(minimum) + " and " + std::to_string(maximum) + ", got " +
                     value);
  }
  return number;
}

namespace {

// The kinds a help text is scoped to: "dynamic, creep: end time" gives
// {dynamic, creep}; "dynamic: time step; creep: the first step" gives both.
std::set<std::string> help_scopes(const std::string& help, const std::set<std::string>& kinds) {
  std::set<std::string> scopes;
  static const std::regex scope_list("(^|; )([a-z_]+(, [a-z_]+)*):");
  for (auto match = std::sregex_iterator(help.begin(), help.end(), scope_list);
       match != std::sregex_iterator(); ++match) {
    std::stringstream words((*match)[2].str());
    std::set<std::string> found;
    for (std::string word; std::getline(words, word, ',');) {
      if (word.front() == ' ') word.erase(0, 1);
      found.insert(word);
    }
    const bool all_kinds = std::all_of(found.begin(), found.end(),
                                       [&](const std::string& w) { return kinds.count(w) > 0; });
    if (all_kinds) scopes.insert(found.begin(), found.end());
  }
  return scopes;
}

} // namespace

void Options::reject_inapplicable(const std::string& selector,
                                  const std::set<std::string>& kinds) const {
  const std::string kind = text(selector);
  for (const auto& option : spec_.options) {
    const std::set<std::string> scopes = help_scopes(option.help, kinds);
    if (scopes.empty() || scopes.count(kind) || !is_set(option.name)) continue;
    std::string list;
    for (const auto& scope : scopes)
      list += (list.empty() ? "" : " or ") + scope;
    throw InputError("option --" + name_given(option.name) + " applies to --" +
                     name_given(selector) + " " + list + " only, not to --" + name_given(selector) +
                     " " + kind);
  }
}

bool Options::flag(const std::string& name) const {
  if (!is_set(name)) return false;
  const std::string value = text(name);
  if (value.empty() || value == "true" || value == "1" || value == "yes") return true;
  if (value == "false" || value == "0" || value == "no") return false;
  throw InputError("option --" + name_given(name) + ": '" + value + "' is not true or false");
}

std::vector<std::pair<std::string, std::string>> Options::indexed(const std::string& name) const {
  const OptionSpec& list = find(name);
  if (!list.indexed) throw std::logic_error("option --" + name + " is not a list");
  std::vector<std::pair<std::string, std::string>> entries;
  for (const std::string& entry : option_entries(list))
    if (is_set(entry)) entries.emplace_back(name_given(entry), text(entry));
  return entries;
}

std::vector<std::pair<std::string, std::string>> Options::effective() const {
  std::vector<std::pair<std::string, std::string>> values;
  for (const auto& option : spec_.options) {
    if (option.indexed) {
      for (const auto& [entry, value] : indexed(option.name))
        values.emplace_back(own_name(entry), value);
    } else if (option.value_name.empty()) {
      values.emplace_back(option.name, flag(option.name) ? "true" : "false");
    } else if (is_set(option.name) || !option.fallback.empty()) {
      values.emplace_back(option.name, text(option.name));
    }
  }
  return values;
}

} // namespace sartor
