#pragma once
// The `sartor` commands: each has a spec (options, help) and a run function.

#include "app/cli.hpp"

#include <nlohmann/json_fwd.hpp>

#include <functional>
#include <string>
#include <vector>

namespace sartor {

struct CaseResult;
struct ClothOutputLabels;

// `sartor run` and `sartor drape` hand their solved case here, with its
// summary and labels, once the results are written and before a failure is
// reported: the Python module (python/sartor_python.cpp) keeps them in memory.
using CaseResultSink = std::function<void(const CaseResult& result, const nlohmann::json& summary,
                                          const ClothOutputLabels& labels)>;

struct Invocation {
  ParsedCommandLine command_line;
  Options options;
  std::vector<std::string> arguments; // as typed, for the run's metadata
  CaseResultSink keep_result = {};    // empty on the command line
};

struct Command {
  const CommandSpec& (*spec)();
  int (*run)(const Invocation&); // exit status
};

const CommandSpec& creep_command();
int run_creep(const Invocation&);
const CommandSpec& fit_command();
int run_fit(const Invocation&);
const CommandSpec& synth_command();
int run_synth(const Invocation&);
const CommandSpec& validate_command();
int run_validate(const Invocation&);
const CommandSpec& fabrics_command();
int run_fabrics(const Invocation&);
const CommandSpec& run_command();
int run_run(const Invocation&);
const CommandSpec& converge_command();
int run_converge(const Invocation&);
const CommandSpec& pattern_command();
int run_pattern(const Invocation&);
const CommandSpec& body_command();
int run_body(const Invocation&);
const CommandSpec& construct_command();
int run_construct(const Invocation&);
const CommandSpec& drape_command();
int run_drape(const Invocation&);
const CommandSpec& edit_command();
int run_edit(const Invocation&);
const CommandSpec& import_command();
int run_import(const Invocation&);
const CommandSpec& wrap_command();
int run_wrap(const Invocation&);
const CommandSpec& drag_command();
int run_drag(const Invocation&);

// Metadata every output JSON carries: version, command line, options used.
nlohmann::json run_metadata(const Invocation& invocation, const std::string& command);

// Runs postproc/SCRIPT on `directory` with /usr/bin/python3 (or $SARTOR_PYTHON)
// on rank 0. Throws InputError, on every rank, when the plot could not be made.
void make_plot(const std::string& script, const std::string& directory);

// Rank 0 writes; everybody waits, and learns of a failure.
bool is_root();

// CPU time of this process (user + system), s.
double process_cpu_seconds();

// "warning: TEXT" on rank 0's standard error for each (plausibility
// warnings of the fabric readers).
void print_warnings(const std::vector<std::string>& warnings);
// The comma-separated numbers of option --NAME; `count` of them unless it is
// 0. Throws InputError naming the option and the item that is not a number.
std::vector<double> option_numbers(const Options& options, const std::string& name,
                                   std::size_t count);

// Option --NAME (or, when it is not given and FALLBACK is, --FALLBACK) as
// a count >= minimum. Throws InputError naming the option used.
int count_option(const Options& options, const std::string& name, long minimum,
                 const std::string& fallback = "");

// Whether option --NAME (--static-solver, --dynamic-solver) chooses the
// minimiser: "minimise" or "snes"; throws InputError naming the option
// for anything else.
bool minimiser_chosen(const Options& options, const std::string& name);

} // namespace sartor
