// sartor converge: a mesh-refinement study of a static cloth case.

#include "analysis/convergence.hpp"
#include "app/cloth_case.hpp"
#include "app/commands.hpp"
#include "app/log_stage.hpp"
#include "app/refine_levels.hpp"
#include "common/csv.hpp"
#include "common/error.hpp"
#include "common/output.hpp"
#include "fem/petsc_call.hpp"

#include <nlohmann/json.hpp>
#include <petscsys.h>

#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <limits>
#include <optional>
#include <sstream>

namespace sartor {

const CommandSpec& converge_command() {
  static const CommandSpec spec{
      "converge",
      "mesh-refinement study of a cloth case: errors and observed orders",
      "sartor converge CASE.yaml --levels N [--quantity Q] [--reference VALUE] [options]",
      "Solves the case of `sartor run` on N meshes, each a uniform refinement of the\n"
      "one before (--mesh-refine base, base+1, ..., base+N-1; every triangle split\n"
      "in four, so the mesh size h halves), and measures one quantity on each:\n"
      "  probe_z     z displacement of the --probe vertex, m (default)\n"
      "  probe_norm  length of the --probe vertex's displacement, m\n"
      "  energy      total energy (membrane + bending + gravity/point-force\n"
      "              potential; pressure does no counted work), J\n"
      "h is the longest triangle edge in material (u, v) coordinates.\n\n"
      "With --reference (an exact value), the error of each level is |q - reference|\n"
      "and the observed order between consecutive levels is\n"
      "  p = log(e_k / e_k+1) / log(h_k / h_k+1).\n"
      "Without it, each three consecutive levels give the self-convergence order\n"
      "  p = log(|q1 - q0| / |q2 - q1|) / log(h0 / h1),\n"
      "a Richardson-extrapolated estimate q2 + (q2 - q1) / ((h1/h2)^p - 1) and\n"
      "Roache's grid convergence index; the error column is then the change from\n"
      "the previous level. A least-squares slope of log(error) against log(h) is\n"
      "reported in both cases.\n\n"
      "Output in DIR: convergence.csv (level,h,triangles,dofs,value,error,\n"
      "newton_iterations,solve_time_s), convergence.json (rows, orders, fit,\n"
      "extrapolation, options), convergence.png (postproc/plot_converge.py),\n"
      "level_K/ (what `sartor run` writes, per level), petsc_options.txt. Both data\n"
      "files are rewritten after every level, so a long study can be watched.\n"
      "A case file's `output:` applies here too: give --output to keep the study\n"
      "apart from the case's `sartor run` results.\n\n"
      "examples:\n"
      "  sartor converge cases/fe/hencky.yaml --levels 4 --output out/hencky-conv\n"
      "  sartor converge cases/fe/hencky.yaml --levels 4 --mesh-rings 4 \\\n"
      "      --reference 0.0205821756 --output out/hencky-conv",
      [] {
        std::vector<OptionSpec> options = case_option_specs();
        options.push_back({"levels", "N", "3", "number of meshes (refinement levels), 1..12"});
        options.push_back(
            {"quantity", "Q", "probe_z", "what converges: probe_z, probe_norm or energy"});
        options.push_back(
            {"reference", "VALUE", "", "exact value of the quantity (m or J) [self-convergence]"});
        options.push_back(
            {"output", "DIR", "out/converge", "output folder (created; files in it are replaced)"});
        options.push_back({"no-plot", "", "", "write data only, no PNG"});
        options.push_back({"prolong", "", "",
                           "statics: start each level from the level before, its solution "
                           "carried to the finer mesh (new vertices at the solved edges' "
                           "midpoints), instead of from the case's placement"});
        return options;
      }(),
      1,
      true};
  return spec;
}

namespace {

struct Quantity {
  std::string name;
  std::string unit;
  std::string description;
};

Quantity parse_quantity(const Options& options) {
  const std::string name = options.text("quantity");
  if (name == "probe_z") return {name, "m", "z displacement of the probe vertex"};
  if (name == "probe_norm") return {name, "m", "length of the probe vertex's displacement"};
  if (name == "energy") {
    return {name, "J", "total energy (membrane + bending + external potential)"};
  }
  throw InputError("option --quantity: unknown quantity '" + name +
                   "' (probe_z, probe_norm, energy)");
}

double measure(const Quantity& quantity, const CaseResult& result) {
  if (quantity.name == "energy") return result.energy.total();
  if (quantity.name == "probe_z") return result.probe->displacement.z();
  return result.probe->displacement.norm();
}

struct Level {
  int level = 0;
  std::string directory;
  CaseResult result; // positions and strains dropped once written
  double value = 0.0;
};

// "nan" for what is undefined, else the shortest exact text.
std::string csv_number(double value) {
  return std::isfinite(value) ? format_number(value) : "nan";
}

// null for what is undefined.
nlohmann::json json_number(double value) {
  return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(nullptr);
}

std::string convergence_csv(const std::vector<Level>& levels, const ConvergenceAnalysis& analysis) {
  std::ostringstream out;
  out << "level,h,triangles,dofs,value,error,newton_iterations,solve_time_s\n";
  for (std::size_t k = 0; k < levels.size(); ++k) {
    const CaseResult& r = levels[k].result;
    out << levels[k].level << ',' << csv_number(r.h) << ',' << r.mesh.triangle_count() << ','
        << r.dofs << ',' << csv_number(levels[k].value) << ',' << csv_number(analysis.error[k])
        << ',' << r.report.newton_iterations << ',' << csv_number(r.solve_seconds) << '\n';
  }
  return out.str();
}

nlohmann::json convergence_json(nlohmann::json report, const std::vector<Level>& levels,
                                const ConvergenceAnalysis& analysis, bool complete) {
  report["complete"] = complete;
  report["rows"] = nlohmann::json::array();
  for (std::size_t k = 0; k < levels.size(); ++k) {
    const CaseResult& r = levels[k].result;
    const double relative = analysis.reference && *analysis.reference != 0.0
                                ? analysis.error[k] / std::abs(*analysis.reference)
                                : std::numeric_limits<double>::quiet_NaN();
    report["rows"].push_back({{"level", levels[k].level},
                              {"mesh_refine", r.mesh_refine},
                              {"h", r.h},
                              {"vertices", r.mesh.vertex_count()},
                              {"triangles", r.mesh.triangle_count()},
                              {"dofs", r.dofs},
                              {"value", levels[k].value},
                              {"error", json_number(analysis.error[k])},
                              {"relative_error", json_number(relative)},
                              {"converged", r.converged},
                              {"newton_iterations", r.report.newton_iterations},
                              {"linear_iterations", r.report.linear_iterations},
                              {"load_steps", r.report.steps.size()},
                              {"final_residual_norm", r.report.final_residual_norm},
                              {"setup_time_s", r.setup_seconds},
                              {"solve_time_s", r.solve_seconds},
                              {"total_time_s", r.total_seconds},
                              {"directory", levels[k].directory}});
  }
  report["orders"] = nlohmann::json::array();
  for (const auto& pair : analysis.pairs) {
    const auto k = std::size_t(pair.from);
    report["orders"].push_back({{"levels", {pair.from, pair.from + 1}},
                                {"h_ratio", levels[k].result.h / levels[k + 1].result.h},
                                {"order", json_number(pair.order)}});
  }
  report["self_convergence"] = nlohmann::json::array();
  for (const auto& triplet : analysis.triplets) {
    report["self_convergence"].push_back(
        {{"levels", {triplet.from, triplet.from + 1, triplet.from + 2}},
         {"monotone", triplet.monotone},
         {"order", json_number(triplet.order)},
         {"richardson_estimate", json_number(triplet.extrapolated)},
         {"gci_fine", json_number(triplet.gci)}});
  }
  report["fit"] = {{"order", json_number(analysis.fitted_order)},
                   {"constant", json_number(analysis.fitted_constant)},
                   {"points", analysis.fitted_points}};
  return report;
}

void print(const char* format, ...) __attribute__((format(printf, 1, 2)));
void print(const char* format, ...) {
  if (!is_root()) return;
  va_list arguments;
  va_start(arguments, format);
  std::vprintf(format, arguments);
  va_end(arguments);
  std::fflush(stdout);
}

std::string order_text(double order) {
  if (!std::isfinite(order)) return "-";
  char text[32];
  std::snprintf(text, sizeof text, "%.3f", order);
  return text;
}

// convergence.json's header: the case, the quantity, the reference and the levels.
nlohmann::json convergence_report(const Invocation& invocation, const std::string& case_file,
                                  const Quantity& quantity, const std::optional<double>& reference,
                                  long base, long level_count) {
  nlohmann::json report = run_metadata(invocation, "converge");
  report["case"] = case_file;
  report["quantity"] = {
      {"name", quantity.name}, {"unit", quantity.unit}, {"description", quantity.description}};
  report["reference"] = reference ? nlohmann::json(*reference) : nlohmann::json(nullptr);
  report["error_kind"] = reference ? "absolute difference from the reference"
                                   : "absolute change from the previous level";
  report["base_mesh_refine"] = base;
  report["levels"] = level_count;
  report["warnings"] = nlohmann::json::array();
  return report;
}

// The level's results in its directory; its positions and strains dropped
// once written.
void write_level(const Invocation& invocation, const std::string& case_file, Level& level) {
  CaseResult& r = level.result;
  nlohmann::json summary = run_metadata(invocation, "converge");
  summary["case"] = case_file;
  summary["level"] = level.level;
  summary["mesh_refine"] = r.mesh_refine;
  summary["h"] = r.h;
  add_case_summary(r, summary);
  write_case_results(level.directory, r, summary);
  r.positions.clear();
  r.strains.clear();
}

// The rest of the table's row of the level just solved (the last of `levels`).
void print_level_row(const std::vector<Level>& levels, const ConvergenceAnalysis& analysis,
                     const std::optional<double>& reference) {
  const int k = levels.back().level;
  const CaseResult& done = levels.back().result;
  double order = std::numeric_limits<double>::quiet_NaN();
  if (reference && k > 0) order = analysis.pairs.back().order;
  if (!reference && k > 1) order = analysis.triplets.back().order;
  const double error = analysis.error.back();
  char error_text[32] = "-";
  if (std::isfinite(error)) std::snprintf(error_text, sizeof error_text, "%.4g", error);
  char relative[32] = "";
  if (reference && *reference != 0.0) {
    std::snprintf(relative, sizeof relative, "%.3e", error / std::abs(*reference));
  }
  print(" %11.5g %9zu %8ld %15.9g %11s %9s %7s %6ld %9.3g%s\n", done.h, done.mesh.triangle_count(),
        long(done.dofs), levels.back().value, error_text, relative, order_text(order).c_str(),
        long(done.report.newton_iterations), done.solve_seconds,
        done.converged ? "" : "  NOT CONVERGED");
}

// The observed orders, the self-convergence of each triplet and the fitted order.
void print_orders(const ConvergenceAnalysis& analysis, const std::optional<double>& reference,
                  const Quantity& quantity) {
  if (reference) {
    for (const auto& pair : analysis.pairs) {
      print("  observed order, levels %d-%d: %s\n", pair.from, pair.from + 1,
            order_text(pair.order).c_str());
    }
  }
  for (const auto& triplet : analysis.triplets) {
    if (triplet.monotone) {
      print("  self-convergence, levels %d-%d-%d: order %s, Richardson estimate %.9g %s, GCI "
            "%.2e\n",
            triplet.from, triplet.from + 1, triplet.from + 2, order_text(triplet.order).c_str(),
            triplet.extrapolated, quantity.unit.c_str(), triplet.gci);
    } else {
      print("  self-convergence, levels %d-%d-%d: not monotone (no order, no extrapolation)\n",
            triplet.from, triplet.from + 1, triplet.from + 2);
    }
  }
  if (analysis.fitted_points >= 2) {
    print("  least-squares order over %d level(s): %s\n", analysis.fitted_points,
          order_text(analysis.fitted_order).c_str());
  }
}

} // namespace

int run_converge(const Invocation& invocation) {
  const Options& options = invocation.options;
  const std::string case_file = invocation.command_line.positionals.at(0);
  const long level_count = options.integer("levels");
  if (level_count < 1 || level_count > 12) {
    throw InputError("option --levels: must lie in 1..12, got " + options.text("levels"));
  }
  const Quantity quantity = parse_quantity(options);
  if (quantity.name != "energy" && !options.is_set("probe")) {
    throw InputError("--quantity " + quantity.name +
                     " needs --probe X,Y,Z (the point whose displacement converges)");
  }
  std::optional<double> reference;
  if (options.is_set("reference")) reference = options.real("reference");
  const bool plot = !options.flag("no-plot");
  const std::string directory = options.text("output");
  const long base = options.integer("mesh-refine");

  nlohmann::json report =
      convergence_report(invocation, case_file, quantity, reference, base, level_count);
  if (is_root()) make_output_directory(directory);

  print("sartor converge: %s, %ld level(s) (mesh_refine %ld..%ld), quantity %s (%s)%s\n",
        case_file.c_str(), level_count, base, base + level_count - 1, quantity.name.c_str(),
        quantity.unit.c_str(), reference ? "" : ", no reference: self-convergence");
  if (reference) print("  reference %.10g %s\n", *reference, quantity.unit.c_str());
  print("%5s %6s %11s %9s %8s %15s %11s %9s %7s %6s %9s\n", "level", "refine", "h (m)", "triangles",
        "dofs", quantity.name.c_str(), reference ? "error" : "change", reference ? "rel.err" : "",
        "order", "Newton", "solve (s)");

  const ClothCase cloth_case = read_cloth_case(options);
  const bool prolong = options.flag("prolong");
  if (prolong && cloth_case.time.analysis != "static") {
    throw InputError("option --prolong: starts static levels from the level before; --analysis " +
                     cloth_case.time.analysis + " starts each from the placement");
  }
  report["start"] = prolong ? "prolonged" : "placement";
  std::vector<Level> levels;
  std::vector<double> h, values;
  std::vector<Eigen::Vector3d> start; // with --prolong: the next level's
  bool warned = false;
  for (int k = 0; k < int(level_count); ++k) {
    Level level;
    level.level = k;
    level.directory = directory + "/level_" + std::to_string(k);
    print("%5d %6ld", k, base + k); // the rest of the row once the level is solved
    try {
      const LogStage stage("Converge level " + std::to_string(k));
      level.result = start.empty()
                         ? solve_case(cloth_case, k)
                         : solve_case(finer_level_case(cloth_case), k, {}, {}, nullptr, &start);
      // The next level's start, before this level's positions are dropped.
      double deepest = 0.0;
      if (prolong && k + 1 < int(level_count))
        start = prolonged_start(cloth_case, level.result, k + 1, &deepest);
    } catch (...) {
      print("\n");
      throw;
    }
    const CaseResult& r = level.result;
    level.value = measure(quantity, r);
    if (k > 0 && !(r.h < levels.back().result.h)) {
      print("\n");
      throw InputError("level " + std::to_string(k) +
                       ": the mesh size did not decrease (h = " + format_number(r.h) + " m)");
    }
    write_level(invocation, case_file, level);

    if (r.probe && k > 0 &&
        (r.probe->initial_position - levels.front().result.probe->initial_position).norm() >
            1e-12 * levels.front().result.h) {
      const std::string warning =
          "the probe vertex at level " + std::to_string(k) +
          " is not the one of level 0 (the --probe point is not a vertex of the coarsest "
          "mesh), so the probe values are not of one point";
      report["warnings"].push_back(warning);
    }

    h.push_back(r.h);
    values.push_back(level.value);
    levels.push_back(std::move(level));
    const ConvergenceAnalysis analysis = analyse_convergence(h, values, reference);
    const CaseResult& done = levels.back().result;
    print_level_row(levels, analysis, reference);
    if (report["warnings"].size() == 1 && !warned) {
      print("  warning: %s\n", report["warnings"][0].get<std::string>().c_str());
      warned = true;
    }

    const bool complete = k + 1 == int(level_count) && done.converged;
    if (is_root()) {
      write_file_atomically(directory + "/convergence.csv", convergence_csv(levels, analysis));
      write_json(directory + "/convergence.json",
                 convergence_json(report, levels, analysis, complete));
    }
    if (!done.converged) {
      write_petsc_options(directory, options);
      throw SolveFailure(
          "level " + std::to_string(k) + " (mesh_refine " + std::to_string(done.mesh_refine) +
          "): the static solve did not converge (" + done.report.reason + " at load factor " +
          format_number(done.load_factor) + "); " + directory +
          " holds the levels so far (convergence.json: \"complete\": false). Try more "
          "--load-steps or -snes_monitor");
    }
  }
  write_petsc_options(directory, options);
  print_orders(analyse_convergence(h, values, reference), reference, quantity);
  if (plot) make_plot("plot_converge.py", directory);
  print("sartor converge: wrote %s\n", directory.c_str());
  return 0;
}

} // namespace sartor
