// sartor: finite-element statics of non-elastic cloth. One executable, one
// command per capability; `sartor --help` lists them.

#include "app/commands.hpp"
#include "common/error.hpp"
#include "fem/petsc_call.hpp"

#include <petscsys.h>

#include <csignal>
#include <cstdio>
#include <exception>
#include <set>
#include <string>
#include <vector>

#include <unistd.h>

namespace {

using sartor::Command;

const std::vector<Command>& commands() {
  static const std::vector<Command> all = {
      {sartor::creep_command, sartor::run_creep},
      {sartor::fit_command, sartor::run_fit},
      {sartor::synth_command, sartor::run_synth},
      {sartor::validate_command, sartor::run_validate},
      {sartor::fabrics_command, sartor::run_fabrics},
      {sartor::run_command, sartor::run_run},
      {sartor::converge_command, sartor::run_converge},
      {sartor::pattern_command, sartor::run_pattern},
      {sartor::body_command, sartor::run_body},
      {sartor::construct_command, sartor::run_construct},
      {sartor::drape_command, sartor::run_drape},
      {sartor::edit_command, sartor::run_edit},
      {sartor::import_command, sartor::run_import},
      {sartor::wrap_command, sartor::run_wrap},
      {sartor::drag_command, sartor::run_drag},
  };
  return all;
}

void print_overview() {
  std::printf("sartor %s: finite-element statics of non-elastic cloth\n\n"
              "usage: sartor COMMAND [options]\n\ncommands:\n",
              SARTOR_VERSION);
  for (const auto& command : commands()) {
    std::printf("  %-10s %s\n", command.spec().name.c_str(), command.spec().summary.c_str());
  }
  std::printf("\n`sartor COMMAND --help` describes a command; docs/user-guide.md has the rest.\n");
}

const Command* find_command(const std::string& name) {
  for (const auto& command : commands()) {
    if (command.spec().name == name) return &command;
  }
  return nullptr;
}

// PETSc's message alone for a bad option value or input; its full traceback
// for anything else, which is a bug worth reporting.
PetscErrorCode report_petsc_error(MPI_Comm comm, int line, const char* function, const char* file,
                                  PetscErrorCode code, PetscErrorType type, const char* message,
                                  void* context) {
  if (!sartor::is_petsc_user_error(code)) {
    return PetscTraceBackErrorHandler(comm, line, function, file, code, type, message, context);
  }
  if (type == PETSC_ERROR_INITIAL && message) {
    PetscMPIInt rank = 0;
    MPI_Comm_rank(comm, &rank);
    if (rank == 0) std::fprintf(stderr, "PETSc: %s\n", message);
  }
  return code;
}

// A bug, not a user's mistake. Other ranks may be waiting in a collective
// call, so a parallel run is aborted.
int report_internal_error(const Command& command, const std::exception& error) {
  std::fprintf(stderr, "sartor %s: internal error: %s\n", command.spec().name.c_str(),
               error.what());
  PetscMPIInt size = 1;
  MPI_Comm_size(PETSC_COMM_WORLD, &size);
  if (size > 1) MPI_Abort(PETSC_COMM_WORLD, 1);
  return 1;
}

// Options that had no effect are most often typos (in a YAML case, say).
PetscErrorCode warn_about_unused_options() {
  PetscInt count = 0;
  char** names = nullptr;
  char** values = nullptr;
  PetscFunctionBeginUser;
  PetscCall(PetscOptionsLeftGet(nullptr, &count, &names, &values));
  for (PetscInt i = 0; i < count; ++i) {
    // PETSc reads these itself, in PetscFinalize.
    static const std::set<std::string> read_at_exit = {
        "options_left", "options_view", "malloc_dump", "memory_view", "objects_dump"};
    if (read_at_exit.count(names[i])) continue;
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "sartor: warning: option -%s%s%s was not used\n",
                          names[i], values[i] ? " " : "", values[i] ? values[i] : ""));
  }
  PetscCall(PetscOptionsLeftRestore(nullptr, &count, &names, &values));
  PetscFunctionReturn(0);
}

// An interrupted run ends with a one-line note and the status of the signal
// (128 + number), not PETSc's handler, which prints a traceback as for a
// crash and calls MPI_Abort. Files are written atomically, so what was written
// before the signal is intact.
extern "C" void end_on_signal(int number) {
  static const char note[] = "sartor: interrupted\n";
  if (number != SIGPIPE) {
    const ssize_t ignored = ::write(STDERR_FILENO, note, sizeof note - 1);
    static_cast<void>(ignored);
  }
  std::signal(number, SIG_DFL);
  std::raise(number);
}

// A closed pipe (`sartor creep | head -1`), Ctrl-C and kill end the program
// quietly; PETSc keeps its handler for crashes (SIGSEGV, SIGFPE), which are bugs.
void install_signal_handlers() {
  for (int number : {SIGPIPE, SIGINT, SIGTERM, SIGHUP})
    std::signal(number, end_on_signal);
}

int run_with_petsc(const Command& command, sartor::ParsedCommandLine parsed,
                   std::vector<std::string> arguments) {
  std::vector<char*> petsc_argv;
  for (auto& argument : parsed.petsc_arguments)
    petsc_argv.push_back(argument.data());
  petsc_argv.push_back(nullptr);
  int argc = int(petsc_argv.size()) - 1;
  char** argv = petsc_argv.data();
  PetscCall(PetscInitialize(&argc, &argv, nullptr, nullptr));
  PetscCall(PetscPushErrorHandler(report_petsc_error, nullptr));
  install_signal_handlers();

  int status = 1;
  try {
    sartor::Options options(command.spec(), parsed.given_names);
    const sartor::Invocation invocation{std::move(parsed), std::move(options),
                                        std::move(arguments)};
    status = command.run(invocation);
  } catch (const sartor::InputError& error) {
    // Inputs are read on every rank, so every rank gets here: one report.
    if (sartor::is_root()) {
      std::fprintf(stderr, "sartor %s: error: %s\n", command.spec().name.c_str(), error.what());
    }
    status = 2;
  } catch (const sartor::SolveFailure& error) {
    if (sartor::is_root()) {
      std::fprintf(stderr, "sartor %s: error: %s\n", command.spec().name.c_str(), error.what());
    }
    status = 1;
  } catch (const sartor::PetscFailure& error) {
    if (error.is_user_error()) {
      if (sartor::is_root()) {
        std::fprintf(stderr, "sartor %s: error: PETSc rejected an option or input (above)\n",
                     command.spec().name.c_str());
      }
      status = 2;
    } else {
      status = report_internal_error(command, error);
    }
  } catch (const std::exception& error) {
    status = report_internal_error(command, error);
  }
  if (status == 0) PetscCall(warn_about_unused_options());
  PetscCall(PetscFinalize());
  return status;
}

} // namespace

int main(int argc, char** argv) {
  const std::vector<std::string> arguments(argv + 1, argv + argc);
  if (arguments.empty() || arguments[0] == "--help" || arguments[0] == "-h" ||
      arguments[0] == "help") {
    if (arguments.size() > 1) {
      if (const Command* command = find_command(arguments[1])) {
        std::fputs(sartor::help_text(command->spec()).c_str(), stdout);
        return 0;
      }
    }
    print_overview();
    return arguments.empty() ? 2 : 0;
  }
  if (arguments[0] == "--version") {
    std::printf("sartor %s\n", SARTOR_VERSION);
    return 0;
  }
  const Command* command = find_command(arguments[0]);
  if (!command) {
    std::fprintf(stderr, "sartor: unknown command '%s'; `sartor --help` lists them\n",
                 arguments[0].c_str());
    return 2;
  }
  const std::vector<std::string> rest(arguments.begin() + 1, arguments.end());
  sartor::ParsedCommandLine parsed;
  try {
    parsed = sartor::parse_command_line(command->spec(), argv[0], rest);
  } catch (const sartor::InputError& error) {
    std::fprintf(stderr, "%s\n", error.what());
    return 2;
  }
  if (parsed.help) {
    std::fputs(sartor::help_text(command->spec()).c_str(), stdout);
    return 0;
  }
  return run_with_petsc(*command, std::move(parsed), arguments);
}
