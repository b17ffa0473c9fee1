#include "app/commands.hpp"
#include "common/error.hpp"

#include <nlohmann/json.hpp>
#include <petscsys.h>

#include <cmath>
#include <cstdlib>
#include <ctime>
#include <spawn.h>
#include <sstream>
#include <stdexcept>
#include <sys/wait.h>

extern char** environ;

namespace sartor {

double process_cpu_seconds() {
  return double(std::clock()) / CLOCKS_PER_SEC;
}

void print_warnings(const std::vector<std::string>& warnings) {
  for (const std::string& warning : warnings)
    PetscFPrintf(PETSC_COMM_WORLD, PETSC_STDERR, "warning: %s\n", warning.c_str());
}

bool minimiser_chosen(const Options& options, const std::string& name) {
  const std::string solver = options.text(name);
  if (solver != "minimise" && solver != "snes") {
    throw InputError("option --" + name + ": unknown solver '" + solver + "' (minimise, snes)");
  }
  return solver == "minimise";
}

int count_option(const Options& options, const std::string& name, long minimum,
                 const std::string& fallback) {
  const std::string used = options.is_set(name) || fallback.empty() ? name : fallback;
  const long value = options.integer(used);
  if (value < minimum) {
    throw InputError("option --" + used + ": must be >= " + std::to_string(minimum) + ", got " +
                     options.text(used));
  }
  return int(value);
}

std::vector<double> option_numbers(const Options& options, const std::string& name,
                                   std::size_t count) {
  const std::string text = options.text(name);
  std::vector<double> values;
  std::stringstream stream(text);
  std::string item;
  while (std::getline(stream, item, ',')) {
    try {
      std::size_t used = 0;
      values.push_back(std::stod(item, &used));
      if (used != item.size() || !std::isfinite(values.back())) throw std::invalid_argument(item);
    } catch (const std::exception&) {
      throw InputError("option --" + name + ": '" + item + "' is not a number");
    }
  }
  if (count != 0 && values.size() != count) {
    throw InputError("option --" + name + ": expected " + std::to_string(count) +
                     " comma-separated numbers, got '" + text + "'");
  }
  return values;
}

bool is_root() {
  PetscMPIInt rank = 0;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  return rank == 0;
}

nlohmann::json run_metadata(const Invocation& invocation, const std::string& command) {
  PetscMPIInt size = 1;
  MPI_Comm_size(PETSC_COMM_WORLD, &size);
  nlohmann::json options = nlohmann::json::object();
  for (const auto& [name, value] : invocation.options.effective())
    options[name] = value;
  return {{"sartor_version", SARTOR_VERSION},
          {"command", command},
          {"arguments", invocation.arguments},
          {"options", options},
          {"mpi_ranks", size}};
}

void make_plot(const std::string& script, const std::string& directory) {
  int status = 0;
  std::string problem;
  if (is_root()) {
    const char* override = std::getenv("SARTOR_PYTHON");
    std::string python = override ? override : "/usr/bin/python3";
    std::string path = std::string(SARTOR_POSTPROC_DIR) + "/" + script;
    std::string target = directory;
    char* argv[] = {python.data(), path.data(), target.data(), nullptr};
    pid_t child = 0;
    if (posix_spawn(&child, python.c_str(), nullptr, nullptr, argv, environ) != 0) {
      status = -1;
    } else if (waitpid(child, &status, 0) < 0) {
      status = -1;
    }
    if (status != 0) {
      problem = "plotting failed: `" + python + " " + path + " " + directory +
                "` did not succeed (needs the Debian packages python3-numpy and "
                "python3-matplotlib; use --no-plot to skip). The data files are complete.";
    }
  }
  MPI_Bcast(&status, 1, MPI_INT, 0, PETSC_COMM_WORLD);
  if (status != 0) throw SolveFailure(problem.empty() ? "plotting failed on rank 0" : problem);
}

} // namespace sartor
