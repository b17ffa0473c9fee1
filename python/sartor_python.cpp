// sartor._sartor: `sartor run` and `sartor drape` in the Python process. The
// commands' own run functions (app/run_command.cpp, drape_command.cpp)
// run with the options a Python call gives, as the command line would give
// them; the solved case comes back through Invocation::keep_result and
// becomes numpy arrays and a dict, with no file read back. PETSc (and MPI)
// start once, at the first call, and end when the interpreter exits.
// docs/python.md describes the interface; python/sartor/__init__.py wraps it.

#include "app/cloth_case.hpp"
#include "app/commands.hpp"
#include "common/error.hpp"
#include "common/output.hpp"
#include "fem/cloth_output.hpp"
#include "fem/petsc_call.hpp"

#include <nlohmann/json.hpp>
#include <petscsys.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace py = pybind11;

namespace {

using sartor::CaseResult;
using sartor::ClothOutputLabels;

// The message of the last PETSc error, for the Python exception.
std::string& last_petsc_message() {
  static std::string message;
  return message;
}

// Keeps PETSc's message of a bad option or input for the exception; prints
// the traceback of anything else (a bug), as the executable does.
PetscErrorCode keep_petsc_error(MPI_Comm comm, int line, const char* function, const char* file,
                                PetscErrorCode code, PetscErrorType type, const char* message,
                                void* context) {
  if (!sartor::is_petsc_user_error(code)) {
    return PetscTraceBackErrorHandler(comm, line, function, file, code, type, message, context);
  }
  if (type == PETSC_ERROR_INITIAL && message) last_petsc_message() = message;
  return code;
}

PetscErrorCode finalize_petsc() {
  PetscBool initialized = PETSC_FALSE, finalized = PETSC_FALSE;
  PetscCall(PetscInitialized(&initialized));
  PetscCall(PetscFinalized(&finalized));
  if (initialized && !finalized) PetscCall(PetscFinalize());
  return 0;
}

// PETSc starts once per process, without its signal handlers (Python keeps
// Ctrl-C); it ends when the interpreter exits. A host that initialised
// PETSc itself (petsc4py) keeps it, and finalises it.
void ensure_petsc() {
  PetscBool initialized = PETSC_FALSE;
  SartorPetscCall(PetscInitialized(&initialized));
  if (initialized) return;
  static char program[] = "sartor";
  static char no_signals[] = "-no_signal_handler";
  static char* words[] = {program, no_signals, nullptr};
  int count = 2;
  char** argv = words;
  if (PetscInitialize(&count, &argv, nullptr, nullptr) != 0) {
    throw std::runtime_error("sartor: PETSc did not initialise");
  }
  py::module_::import("atexit").attr("register")(py::cpp_function([] { finalize_petsc(); }));
}

// PETSc options set for every later call (set_petsc_options).
std::vector<std::pair<std::string, std::string>>& persistent_petsc_options() {
  static std::vector<std::pair<std::string, std::string>> options;
  return options;
}

// The text an option value stands for: a list or tuple joined by commas.
std::string option_text(const py::handle& value) {
  if (py::isinstance<py::list>(value) || py::isinstance<py::tuple>(value)) {
    std::string joined;
    for (const py::handle item : value)
      joined += (joined.empty() ? "" : ",") + std::string(py::str(item));
    return joined;
  }
  return py::str(value);
}

// The `sartor COMMAND` words of keyword options (underscores become dashes):
// True gives a flag, False and None leave the option out.
void add_option_words(const py::dict& options, std::vector<std::string>& words) {
  for (const auto& [key, value] : options) {
    if (value.is_none() || (py::isinstance<py::bool_>(value) && !value.cast<bool>())) continue;
    std::string name = py::str(key);
    std::replace(name.begin(), name.end(), '_', '-');
    words.push_back("--" + name);
    if (!py::isinstance<py::bool_>(value)) words.push_back(option_text(value));
  }
}

// PETSc options without their dash; None gives a flag.
void add_petsc_words(const std::vector<std::pair<std::string, std::string>>& options,
                     std::vector<std::string>& words) {
  for (const auto& [name, value] : options) {
    words.push_back("-" + name);
    if (!value.empty()) words.push_back(value);
  }
}

std::vector<std::pair<std::string, std::string>> petsc_pairs(const py::dict& petsc) {
  std::vector<std::pair<std::string, std::string>> pairs;
  for (const auto& [key, value] : petsc)
    pairs.emplace_back(py::str(key), value.is_none() ? std::string() : option_text(value));
  return pairs;
}

// A case given as a dict becomes DIRECTORY/case.yaml: `sartor run` reads it
// as it reads a case file, and it re-runs the job from the command line.
std::string write_case_file(const py::dict& options, const std::string& directory) {
  sartor::make_output_directory(directory);
  const std::string path = directory + "/case.yaml";
  std::ofstream file(path);
  file << "# written by the sartor Python module\n";
  for (const auto& [key, value] : options) {
    if (value.is_none()) continue;
    std::string text = py::isinstance<py::bool_>(value) ? (value.cast<bool>() ? "true" : "false")
                                                        : option_text(value);
    std::string quoted;
    for (const char c : text)
      quoted += (c == '"' || c == '\\') ? std::string("\\") + c : std::string(1, c);
    file << std::string(py::str(key)) << ": \"" << quoted << "\"\n";
  }
  if (!file) throw sartor::InputError(path + ": cannot write the case file");
  return path;
}

template <typename T>
py::array_t<T> array(std::vector<py::ssize_t> shape, const std::vector<T>& data) {
  py::array_t<T> result(shape);
  std::copy(data.begin(), data.end(), result.mutable_data());
  return result;
}

py::array_t<double> vectors_array(const std::vector<Eigen::Vector3d>& vectors) {
  std::vector<double> flat;
  flat.reserve(3 * vectors.size());
  for (const auto& v : vectors)
    flat.insert(flat.end(), {v.x(), v.y(), v.z()});
  return array<double>({py::ssize_t(vectors.size()), 3}, flat);
}

py::dict cell_fields(const std::vector<sartor::element::MembraneStrain>& strains) {
  const std::vector<std::pair<const char*, double sartor::element::MembraneStrain::*>> members = {
      {"strain_warp", &sartor::element::MembraneStrain::warp},
      {"strain_weft", &sartor::element::MembraneStrain::weft},
      {"strain_shear", &sartor::element::MembraneStrain::shear},
      {"tension_warp", &sartor::element::MembraneStrain::tension_warp},
      {"tension_weft", &sartor::element::MembraneStrain::tension_weft}};
  py::dict fields;
  for (const auto& [name, member] : members) {
    std::vector<double> values;
    for (const auto& strain : strains)
      values.push_back(strain.*member);
    fields[name] = array<double>({py::ssize_t(values.size())}, values);
  }
  return fields;
}

py::dict mesh_arrays(const sartor::TriangleMesh& mesh, const ClothOutputLabels& labels) {
  const auto triangles = py::ssize_t(mesh.triangle_count());
  std::vector<long> corners, fabric_ids(mesh.triangle_count(), 0);
  std::vector<double> uv;
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    for (int k = 0; k < 3; ++k) {
      corners.push_back(mesh.triangles[t][k]);
      uv.insert(uv.end(), {mesh.material_uv[t][k].x(), mesh.material_uv[t][k].y()});
    }
    if (!mesh.material_ids.empty()) fabric_ids[t] = mesh.material_ids[t];
  }
  py::dict arrays;
  arrays["initial_positions"] = vectors_array(mesh.positions);
  arrays["triangles"] = array<long>({triangles, 3}, corners);
  arrays["material_uv"] = array<double>({triangles, 3, 2}, uv);
  arrays["fabric_ids"] = array<long>({triangles}, fabric_ids);
  arrays["fabric_names"] = labels.fabrics;
  std::vector<long> panels(labels.panel_of_triangle.begin(), labels.panel_of_triangle.end());
  arrays["panel_ids"] = array<long>({py::ssize_t(panels.size())}, panels);
  arrays["panel_names"] = labels.panels;
  return arrays;
}

// The solved case as Python objects: arrays of the mesh and of the final
// state, the summary (as summary.json has it) and the unit of every array.
py::dict result_dict(const CaseResult& result, const nlohmann::json& summary,
                     const ClothOutputLabels& labels) {
  py::dict out = mesh_arrays(result.mesh, labels);
  out["positions"] = vectors_array(result.positions);
  std::vector<Eigen::Vector3d> displacement = result.positions;
  for (std::size_t v = 0; v < displacement.size(); ++v)
    displacement[v] -= result.mesh.positions[v];
  out["displacement"] = vectors_array(displacement);
  out["cell_fields"] = cell_fields(result.strains);
  // Keyed as result.h5's datasets, whose `units` attributes say the same.
  py::dict units;
  for (const char* name :
       {"fields/position", "fields/displacement", "mesh/initial_position", "mesh/material_uv"})
    units[name] = "m";
  for (const char* name : {"mesh/triangles", "mesh/fabric_id", "cell_fields/strain_warp",
                           "cell_fields/strain_weft", "cell_fields/strain_shear"})
    units[name] = "1";
  units["cell_fields/tension_warp"] = "N/m";
  units["cell_fields/tension_weft"] = "N/m";
  if (!labels.panel_of_triangle.empty()) units["mesh/panel_id"] = "1";
  py::dict vertex_fields;
  for (const sartor::ClothNodeField& field : result.vertex_loads) {
    vertex_fields[field.name.c_str()] =
        array<double>({py::ssize_t(field.values.size())}, field.values);
    units[("fields/" + field.name).c_str()] = field.units;
  }
  out["vertex_fields"] = vertex_fields;
  out["units"] = units;
  out["summary"] = py::module_::import("json").attr("loads")(summary.dump());
  return out;
}

// Options that had no effect (most often typos), as the executable warns.
std::vector<std::string> unused_options() {
  static const std::set<std::string> read_at_exit = {"options_left", "options_view", "malloc_dump",
                                                     "memory_view", "objects_dump"};
  PetscInt count = 0;
  char** names = nullptr;
  char** values = nullptr;
  SartorPetscCall(PetscOptionsLeftGet(nullptr, &count, &names, &values));
  std::vector<std::string> unused;
  for (PetscInt i = 0; i < count; ++i) {
    if (read_at_exit.count(names[i])) continue;
    unused.push_back("-" + std::string(names[i]) + (values[i] ? " " + std::string(values[i]) : ""));
  }
  SartorPetscCall(PetscOptionsLeftRestore(nullptr, &count, &names, &values));
  return unused;
}

// The options database holds exactly this call's command line.
void load_options(const sartor::ParsedCommandLine& parsed) {
  std::vector<std::string> arguments = parsed.petsc_arguments;
  std::vector<char*> pointers;
  for (auto& argument : arguments)
    pointers.push_back(argument.data());
  pointers.push_back(nullptr);
  int count = int(pointers.size()) - 1;
  char** argv = pointers.data();
  SartorPetscCall(PetscOptionsClear(nullptr));
  SartorPetscCall(PetscOptionsInsert(nullptr, &count, &argv, nullptr));
}

struct Outcome {
  std::optional<py::dict> result;
  std::string error;     // empty: none
  const char* kind = ""; // InputError, SolveFailure or Error
};

// Runs COMMAND's own run function as `sartor COMMAND WORDS...` would.
Outcome run_in_process(const sartor::Command& command, const std::vector<std::string>& words) {
  ensure_petsc();
  Outcome outcome;
  const std::string& name = command.spec().name;
  last_petsc_message().clear();
  SartorPetscCall(PetscPushErrorHandler(keep_petsc_error, nullptr));
  try {
    sartor::ParsedCommandLine parsed = sartor::parse_command_line(command.spec(), "sartor", words);
    load_options(parsed);
    sartor::Invocation invocation{
        parsed, sartor::Options(command.spec(), parsed.given_names), words, {}};
    invocation.arguments.insert(invocation.arguments.begin(), name);
    invocation.keep_result = [&outcome](const CaseResult& result, const nlohmann::json& summary,
                                        const ClothOutputLabels& labels) {
      outcome.result = result_dict(result, summary, labels);
    };
    command.run(invocation);
  } catch (const sartor::InputError& error) {
    // The command line's own errors name the command already.
    const std::string what = error.what();
    const std::string prefix = "sartor " + name + ": ";
    outcome = {std::nullopt, what.rfind(prefix, 0) == 0 ? what : prefix + what, "InputError"};
  } catch (const sartor::SolveFailure& error) {
    outcome.error = "sartor " + name + ": " + error.what();
    outcome.kind = "SolveFailure";
  } catch (const sartor::PetscFailure& error) {
    const bool input = error.is_user_error();
    outcome = {std::nullopt,
               "sartor " + name + ": " +
                   (input ? "PETSc rejected an option or input: " + last_petsc_message()
                          : std::string(error.what())),
               input ? "InputError" : "Error"};
  } catch (const std::exception& error) {
    // A bug, as the executable's "internal error" says.
    outcome = {std::nullopt, "sartor " + name + ": internal error: " + error.what(), "Error"};
  }
  SartorPetscCall(PetscPopErrorHandler());
  if (outcome.result) (*outcome.result)["unused_options"] = unused_options();
  std::fflush(stdout);
  std::fflush(stderr);
  return outcome;
}

py::object outcome_or_raise(const py::module_& module, Outcome outcome) {
  if (outcome.error.empty()) return *outcome.result;
  const py::object type = module.attr(outcome.kind);
  py::object error = type(outcome.error);
  error.attr("result") = outcome.result ? py::object(*outcome.result) : py::object(py::none());
  PyErr_SetObject(type.ptr(), error.ptr());
  throw py::error_already_set();
}

std::vector<std::string> command_words(const std::string& argument, const std::string& output,
                                       bool plot, const py::dict& petsc, const py::dict& options) {
  std::vector<std::string> words{argument, "--output", output};
  if (!plot) words.push_back("--no-plot");
  add_option_words(options, words);
  add_petsc_words(persistent_petsc_options(), words);
  add_petsc_words(petsc_pairs(petsc), words);
  return words;
}

const char* const run_doc = R"(run(case, output, plot=False, petsc={}, options={}) -> dict

`sartor run CASE --output OUTPUT` in this process. case: a case file (YAML)
or a dict of its options (written to OUTPUT/case.yaml). options: options of
`sartor run --help` with underscores for dashes ({"mesh_nx": 8}), which win
over the case's; True gives a flag, False and None leave an option out, a
list is joined with commas. petsc: PETSc options without their dash (None:
a flag). Returns positions, initial_positions, displacement (vertices, 3) m;
triangles (triangles, 3); material_uv (triangles, 3, 2) m; cell_fields and
vertex_fields (dicts of arrays); fabric_ids/names, panel_ids/names; units;
summary (as summary.json); unused_options. Raises InputError for a bad
option or input, SolveFailure (with .result) when the solve fails.)";

} // namespace

PYBIND11_MODULE(_sartor, module) {
  module.doc() = "Sartor's case pipeline and drape in-process (docs/python.md)";
  const py::object base = py::reinterpret_steal<py::object>(PyErr_NewExceptionWithDoc(
      "sartor._sartor.Error", "sartor failed: its message", PyExc_RuntimeError, nullptr));
  module.attr("Error") = base;
  module.attr("InputError") = py::reinterpret_steal<py::object>(PyErr_NewExceptionWithDoc(
      "sartor._sartor.InputError", "a bad option or input (the executable's exit status 2)",
      py::make_tuple(base, py::handle(PyExc_ValueError)).ptr(), nullptr));
  module.attr("SolveFailure") = py::reinterpret_steal<py::object>(PyErr_NewExceptionWithDoc(
      "sartor._sartor.SolveFailure",
      "the solve did not converge (exit status 1); .result holds what it reached", base.ptr(),
      nullptr));

  module.def(
      "run",
      [module](const py::object& case_spec, const std::string& output, bool plot,
               const py::dict& petsc, const py::dict& options) {
        std::string file = py::str(case_spec);
        if (py::isinstance<py::dict>(case_spec)) {
          try {
            file = write_case_file(case_spec.cast<py::dict>(), output);
          } catch (const sartor::InputError& error) {
            return outcome_or_raise(
                module, {std::nullopt, std::string("sartor run: ") + error.what(), "InputError"});
          }
        }
        return outcome_or_raise(module,
                                run_in_process({sartor::run_command, sartor::run_run},
                                               command_words(file, output, plot, petsc, options)));
      },
      run_doc, py::arg("case"), py::arg("output"), py::arg("plot") = false,
      py::arg("petsc") = py::dict(), py::arg("options") = py::dict());
  module.def(
      "drape",
      [module](const std::string& pattern, const std::string& output, bool plot,
               const py::dict& petsc, const py::dict& options) {
        return outcome_or_raise(
            module, run_in_process({sartor::drape_command, sartor::run_drape},
                                   command_words(pattern, output, plot, petsc, options)));
      },
      "drape(pattern, output, plot=False, petsc={}, options={}) -> dict\n\n`sartor drape "
      "PATTERN --output OUTPUT` in this process; arguments and result as for run().",
      py::arg("pattern"), py::arg("output"), py::arg("plot") = false, py::arg("petsc") = py::dict(),
      py::arg("options") = py::dict());
  module.def(
      "set_petsc_options",
      [](const py::dict& petsc) { persistent_petsc_options() = petsc_pairs(petsc); },
      "PETSc options (without their dash; None: a flag) given to every later run and drape, "
      "before the call's own; an empty dict clears them.",
      py::arg("petsc"));
  module.def(
      "petsc_options", [] { return persistent_petsc_options(); },
      "The options of set_petsc_options, as (name, value) pairs.");
}
