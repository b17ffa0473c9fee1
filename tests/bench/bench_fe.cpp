// Finite-element performance benchmark: the static solve of a hanging sheet
// (1 m x 1 m cotton-twill-like cloth in the x-z plane, its two top corners
// pinned, under gravity) on meshes of increasing size. An MPI program; it
// measures and prints, it never fails on time.
//
// Per mesh size it reports triangles, vertices, dofs and ranks; the setup
// time (mesh generation and ClothProblem: DMPlex, distribution, section);
// the wall time of one residual, Jacobian and energy assembly (median of
// --repeat assemblies at the solved state) and its cost per triangle; the
// Newton and linear iterations and the time of solve_static; and the peak
// resident memory summed over the ranks.
//
// Solver (--solver; PETSc options on the command line take precedence):
// hypre (default), CG preconditioned by BoomerAMG; gamg, CG + GAMG with the
// rigid-body near-null space the incremental system attaches; mumps, the
// direct solve (MUMPS LU) for comparisons at small sizes. The sheet hangs in
// its own plane and its planar equilibrium has compressed zones, so the
// Jacobian is indefinite out of plane (the sheet would rather wrinkle): CG +
// GAMG breaks down there (DIVERGED_INDEFINITE_MAT), also with PSD-projected
// membrane Hessians (Newton then stagnates), while BoomerAMG's scalar
// coarsening keeps the out-of-plane block, which the load hardly excites, out
// of the Krylov space.
//
// Line search: basic (full Newton steps) by default. The statics' default
// backtracking on the potential stalls near |F| ~ 1e-6 N on this problem:
// the potential (~1 J, mostly gravity) then changes by less than its
// round-off, and which steps it accepts depends on summation order (rank
// count), so iteration counts would measure noise. From the flat start the
// full Newton steps converge in 3 iterations at every size.
//
// Run: tests/bench/run_fe_benchmark.sh OUTDIR (1 and 2 ranks, CSV and JSON),
// or by hand: mpiexec -n 2 build/tests/bench/sartor-bench-fe --sizes 71,224

#include "fem/cloth_problem.hpp"
#include "fem/petsc_options.hpp"
#include "material/tension_curve.hpp"
#include "mesh/generators.hpp"
#include "solvers/statics.hpp"

#include <nlohmann/json.hpp>
#include <petscsys.h>

#include <algorithm>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <exception>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <unistd.h>

namespace sartor {
namespace {

const char* const usage_text =
    "usage: sartor-bench-fe [--sizes N,N,...] [--repeat R] [--solves K]\n"
    "                       [--solver hypre|gamg|mumps] [--load-steps S] [--project-membrane]\n"
    "                       [--csv FILE] [--json FILE] [PETSc options]\n"
    "\n"
    "Static solve of a 1 m hanging sheet (two top corners pinned, gravity,\n"
    "cotton-twill-like moduli) on an N x N rectangle of 2 N^2 triangles per size.\n"
    "\n"
    "  --sizes N,...   cells per side (default 71,99,224: 1e4, 2e4, 1e5 triangles;\n"
    "                  141, 447, 708 give 4e4, 4e5, 1e6)\n"
    "  --repeat R      assemblies timed per kind (default 5; the median is reported)\n"
    "  --solves K      static solves per size from the flat start (default 1; the\n"
    "                  median time is reported, and the fastest)\n"
    "  --solver NAME   hypre (default): -ksp_type cg -pc_type hypre (BoomerAMG, HMIS\n"
    "                  coarsening, ext+i interpolation, P_max 4, one aggressive level);\n"
    "                  gamg: -ksp_type cg -pc_type gamg (breaks down on this problem:\n"
    "                  its Jacobian is indefinite out of plane); mumps: -ksp_type\n"
    "                  preonly -pc_type lu -pc_factor_mat_solver_type mumps.\n"
    "                  Every solver runs with -snes_linesearch_type basic (full Newton\n"
    "                  steps). PETSc options on the command line take precedence.\n"
    "  --project-membrane  PSD-project the membrane element Hessians\n"
    "  --load-steps S  load steps of solve_static (default 1)\n"
    "  --csv FILE      write one row per size (rank 0)\n"
    "  --json FILE     write the rows and the run's settings (rank 0)\n";

struct Settings {
  std::vector<int> sizes{71, 99, 224};
  int repeat = 5;
  int solves = 1;
  std::string solver = "hypre";
  int load_steps = 1;
  bool project_membrane = false;
  std::string csv;
  std::string json;
  bool help = false;
  std::string error;
};

bool parse_int(const std::string& text, int minimum, int* value) {
  try {
    std::size_t used = 0;
    const long parsed = std::stol(text, &used);
    if (used != text.size() || parsed < minimum || parsed > 1000000) return false;
    *value = int(parsed);
    return true;
  } catch (const std::exception&) {
    return false;
  }
}

// Takes the --options out of argv; the rest goes to PETSc.
Settings parse_arguments(int* argc, char** argv) {
  Settings settings;
  int kept = 1;
  for (int i = 1; i < *argc; ++i) {
    const std::string name = argv[i];
    if (name.rfind("--", 0) != 0) {
      argv[kept++] = argv[i];
      continue;
    }
    if (name == "--help") {
      settings.help = true;
      continue;
    }
    if (name == "--project-membrane") {
      settings.project_membrane = true;
      continue;
    }
    if (i + 1 >= *argc) {
      settings.error = name + " needs a value";
      continue;
    }
    const std::string value = argv[++i];
    if (name == "--sizes") {
      settings.sizes.clear();
      std::stringstream list(value);
      std::string item;
      while (std::getline(list, item, ',')) {
        int n = 0;
        if (!parse_int(item, 1, &n)) {
          settings.error = "--sizes: '" + item + "' is not a positive integer";
          break;
        }
        settings.sizes.push_back(n);
      }
      if (settings.sizes.empty() && settings.error.empty()) settings.error = "--sizes is empty";
    } else if (name == "--repeat") {
      if (!parse_int(value, 1, &settings.repeat)) settings.error = "--repeat must be >= 1";
    } else if (name == "--load-steps") {
      if (!parse_int(value, 1, &settings.load_steps)) settings.error = "--load-steps must be >= 1";
    } else if (name == "--solver") {
      settings.solver = value;
      if (value != "hypre" && value != "gamg" && value != "mumps")
        settings.error = "--solver must be hypre, gamg or mumps";
    } else if (name == "--solves") {
      if (!parse_int(value, 1, &settings.solves)) settings.error = "--solves must be >= 1";
    } else if (name == "--csv") {
      settings.csv = value;
    } else if (name == "--json") {
      settings.json = value;
    } else {
      settings.error = "unknown option " + name;
    }
  }
  *argc = kept;
  argv[kept] = nullptr;
  return settings;
}

std::string option_value(const char* name) {
  char value[256] = "";
  PetscBool found = PETSC_FALSE;
  if (PetscOptionsGetString(nullptr, nullptr, name, value, sizeof value, &found) != 0 || !found)
    return "";
  return value;
}

// Resident memory of this process from /proc/self/status, bytes (0 if unknown).
double status_bytes(const char* field) {
  std::ifstream status("/proc/self/status");
  std::string line;
  const std::size_t length = std::strlen(field);
  while (std::getline(status, line)) {
    if (line.compare(0, length, field) == 0 && line.size() > length && line[length] == ':') {
      return 1024.0 * std::atof(line.c_str() + length + 1); // "VmHWM:   1234 kB"
    }
  }
  return 0.0;
}

// Resets the peak resident size (VmHWM) to the current one; false where the
// kernel does not allow it (the peak is then the process's lifetime peak).
bool reset_peak_memory() {
  std::ofstream clear("/proc/self/clear_refs");
  if (!clear) return false;
  clear << "5";
  clear.flush();
  return bool(clear);
}

double now(MPI_Comm comm) {
  MPI_Barrier(comm);
  return MPI_Wtime();
}

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

void progress(MPI_Comm comm, const char* format, ...) __attribute__((format(printf, 2, 3)));
void progress(MPI_Comm comm, const char* format, ...) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  if (rank != 0) return;
  va_list arguments;
  va_start(arguments, format);
  std::vprintf(format, arguments);
  va_end(arguments);
  std::fflush(stdout);
}

struct Row {
  int n = 0;
  long triangles = 0, vertices = 0, dofs = 0;
  int ranks = 1;
  double mesh_s = 0, problem_s = 0, setup_s = 0;
  double preallocation_s = 0, residual_s = 0, jacobian_s = 0, energy_s = 0;
  long newton_iterations = 0, linear_iterations = 0;
  bool converged = false;
  std::string reason;
  double solve_s = 0, solve_min_s = 0, initial_residual = 0, final_residual = 0, sag_m = 0;
  double peak_bytes = 0, baseline_bytes = 0, max_rank_peak_bytes = 0;
  bool peak_reset = false;

  // Core time per triangle: wall time x ranks / triangles.
  double per_triangle_ns(double seconds) const {
    return 1e9 * seconds * double(ranks) / double(triangles);
  }
  double bytes_per_vertex() const { return (peak_bytes - baseline_bytes) / double(vertices); }
};

const char* const csv_header =
    "n,triangles,vertices,dofs,ranks,solver,mesh_s,problem_s,setup_s,preallocation_s,"
    "residual_s,jacobian_s,energy_s,residual_ns_per_triangle,jacobian_ns_per_triangle,"
    "energy_ns_per_triangle,newton_iterations,linear_iterations,converged,solve_s,solve_min_s,"
    "initial_residual_N,final_residual_N,sag_m,peak_rss_MiB,baseline_rss_MiB,"
    "max_rank_peak_rss_MiB,bytes_per_vertex";

std::string csv_row(const Row& r, const std::string& solver) {
  constexpr double mib = 1024.0 * 1024.0;
  char line[1024];
  std::snprintf(line, sizeof line,
                "%d,%ld,%ld,%ld,%d,%s,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%ld,%ld,"
                "%d,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g",
                r.n, r.triangles, r.vertices, r.dofs, r.ranks, solver.c_str(), r.mesh_s,
                r.problem_s, r.setup_s, r.preallocation_s, r.residual_s, r.jacobian_s, r.energy_s,
                r.per_triangle_ns(r.residual_s), r.per_triangle_ns(r.jacobian_s),
                r.per_triangle_ns(r.energy_s), r.newton_iterations, r.linear_iterations,
                r.converged ? 1 : 0, r.solve_s, r.solve_min_s, r.initial_residual, r.final_residual,
                r.sag_m, r.peak_bytes / mib, r.baseline_bytes / mib, r.max_rank_peak_bytes / mib,
                r.bytes_per_vertex());
  return line;
}

nlohmann::json json_row(const Row& r) {
  constexpr double mib = 1024.0 * 1024.0;
  return {{"n", r.n},
          {"triangles", r.triangles},
          {"vertices", r.vertices},
          {"dofs", r.dofs},
          {"ranks", r.ranks},
          {"setup_s", {{"mesh", r.mesh_s}, {"problem", r.problem_s}, {"total", r.setup_s}}},
          {"assembly",
           {{"preallocation_s", r.preallocation_s},
            {"residual_s", r.residual_s},
            {"jacobian_s", r.jacobian_s},
            {"energy_s", r.energy_s},
            {"residual_ns_per_triangle", r.per_triangle_ns(r.residual_s)},
            {"jacobian_ns_per_triangle", r.per_triangle_ns(r.jacobian_s)},
            {"energy_ns_per_triangle", r.per_triangle_ns(r.energy_s)}}},
          {"solve",
           {{"converged", r.converged},
            {"reason", r.reason},
            {"newton_iterations", r.newton_iterations},
            {"linear_iterations", r.linear_iterations},
            {"seconds", r.solve_s},
            {"fastest_seconds", r.solve_min_s},
            {"initial_residual_N", r.initial_residual},
            {"final_residual_N", r.final_residual},
            {"sag_m", r.sag_m}}},
          {"memory",
           {{"peak_rss_MiB", r.peak_bytes / mib},
            {"baseline_rss_MiB", r.baseline_bytes / mib},
            {"max_rank_peak_rss_MiB", r.max_rank_peak_bytes / mib},
            {"bytes_per_vertex", r.bytes_per_vertex()},
            {"peak_reset_per_size", r.peak_reset}}}};
}

ClothMaterial cotton_twill(bool project_membrane) {
  ClothMaterial material({TensionCurve::linear(65200, "benchmark warp"),
                          TensionCurve::linear(28200, "benchmark weft"), 4288.0, 0.0});
  // The discrete shell, as the tables of docs/finite-elements.md were
  // measured (the patch model's cost per Jacobian is given beside them).
  material.bending_model = element::BendingModel::discrete_shell;
  material.bending_stiffness = 1e-5;
  material.areal_density = 0.2;
  material.project_membrane = project_membrane;
  return material;
}

// The vertex nearest to `target`.
int nearest_vertex(const TriangleMesh& mesh, const Eigen::Vector3d& target) {
  std::size_t best = 0;
  for (std::size_t v = 1; v < mesh.vertex_count(); ++v) {
    if ((mesh.positions[v] - target).squaredNorm() < (mesh.positions[best] - target).squaredNorm())
      best = v;
  }
  return int(best);
}

// Times `repeat` calls of `assemble` (collective), returns the median, s.
template <typename Assemble>
PetscErrorCode time_assembly(MPI_Comm comm, int repeat, const Assemble& assemble, double* seconds) {
  std::vector<double> times;
  PetscFunctionBeginUser;
  PetscCall(assemble()); // warm-up: first touch of the matrix and vector memory
  for (int k = 0; k < repeat; ++k) {
    const double start = now(comm);
    PetscCall(assemble());
    times.push_back(now(comm) - start);
  }
  *seconds = median(times);
  PetscFunctionReturn(0);
}

PetscErrorCode run_size(MPI_Comm comm, const Settings& settings, int n, Row* row) {
  PetscMPIInt ranks = 1;
  PetscFunctionBeginUser;
  MPI_Comm_size(comm, &ranks);
  row->n = n;
  row->ranks = ranks;
  row->peak_reset = reset_peak_memory();
  double baseline = status_bytes("VmRSS");

  // Setup: the serial mesh on every rank, then the distributed problem.
  double start = now(comm);
  TriangleMesh mesh = mesh::rectangle(1.0, 1.0, n, n);
  for (auto& p : mesh.positions)
    p = Eigen::Vector3d(p[0], 0.0, p[1]); // hang in the x-z plane, weft up
  const std::vector<int> pins = {nearest_vertex(mesh, {0, 0, 1}), nearest_vertex(mesh, {1, 0, 1})};
  row->mesh_s = now(comm) - start;
  row->triangles = long(mesh.triangle_count());
  row->vertices = long(mesh.vertex_count());
  progress(comm, "n = %d: %ld triangles, %ld vertices, %d rank(s)\n", n, row->triangles,
           row->vertices, ranks);
  progress(comm, "  mesh      %9.3f s\n", row->mesh_s);

  start = now(comm);
  ClothProblem problem(comm, mesh, cotton_twill(settings.project_membrane), pins);
  problem.loads.gravity = {0.0, 0.0, -9.80665};
  Vec x = nullptr;
  PetscCall(problem.create_solution(&x));
  row->problem_s = now(comm) - start;
  row->setup_s = row->mesh_s + row->problem_s;
  row->dofs = long(problem.global_dof_count());
  progress(comm, "  problem   %9.3f s  (%ld dofs)\n", row->problem_s, row->dofs);

  // The static solve from the flat, unstressed placement, --solves times.
  StaticOptions options;
  options.load_steps = settings.load_steps;
  StaticReport report;
  std::vector<double> solve_times;
  for (int k = 0; k < settings.solves; ++k) {
    if (k > 0) {
      PetscCall(VecDestroy(&x));
      PetscCall(problem.create_solution(&x));
    }
    report = StaticReport();
    start = now(comm);
    PetscCall(solve_static(problem, x, options, &report));
    solve_times.push_back(now(comm) - start);
  }
  row->solve_s = median(solve_times);
  row->solve_min_s = *std::min_element(solve_times.begin(), solve_times.end());
  row->converged = report.converged;
  row->reason = report.reason;
  row->newton_iterations = long(report.newton_iterations);
  row->linear_iterations = long(report.linear_iterations);
  row->initial_residual = report.initial_residual_norm;
  row->final_residual = report.final_residual_norm;
  // Sag: the lowest point of the sheet below its rest bottom edge (z = 0).
  {
    const PetscScalar* values = nullptr;
    PetscInt size = 0;
    double lowest = 0.0;
    PetscCall(VecGetLocalSize(x, &size));
    PetscCall(VecGetArrayRead(x, &values));
    for (PetscInt i = 2; i < size; i += 3)
      lowest = std::min(lowest, double(values[i]));
    PetscCall(VecRestoreArrayRead(x, &values));
    double global_lowest = 0.0;
    MPI_Allreduce(&lowest, &global_lowest, 1, MPI_DOUBLE, MPI_MIN, comm);
    row->sag_m = -global_lowest;
  }
  progress(comm,
           "  solve     %9.3f s  (fastest of %d: %.3f s; %s, %ld Newton, %ld linear iterations, "
           "|F| %.3g -> %.3g N)\n",
           row->solve_s, settings.solves, row->solve_min_s, row->reason.c_str(),
           row->newton_iterations, row->linear_iterations, row->initial_residual,
           row->final_residual);

  // Assembly at the solved (stressed) state.
  Vec f = nullptr;
  Mat J = nullptr;
  PetscCall(VecDuplicate(x, &f));
  start = now(comm);
  PetscCall(problem.create_jacobian(&J));
  row->preallocation_s = now(comm) - start;
  PetscCall(time_assembly(
      comm, settings.repeat, [&] { return problem.residual(x, f); }, &row->residual_s));
  PetscCall(time_assembly(
      comm, settings.repeat, [&] { return problem.jacobian(x, J); }, &row->jacobian_s));
  ClothEnergy energy;
  PetscCall(time_assembly(
      comm, settings.repeat, [&] { return problem.energy(x, &energy); }, &row->energy_s));
  progress(comm,
           "  assembly  residual %.4g s (%.0f ns/triangle), Jacobian %.4g s (%.0f ns/triangle), "
           "energy %.4g s (%.0f ns/triangle); preallocation %.3g s\n",
           row->residual_s, row->per_triangle_ns(row->residual_s), row->jacobian_s,
           row->per_triangle_ns(row->jacobian_s), row->energy_s,
           row->per_triangle_ns(row->energy_s), row->preallocation_s);

  double local[2] = {status_bytes("VmHWM"), baseline}, sums[2] = {0, 0};
  MPI_Allreduce(local, sums, 2, MPI_DOUBLE, MPI_SUM, comm);
  MPI_Allreduce(local, &row->max_rank_peak_bytes, 1, MPI_DOUBLE, MPI_MAX, comm);
  row->peak_bytes = sums[0];
  row->baseline_bytes = sums[1];
  progress(
      comm, "  memory    %.1f MiB peak over %d rank(s) (%.1f MiB at start): %.0f bytes/vertex\n",
      row->peak_bytes / 1048576.0, ranks, row->baseline_bytes / 1048576.0, row->bytes_per_vertex());

  PetscCall(MatDestroy(&J));
  PetscCall(VecDestroy(&f));
  PetscCall(VecDestroy(&x));
  PetscFunctionReturn(0);
}

std::string petsc_options() {
  char* all = nullptr;
  if (PetscOptionsGetAll(nullptr, &all) != 0 || !all) return "";
  std::string text = all;
  PetscFree(all);
  return text;
}

std::string timestamp() {
  const std::time_t t = std::time(nullptr);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&t));
  return text;
}

int run(int argc, char** argv) {
  Settings settings = parse_arguments(&argc, argv);
  if (PetscInitialize(&argc, &argv, nullptr, nullptr) != 0) return 1;
  MPI_Comm comm = PETSC_COMM_WORLD;
  PetscMPIInt rank = 0, ranks = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &ranks);
  if (settings.help || !settings.error.empty()) {
    if (rank == 0) {
      if (!settings.error.empty())
        std::fprintf(stderr, "sartor-bench-fe: %s\n", settings.error.c_str());
      std::fputs(usage_text, settings.help ? stdout : stderr);
    }
    PetscFinalize();
    return settings.help ? 0 : 2;
  }
  int status = 0;
  // Full Newton steps: see "Line search" at the top of this file.
  status |= set_default_option("-snes_linesearch_type", "basic");
  if (settings.solver == "hypre") {
    status |= set_default_option("-ksp_type", "cg");
    status |= set_default_option("-pc_type", "hypre");
    if (option_value("-pc_type") == "hypre") {
      status |= set_default_option("-pc_hypre_type", "boomeramg");
      status |= set_default_option("-pc_hypre_boomeramg_coarsen_type", "HMIS");
      status |= set_default_option("-pc_hypre_boomeramg_interp_type", "ext+i");
      status |= set_default_option("-pc_hypre_boomeramg_P_max", "4");
      status |= set_default_option("-pc_hypre_boomeramg_agg_nl", "1");
    }
  } else if (settings.solver == "gamg") {
    status |= set_default_option("-ksp_type", "cg");
    status |= set_default_option("-pc_type", "gamg");
  } else {
    status |= set_default_option("-ksp_type", "preonly");
    status |= set_default_option("-pc_type", "lu");
    status |= set_default_option("-pc_factor_mat_solver_type", "mumps");
  }
  std::string solver = option_value("-ksp_type") + "+" + option_value("-pc_type");
  if (!option_value("-pc_factor_mat_solver_type").empty() && option_value("-pc_type") == "lu")
    solver += "+" + option_value("-pc_factor_mat_solver_type");
  char host[256] = "";
  gethostname(host, sizeof host - 1);
  progress(comm,
           "sartor-bench-fe: hanging sheet, %d rank(s) on %s (%u hardware threads), solver %s\n",
           ranks, host, std::thread::hardware_concurrency(), solver.c_str());

  std::vector<Row> rows;
  for (int n : settings.sizes) {
    try {
      Row row;
      if (run_size(comm, settings, n, &row) != 0) {
        status = 1;
        break;
      }
      rows.push_back(row);
    } catch (const std::exception& error) {
      std::fprintf(stderr, "sartor-bench-fe: rank %d: n = %d: %s\n", rank, n, error.what());
      MPI_Abort(comm, 1);
    }
  }

  if (rank == 0 && !settings.csv.empty()) {
    std::ofstream csv(settings.csv);
    csv << csv_header << '\n';
    for (const Row& row : rows)
      csv << csv_row(row, solver) << '\n';
    if (!csv) {
      std::fprintf(stderr, "sartor-bench-fe: %s: cannot write\n", settings.csv.c_str());
      status = 1;
    }
  }
  if (rank == 0 && !settings.json.empty()) {
    nlohmann::json document = {
        {"benchmark", "hanging sheet static solve"},
        {"sartor_version", SARTOR_VERSION},
        {"date", timestamp()},
        {"host", host},
        {"hardware_threads", std::thread::hardware_concurrency()},
        {"ranks", ranks},
        {"solver", solver},
        {"petsc_version",
         PETSC_VERSION_MAJOR * 10000 + PETSC_VERSION_MINOR * 100 + PETSC_VERSION_SUBMINOR},
        {"petsc_options", petsc_options()},
        {"load_steps", settings.load_steps},
        {"assembly_repeats", settings.repeat},
        {"solves", settings.solves},
        {"problem",
         {{"sheet_m", 1.0},
          {"warp_modulus_N_per_m", 65200},
          {"weft_modulus_N_per_m", 28200},
          {"shear_modulus_N_per_m", 4288},
          {"areal_density_kg_per_m2", 0.2},
          {"bending_stiffness_N_m", 1e-5},
          {"gravity_m_per_s2", 9.80665}}},
        {"rows", nlohmann::json::array()}};
    for (const Row& row : rows)
      document["rows"].push_back(json_row(row));
    std::ofstream json(settings.json);
    json << document.dump(2) << '\n';
    if (!json) {
      std::fprintf(stderr, "sartor-bench-fe: %s: cannot write\n", settings.json.c_str());
      status = 1;
    }
  }
  const int finalized = PetscFinalize();
  return status != 0 || finalized != 0 ? 1 : 0;
}

} // namespace
} // namespace sartor

int main(int argc, char** argv) {
  return sartor::run(argc, argv);
}
