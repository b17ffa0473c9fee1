// sartor fit: creep-law parameters from a measured creep-and-recovery curve.

#include "app/commands.hpp"
#include "common/csv.hpp"
#include "common/error.hpp"
#include "common/output.hpp"
#include "fem/petsc_call.hpp"
#include "material/fabric.hpp"
#include "solvers/creep_fit.hpp"

#include <nlohmann/json.hpp>
#include <petscsys.h>
#include <yaml-cpp/yaml.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <sstream>

namespace sartor {

const CommandSpec& fit_command() {
  static const CommandSpec spec{
      "fit",
      "fit creep-law parameters to a measured creep-and-recovery curve",
      "sartor fit DATA.csv [--force N --width M | --tension N/M] [options]",
      "Determines the immediate-elastic modulus K and the creep parameters E, alpha,\n"
      "lambda_load, lambda_unload from a creep-and-recovery test (constant force or\n"
      "any load history): first by the thesis' step-by-step procedure (§5.2.2; for\n"
      "a load history a grid of linear fits over the rates), then by a joint\n"
      "nonlinear least-squares fit of all five (Levenberg-Marquardt in log\n"
      "parameters with column scaling; the optimum is certified by a final\n"
      "Gauss-Newton step, recorded in fit.json), with standard errors and\n"
      "confidence intervals, and a second set from a residual bootstrap. Residual\n"
      "autocorrelation (drift) is measured and, when present, widens the\n"
      "intervals. Warns when the test did not reach\n"
      "saturation or full recovery (thesis App. A).\n\n"
      "DATA.csv has columns time_s and strain, and optionally tension_N_per_m or\n"
      "force_N (then the load and unload times are read from it; a column that\n"
      "varies during loading - ramps, several levels, cycles - is the load history,\n"
      "piecewise linear between samples, integrated exactly by the law; so is\n"
      "--load-history FILE for DATA without a load column). Headers may\n"
      "carry units, as instruments write them: \"Time (s)\", time [min], Strain (%),\n"
      "Extension (mm) with --gauge-length, Force (kgf), Load (kN), Tension (N/mm); see\n"
      "docs/formats.md. Without them the load is taken to start at the first sample\n"
      "and the unloading is found as the largest strain drop.\n\n"
      "Output in DIR: fit.json, fit.csv (data, fit, residual), fabric.yaml (usable\n"
      "by sartor creep --fabric), fit.png.\n\n"
      "examples:\n"
      "  sartor fit cases/fit/cotton_twill_warp.csv\n"
      "  sartor fit my_test.csv --force 196.1 --width 0.08 --unload-time 3600\n"
      "  sartor fit ramped.csv --load-history load.csv\n"
      "  sartor fit silk_warp.csv --weft-data silk_weft.csv --name silk",
      {
          {"force", "N", "", "test force, N (with --width), when DATA has no tension column"},
          {"width", "M", "", "specimen width, m"},
          {"gauge-length", "M", "",
           "gauge length, m, when DATA gives the extension (mm, cm, m) instead of strain"},
          {"tension", "N/M", "", "test tension per unit width, N/m"},
          {"load-time", "S", "", "time at which the load was applied, s"},
          {"unload-time", "S", "", "time at which the load was removed, s"},
          {"load-history", "FILE", "",
           "CSV of time and tension (or force, with --width): any piecewise-linear load, for "
           "DATA without a load column"},
          {"confidence", "LEVEL", "0.95", "confidence level of the intervals, in (0, 1)"},
          {"bootstrap", "N", "200",
           "residual-bootstrap refits for the second, non-linearised intervals (0: none)"},
          {"seed", "N", "1", "random seed of the bootstrap"},
          {"name", "NAME", "", "fabric name in fabric.yaml [file name of DATA]"},
          {"direction", "DIR", "warp", "fabric direction the test measured: warp or weft"},
          {"weft-data", "FILE", "",
           "the weft test of the same fabric (with its load column), fitted in the same run: "
           "DATA is then the warp test, fabric.yaml has both directions, the weft's fit files "
           "are in DIR/weft"},
          {"output", "DIR", "out/fit", "output folder (created; files in it are replaced)"},
          {"no-plot", "", "", "write data only, no PNG"},
      },
      1};
  return spec;
}

namespace {

std::optional<double> optional_positive(const Options& options, const std::string& name) {
  if (!options.is_set(name)) return std::nullopt;
  return options.positive_real(name);
}

std::optional<double> optional_real(const Options& options, const std::string& name) {
  if (!options.is_set(name)) return std::nullopt;
  return options.real(name);
}

nlohmann::json parameters_json(const CreepTestParameters& p) {
  return {{"elastic_modulus_N_per_m", p.elastic_modulus},
          {"E_N_per_m", p.creep_modulus},
          {"alpha", p.alpha},
          {"lambda_load_per_s", p.lambda_load},
          {"lambda_unload_per_s", p.lambda_unload}};
}

std::string fit_csv(const CreepTestData& data, const CreepTestParameters& parameters) {
  std::vector<double> model(data.time.size());
  evaluate_model(data, parameters, 0, data.time.size(), model.data());
  std::ostringstream out;
  out << "time_s,strain_measured,strain_fit,residual,phase,tension_N_per_m\n";
  for (std::size_t i = 0; i < model.size(); ++i) {
    out << format_number(data.time[i]) << ',' << format_number(data.strain[i]) << ','
        << format_number(model[i]) << ',' << format_number(data.strain[i] - model[i]) << ','
        << int(data.test.phase(data.time[i])) << ','
        << format_number(
               data.history.empty()
                   ? (data.test.phase(data.time[i]) == TestPhase::loading ? data.test.tension : 0.0)
                   : tension_at(data.history, data.time[i]))
        << '\n';
  }
  return out.str();
}

struct FittedDirection {
  std::string direction, source;
  CreepTestParameters parameters;
};

std::string fabric_yaml(const std::string& name, const std::vector<FittedDirection>& fitted) {
  std::string sources;
  for (const FittedDirection& f : fitted)
    sources += (sources.empty() ? "" : " and ") + f.source;
  YAML::Emitter out;
  out.SetDoublePrecision(17);
  out << YAML::Comment("Written by sartor fit; loads with sartor creep --fabric FILE")
      << YAML::BeginMap << YAML::Key << "name" << YAML::Value << name << YAML::Key << "source"
      << YAML::Value << "sartor fit of " + sources;
  for (const FittedDirection& f : fitted) {
    const CreepTestParameters& p = f.parameters;
    out << YAML::Key << f.direction << YAML::Value << YAML::BeginMap << YAML::Key << "E"
        << YAML::Value << p.creep_modulus << YAML::Comment("N/m") << YAML::Key << "alpha"
        << YAML::Value << p.alpha << YAML::Key << "lambda_load" << YAML::Value << p.lambda_load
        << YAML::Comment("1/s") << YAML::Key << "lambda_unload" << YAML::Value << p.lambda_unload
        << YAML::Comment("1/s") << YAML::Key << "elastic_modulus" << YAML::Value
        << p.elastic_modulus << YAML::Comment("N/m, secant modulus at the test load")
        << YAML::EndMap;
  }
  out << YAML::EndMap;
  return std::string(out.c_str()) + "\n";
}

nlohmann::json
estimates_json(const std::array<ParameterEstimate, creep_test_parameter_count>& estimates) {
  nlohmann::json parameters = nlohmann::json::object();
  for (std::size_t j = 0; j < creep_test_parameter_count; ++j) {
    const ParameterEstimate& e = estimates[j];
    parameters[creep_test_parameter_names()[j]] = {{"value", e.value},
                                                   {"std_error", e.std_error},
                                                   {"ci_low", e.ci_low},
                                                   {"ci_high", e.ci_high}};
  }
  return parameters;
}

nlohmann::json fit_report(const Invocation& invocation, const CreepTestData& data,
                          const ThesisEstimate& initial, const CreepFit& fit,
                          const BootstrapEstimate& bootstrap) {
  nlohmann::json report = run_metadata(invocation, "fit");
  report["input"] = {{"file", data.path},
                     {"samples", data.time.size()},
                     {"tension_N_per_m", data.test.tension},
                     {"tension_from", data.tension_origin},
                     {"load_time_s", data.test.load_time},
                     {"load_time_from", data.load_time_origin},
                     {"unload_time_s", data.test.unload_time},
                     {"unload_time_from", data.unload_time_origin},
                     {"end_time_s", data.time.back()},
                     {"load_history_knots", data.history.size()}};
  report["start_method"] = data.history.empty() ? "thesis §5.2.2" : "grid of linear fits";
  report["thesis_estimate"] = parameters_json(initial.parameters);
  report["thesis_estimate"]["immediate_strain"] = initial.immediate_strain;
  report["thesis_estimate"]["nonelastic_strain_at_unload"] = initial.nonelastic_at_unload;
  report["thesis_estimate"]["permanent_strain_at_end"] = initial.permanent_at_end;
  report["thesis_estimate"]["notes"] = initial.notes;
  report["confidence_level"] = fit.confidence_level;
  report["parameters"] = estimates_json(fit.estimates);
  report["correlation"] = {{"order", creep_test_parameter_names()}, {"matrix", fit.correlation}};
  report["goodness"] = {{"rmse", fit.rmse},
                        {"r_squared", fit.r_squared},
                        {"residual_std", fit.residual_std},
                        {"samples", fit.samples},
                        {"degrees_of_freedom", fit.degrees_of_freedom}};
  report["saturation"] = {{"loading_saturation_fraction", fit.loading_saturation},
                          {"recovery_remaining_fraction", fit.recovery_remaining},
                          {"loading_saturated", fit.loading_saturated},
                          {"recovery_relaxed", fit.recovery_relaxed},
                          {"warnings", fit.warnings}};
  report["solver"] = {
      {"method", fit.solver},
      {"converged", fit.converged},
      {"reason", fit.converged_reason},
      {"iterations", fit.iterations},
      {"optimum_certified", fit.optimum_certified},
      {"certification", fit.certification},
      {"final_gauss_newton_step_standard_errors", fit.certificate_step_standard_errors},
      {"final_step_descent_over_residual_variance", fit.certificate_descent_over_variance}};
  const ResidualAutocorrelation& a = fit.autocorrelation;
  report["autocorrelation"] = {{"lag1", a.lag1},
                               {"z_score", a.z_score},
                               {"durbin_watson", a.durbin_watson},
                               {"present", a.present},
                               {"variance_inflation", a.variance_inflation},
                               {"effective_samples", a.effective_samples}};
  if (bootstrap.replicates > 0) {
    report["bootstrap"] = {{"replicates", bootstrap.replicates},
                           {"failed", bootstrap.failed},
                           {"ar1_coefficient", bootstrap.ar1_coefficient},
                           {"parameters", estimates_json(bootstrap.estimates)}};
  }
  return report;
}

void print_estimates(const std::array<ParameterEstimate, creep_test_parameter_count>& estimates,
                     double confidence, bool with_values) {
  for (std::size_t j = 0; j < creep_test_parameter_count; ++j) {
    const ParameterEstimate& e = estimates[j];
    char value[40] = "", line[200];
    if (with_values) std::snprintf(value, sizeof value, "%.6g", e.value);
    std::snprintf(line, sizeof line, "  %-24s %-12s +- %-10.3g (%.4g%% CI %.6g .. %.6g)\n",
                  creep_test_parameter_names()[j], value, e.std_error, 100 * confidence, e.ci_low,
                  e.ci_high);
    SartorPetscCall(PetscPrintf(PETSC_COMM_WORLD, "%s", line));
  }
}

void print_fit(const CreepTestData& data, const CreepFit& fit, const BootstrapEstimate& bootstrap) {
  SartorPetscCall(PetscPrintf(PETSC_COMM_WORLD, "sartor fit: %s, %zu samples, tension %.6g N/m\n",
                              data.path.c_str(), data.time.size(),
                              static_cast<double>(data.test.tension)));
  print_estimates(fit.estimates, fit.confidence_level, true);
  SartorPetscCall(PetscPrintf(
      PETSC_COMM_WORLD, "  RMSE %.3g, R^2 %.6f, %ld Levenberg-Marquardt iterations (%s)\n",
      fit.rmse, fit.r_squared, fit.iterations, fit.converged_reason.c_str()));
  SartorPetscCall(
      PetscPrintf(PETSC_COMM_WORLD, "  optimum certified: %s\n", fit.certification.c_str()));
  if (bootstrap.replicates > 0) {
    SartorPetscCall(PetscPrintf(PETSC_COMM_WORLD, "  residual bootstrap, %ld refits%s:\n",
                                bootstrap.replicates,
                                bootstrap.ar1_coefficient != 0.0 ? " (AR(1) innovations)" : ""));
    print_estimates(bootstrap.estimates, fit.confidence_level, false);
  }
  SartorPetscCall(
      PetscPrintf(PETSC_COMM_WORLD,
                  "  residual lag-1 autocorrelation %.3g (%.1f x its spread for "
                  "independent noise): %s\n",
                  fit.autocorrelation.lag1, fit.autocorrelation.z_score,
                  fit.autocorrelation.present ? "present, intervals widened" : "none detected"));
  for (const auto& warning : fit.warnings) {
    SartorPetscCall(PetscPrintf(PETSC_COMM_WORLD, "  warning: %s\n", warning.c_str()));
  }
}

} // namespace

namespace {

struct FitSettings {
  double confidence = 0.95;
  long replicates = 0;
  unsigned long seed = 1;
  bool plot = true;
};

// Fits one direction's test and writes fit.json and fit.csv (and fit.png) in
// `directory`; throws when the fit reaches no certified optimum.
CreepFit fit_direction(const Invocation& invocation, const std::string& path,
                       const CreepTestDescription& given, const FitSettings& settings,
                       const std::string& directory) {
  const auto started = std::chrono::steady_clock::now();
  const CreepTestData data = read_creep_test_data(path, given);
  const auto read = std::chrono::steady_clock::now();
  const ThesisEstimate initial = start_estimate(data);
  const auto estimated = std::chrono::steady_clock::now();
  CreepFit fit;
  SartorPetscCall(
      fit_creep_test(PETSC_COMM_WORLD, data, initial.parameters, settings.confidence, &fit));
  const auto fitted = std::chrono::steady_clock::now();

  BootstrapEstimate bootstrap;
  if (settings.replicates > 0 && fit.converged) {
    SartorPetscCall(bootstrap_creep_fit(PETSC_COMM_WORLD, data, fit, settings.replicates,
                                        settings.seed, &bootstrap));
  }
  const auto bootstrapped = std::chrono::steady_clock::now();

  nlohmann::json report = fit_report(invocation, data, initial, fit, bootstrap);
  report["solver"]["read_time_s"] = std::chrono::duration<double>(read - started).count();
  report["solver"]["estimate_time_s"] = std::chrono::duration<double>(estimated - read).count();
  report["solver"]["refine_time_s"] = std::chrono::duration<double>(fitted - estimated).count();
  report["solver"]["bootstrap_time_s"] =
      std::chrono::duration<double>(bootstrapped - fitted).count();

  if (is_root()) {
    make_output_directory(directory);
    write_json(directory + "/fit.json", report);
    write_file_atomically(directory + "/fit.csv", fit_csv(data, fit.parameters));
  }
  if (!fit.converged) {
    throw SolveFailure("the least-squares refinement did not reach a certified optimum (" +
                       fit.converged_reason + "; " + fit.certification + "); " + directory +
                       "/fit.json holds the thesis estimate and the last iterate");
  }
  print_fit(data, fit, bootstrap);
  if (settings.plot) make_plot("plot_fit.py", directory);
  return fit;
}

} // namespace

int run_fit(const Invocation& invocation) {
  const Options& options = invocation.options;
  const std::string path = invocation.command_line.positionals.at(0);
  FitSettings settings;
  settings.confidence = options.real("confidence");
  if (!(settings.confidence > 0.0 && settings.confidence < 1.0)) {
    throw InputError("option --confidence: must lie in (0, 1), got " + options.text("confidence"));
  }
  settings.replicates = options.integer("bootstrap");
  if (settings.replicates != 0 && settings.replicates < 20) {
    throw InputError("option --bootstrap: give 0 (none) or at least 20 refits, got " +
                     options.text("bootstrap"));
  }
  settings.seed = (unsigned long)options.integer("seed");
  settings.plot = !options.flag("no-plot");
  const std::string direction = options.text("direction");
  parse_direction(direction, "option --direction");
  if (options.is_set("weft-data") && direction != "warp") {
    throw InputError("option --weft-data: DATA.csv is then the warp test; drop --direction " +
                     direction);
  }
  const std::string name =
      options.is_set("name") ? options.text("name") : std::filesystem::path(path).stem().string();

  CreepTestDescription given;
  given.tension = optional_positive(options, "tension");
  given.force = optional_positive(options, "force");
  given.width = optional_positive(options, "width");
  given.gauge_length = optional_positive(options, "gauge-length");
  given.load_time = optional_real(options, "load-time");
  given.unload_time = optional_real(options, "unload-time");
  if (options.is_set("load-history")) given.load_history = options.text("load-history");

  const std::string directory = options.text("output");
  std::vector<FittedDirection> fitted;
  fitted.push_back(
      {direction, path, fit_direction(invocation, path, given, settings, directory).parameters});
  if (options.is_set("weft-data")) {
    // The weft test carries its own load; only the specimen's geometry is shared.
    CreepTestDescription weft;
    weft.width = given.width;
    weft.gauge_length = given.gauge_length;
    const std::string weft_path = options.text("weft-data");
    fitted.push_back(
        {"weft", weft_path,
         fit_direction(invocation, weft_path, weft, settings, directory + "/weft").parameters});
  }
  if (is_root()) write_file_atomically(directory + "/fabric.yaml", fabric_yaml(name, fitted));
  SartorPetscCall(PetscPrintf(PETSC_COMM_WORLD, "sartor fit: wrote %s\n", directory.c_str()));
  return 0;
}

} // namespace sartor
