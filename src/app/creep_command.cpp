// sartor creep: the non-elastic stretch of a fabric strip under a load history.

#include "app/case_checks.hpp"
#include "app/commands.hpp"
#include "common/csv.hpp"
#include "common/error.hpp"
#include "common/output.hpp"
#include "fem/petsc_call.hpp"
#include "material/strip_creep.hpp"

#include <nlohmann/json.hpp>
#include <petscsys.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <sstream>

namespace sartor {

const CommandSpec& creep_command() {
  static const CommandSpec spec{
      "creep",
      "creep and recovery of a fabric strip under a load history",
      "sartor creep [--fabric SPEC] [load options] [--output DIR]",
      "Integrates the modified Kelvin creep law (thesis eqs. 5.7, 5.8) exactly over a\n"
      "piecewise-linear tension history and writes, per fabric direction, the total\n"
      "strain and its immediate-elastic, viscoelastic and permanent parts.\n\n"
      "The default is the thesis' constant-force test (20 kgf on an 8 cm wide strip,\n"
      "1 h loading, 1 h recovery) for all ten Table 5.1 parameter sets, plotted in\n"
      "the style of thesis Fig. 5.9.\n\n"
      "Output in DIR: summary.json, creep.csv (one run) or creep_FABRIC_DIR.csv\n"
      "(several runs), creep.png. Formats: docs/formats.md.\n\n"
      "examples:\n"
      "  sartor creep\n"
      "  sartor creep --fabric denim:weft --force 50 --width 0.05 --load-duration 600\n"
      "  sartor creep --fabric my_fabric.yaml --tension-history history.csv",
      {
          {"fabric", "SPEC", "all",
           "preset (cotton_twill), preset:direction (silk:weft), all, or FILE.yaml[:dir]"},
          {"force", "N", "196.133", "constant test force (20 kgf)"},
          {"width", "M", "0.08", "strip width, m"},
          {"tension", "N/M", "", "test tension per unit width, N/m (instead of force/width)"},
          {"load-duration", "S", "3600", "loading time of the constant-force test, s"},
          {"recovery-duration", "S", "3600", "recovery time after the load is removed, s"},
          {"tension-history", "FILE", "",
           "piecewise-linear tension history, CSV time_s,tension_N_per_m (replaces the test)"},
          {"elastic-modulus", "N/M", "", "linear immediate-elastic modulus for every fabric, N/m"},
          {"sample-interval", "S", "", "write a row every S seconds (default: log-spaced rows)"},
          {"samples-per-decade", "N", "50", "log-spaced rows per decade of time after each change"},
          {"first-sample", "S", "0.01", "first log-spaced row, s after each change"},
          {"output", "DIR", "out/creep", "output folder (created; files in it are replaced)"},
          {"no-plot", "", "", "write data only, no PNG"},
      },
      0};
  return spec;
}

namespace {

// A strain past the range of doubles (a tension of 1e300 N/m, a modulus of
// 1e-300) would be written as inf: said instead, with the values that did it.
void reject_overflow(const std::vector<StripState>& rows, const std::string& label) {
  for (const StripState& r : rows) {
    for (double value :
         {r.tension, r.strain_total, r.strain_elastic, r.strain_viscoelastic, r.strain_permanent}) {
      if (std::isfinite(value)) continue;
      throw InputError(label + ": the strain at t = " + format_number(r.time) + " s under " +
                       format_number(r.tension) +
                       " N/m is not a finite number; check the load and the moduli and their "
                       "units");
    }
  }
}

std::string csv_text(const std::vector<StripState>& rows) {
  std::ostringstream out;
  out << "time_s,tension_N_per_m,strain_total,strain_elastic,strain_viscoelastic,"
         "strain_permanent\n";
  for (const auto& r : rows) {
    out << format_number(r.time) << ',' << format_number(r.tension) << ','
        << format_number(r.strain_total) << ',' << format_number(r.strain_elastic) << ','
        << format_number(r.strain_viscoelastic) << ',' << format_number(r.strain_permanent) << '\n';
  }
  return out.str();
}

nlohmann::json material_json(const DirectionalMaterial& material) {
  nlohmann::json curve = nlohmann::json::array();
  for (const auto& p : material.elastic.points())
    curve.push_back({p.strain, p.tension});
  nlohmann::json elastic =
      material.elastic.is_linear()
          ? nlohmann::json{{"modulus_N_per_m", material.elastic.initial_modulus()}}
          : nlohmann::json{{"curve_strain_tension", curve}};
  return {{"E_N_per_m", material.creep.creep_modulus},
          {"alpha", material.creep.alpha},
          {"lambda_load_per_s", material.creep.lambda_load},
          {"lambda_unload_per_s", material.creep.lambda_unload},
          {"elastic", elastic}};
}

// The first row at `time`: at a jump, the state just before it.
const StripState& first_row_at(const std::vector<StripState>& rows, double time) {
  return *std::lower_bound(rows.begin(), rows.end(), time,
                           [](const StripState& r, double t) { return r.time < t; });
}

nlohmann::json state_json(const StripState& s) {
  return {{"time_s", s.time},
          {"tension_N_per_m", s.tension},
          {"strain_total", s.strain_total},
          {"strain_elastic", s.strain_elastic},
          {"strain_viscoelastic", s.strain_viscoelastic},
          {"strain_permanent", s.strain_permanent}};
}

std::string file_label(const MaterialChoice& choice) {
  std::string label = choice.fabric.name + "_" + name_of(choice.direction);
  std::replace_if(
      label.begin(), label.end(),
      [](char c) { return !std::isalnum(static_cast<unsigned char>(c)) && c != '_'; }, '_');
  return label;
}

// The fabrics and directions --fabric names, checked for creep, their
// elastic curves linear where --elastic-modulus is given.
std::vector<MaterialChoice> creep_choices(const Options& options) {
  std::vector<MaterialChoice> choices = resolve_fabrics(options.text("fabric"));
  for (const auto& choice : choices) {
    print_warnings(choice.fabric.warnings);
    choice.fabric.check_creep();
  }
  if (options.is_set("elastic-modulus")) {
    const double modulus = options.positive_real("elastic-modulus");
    for (auto& choice : choices) {
      const std::string context = choice.label() + " (--elastic-modulus)";
      auto& material =
          choice.direction == Direction::warp ? choice.fabric.warp : choice.fabric.weft;
      material->elastic = TensionCurve::linear(modulus, context);
    }
  }
  return choices;
}

} // namespace

int run_creep(const Invocation& invocation) {
  const Options& options = invocation.options;
  const auto started = std::chrono::steady_clock::now();
  const std::vector<MaterialChoice> choices = creep_choices(options);

  nlohmann::json load;
  const bool from_file = options.is_set("tension-history");
  for (const char* test_option :
       {"force", "width", "tension", "load-duration", "recovery-duration"}) {
    if (from_file && options.is_set(test_option)) {
      throw InputError(std::string("--tension-history replaces the constant-force test; drop --") +
                       test_option);
    }
  }
  if (options.is_set("tension") && (options.is_set("force") || options.is_set("width"))) {
    throw InputError("give --tension or --force with --width, not both");
  }
  const TensionHistory history = [&] {
    if (from_file) {
      const std::string path = options.text("tension-history");
      load = {{"kind", "history"}, {"file", path}};
      return TensionHistory::from_csv(path);
    }
    const double tension = options.is_set("tension")
                               ? options.positive_real("tension")
                               : options.positive_real("force") / options.positive_real("width");
    const double load_duration = options.positive_real("load-duration");
    const double recovery_duration = options.nonnegative_real("recovery-duration");
    load = {{"kind", "creep_recovery"},
            {"tension_N_per_m", tension},
            {"load_duration_s", load_duration},
            {"recovery_duration_s", recovery_duration}};
    if (!options.is_set("tension")) {
      load["force_N"] = options.real("force");
      load["width_m"] = options.real("width");
    }
    return TensionHistory::creep_recovery(tension, load_duration, recovery_duration);
  }();
  check_simulated_time(history.end_time(), "load-duration");
  if (options.is_set("sample-interval")) {
    check_time_divisions(history.end_time(), "load-duration",
                         options.positive_real("sample-interval"), "sample-interval");
  }
  const std::vector<double> times =
      options.is_set("sample-interval")
          ? uniform_sample_times(history, options.positive_real("sample-interval"))
          : log_sample_times(history, options.positive_real("first-sample"),
                             int(options.integer_in("samples-per-decade", 1, 10000)));

  const std::string directory = options.text("output");
  if (is_root()) make_output_directory(directory);
  nlohmann::json summary = run_metadata(invocation, "creep");
  summary["load"] = load;
  summary["runs"] = nlohmann::json::array();
  for (const auto& choice : choices) {
    const std::vector<StripState> rows = simulate_strip(choice.material(), history, times);
    reject_overflow(rows, choice.label());
    const std::string csv =
        choices.size() == 1 ? "creep.csv" : "creep_" + file_label(choice) + ".csv";
    if (is_root()) write_file_atomically(directory + "/" + csv, csv_text(rows));
    nlohmann::json run = {{"name", choice.label()},
                          {"fabric", choice.fabric.name},
                          {"direction", name_of(choice.direction)},
                          {"source", choice.fabric.source},
                          {"csv", csv},
                          {"rows", rows.size()},
                          {"load", load},
                          {"parameters", material_json(choice.material())},
                          {"final", state_json(rows.back())}};
    if (!from_file) {
      const double tension = load["tension_N_per_m"];
      const double unload = load["load_duration_s"];
      run["saturation_creep_strain"] = saturation_strain(choice.material().creep, tension);
      run["end_of_loading"] = state_json(first_row_at(rows, unload));
    }
    summary["runs"].push_back(run);
    SartorPetscCall(PetscPrintf(PETSC_COMM_WORLD,
                                "  %-22s total strain %.4f%% at t = %s s (%zu rows)\n",
                                choice.label().c_str(), 100.0 * rows.back().strain_total,
                                format_number(rows.back().time).c_str(), rows.size()));
  }
  summary["wall_time_s"] =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  if (is_root()) write_json(directory + "/summary.json", summary);
  if (!options.flag("no-plot")) make_plot("plot_creep.py", directory);
  SartorPetscCall(PetscPrintf(PETSC_COMM_WORLD, "sartor creep: wrote %s (%zu run%s)\n",
                              directory.c_str(), choices.size(), choices.size() == 1 ? "" : "s"));
  return 0;
}

} // namespace sartor
