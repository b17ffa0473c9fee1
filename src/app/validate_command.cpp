// sartor validate: fit one creep test, predict another, report the prediction error.

#include "app/commands.hpp"
#include "common/csv.hpp"
#include "common/error.hpp"
#include "common/output.hpp"
#include "fem/petsc_call.hpp"
#include "solvers/creep_fit.hpp"

#include <nlohmann/json.hpp>
#include <petscsys.h>

#include <optional>
#include <sstream>

namespace sartor {

const CommandSpec& validate_command() {
  static const CommandSpec spec{
      "validate",
      "fit one creep test, predict another: the prediction error with its uncertainty band",
      "sartor validate FIT.csv PREDICT.csv [options]",
      "Fits the five parameters (K, E, alpha, lambda_load, lambda_unload) to FIT.csv\n"
      "(with the tests of --also-fit: one least-squares fit) as `sartor fit` does,\n"
      "then predicts PREDICT.csv (another load level, another load history) with\n"
      "them and reports the prediction error: its RMSE, its\n"
      "largest value and when it occurs, the confidence band of the predicted curve\n"
      "(delta method with the fit's covariance, widened when the fit's residuals are\n"
      "autocorrelated), and the fraction of the measured samples inside the\n"
      "prediction interval (band and the fit's noise together; about the confidence\n"
      "level when the model transfers to the other test).\n\n"
      "Both files are read as by `sartor fit` (docs/formats.md): a tension or force\n"
      "column is the load (a varying one the load history); otherwise give the\n"
      "tension or a load-history file for each.\n\n"
      "Output in DIR: validate.json, validate.csv (the prediction, its band and the\n"
      "error per sample), validate.png.\n\n"
      "example:\n"
      "  sartor validate cotton_20kgf.csv cotton_10kgf.csv --width 0.08",
      {
          {"width", "M", "", "specimen width, m, for force columns"},
          {"gauge-length", "M", "", "gauge length, m, for extension columns"},
          {"fit-tension", "N/M", "", "tension of FIT.csv when it has no load column, N/m"},
          {"predict-tension", "N/M", "", "tension of PREDICT.csv when it has no load column, N/m"},
          {"fit-load-history", "FILE", "",
           "load history of FIT.csv (as sartor fit --load-history)"},
          {"also-fit", "FILES", "",
           "comma-separated further tests of the same fabric direction, fitted together with "
           "FIT.csv (each with its load column)"},
          {"predict-load-history", "FILE", "", "load history of PREDICT.csv"},
          {"confidence", "LEVEL", "0.95", "confidence level of the band, in (0, 1)"},
          {"output", "DIR", "out/validate", "output folder (created; files in it are replaced)"},
          {"no-plot", "", "", "write data only, no PNG"},
      },
      2};
  return spec;
}

namespace {

std::optional<double> optional_positive(const Options& options, const std::string& name) {
  if (!options.is_set(name)) return std::nullopt;
  return options.positive_real(name);
}

CreepTestData read_test(const Options& options, const std::string& path, const std::string& role) {
  CreepTestDescription given;
  given.width = optional_positive(options, "width");
  given.gauge_length = optional_positive(options, "gauge-length");
  given.tension = optional_positive(options, role + "-tension");
  if (options.is_set(role + "-load-history")) {
    given.load_history = options.text(role + "-load-history");
  }
  return read_creep_test_data(path, given);
}

std::string validate_csv(const CreepTestData& data, const CreepPrediction& prediction) {
  std::ostringstream out;
  out << "time_s,strain_measured,strain_predicted,band_low,band_high,interval_half_width,error\n";
  for (std::size_t i = 0; i < data.time.size(); ++i) {
    const double predicted = prediction.strain[i];
    out << format_number(data.time[i]) << ',' << format_number(data.strain[i]) << ','
        << format_number(predicted) << ',' << format_number(predicted - prediction.band[i]) << ','
        << format_number(predicted + prediction.band[i]) << ','
        << format_number(prediction.interval[i]) << ',' << format_number(prediction.error[i])
        << '\n';
  }
  return out.str();
}

nlohmann::json test_json(const CreepTestData& data) {
  return {{"file", data.path},
          {"samples", data.time.size()},
          {"peak_tension_N_per_m", data.test.tension},
          {"tension_from", data.tension_origin},
          {"load_history_knots", data.history.size()},
          {"tests", std::max<std::size_t>(1, data.segments.size())}};
}

nlohmann::json validate_report(const Invocation& invocation, const CreepTestData& fitted,
                               const CreepFit& fit, const CreepTestData& predicted,
                               const CreepPrediction& prediction) {
  nlohmann::json report = run_metadata(invocation, "validate");
  nlohmann::json parameters = nlohmann::json::object();
  for (std::size_t j = 0; j < creep_test_parameter_count; ++j) {
    const ParameterEstimate& e = fit.estimates[j];
    parameters[creep_test_parameter_names()[j]] = {{"value", e.value},
                                                   {"std_error", e.std_error},
                                                   {"ci_low", e.ci_low},
                                                   {"ci_high", e.ci_high}};
  }
  report["confidence_level"] = fit.confidence_level;
  report["fit"] = {{"input", test_json(fitted)},
                   {"parameters", parameters},
                   {"rmse", fit.rmse},
                   {"residual_std", fit.residual_std},
                   {"autocorrelation_present", fit.autocorrelation.present},
                   {"certification", fit.certification},
                   {"warnings", fit.warnings}};
  report["prediction"] = {
      {"input", test_json(predicted)},
      {"rmse", prediction.rmse},
      {"rmse_over_fit_residual_std", prediction.rmse / fit.residual_std},
      {"max_abs_error", prediction.max_abs_error},
      {"time_of_max_abs_error_s", prediction.time_of_max_error},
      {"band_half_width_rms", prediction.band_rms},
      {"band_half_width_max", prediction.band_max},
      {"fraction_within_prediction_interval", prediction.within_prediction_interval}};
  return report;
}

} // namespace

int run_validate(const Invocation& invocation) {
  const Options& options = invocation.options;
  const double confidence = options.real("confidence");
  if (!(confidence > 0.0 && confidence < 1.0)) {
    throw InputError("option --confidence: must lie in (0, 1), got " + options.text("confidence"));
  }
  const auto& files = invocation.command_line.positionals;
  std::vector<CreepTestData> tests{read_test(options, files.at(0), "fit")};
  if (options.is_set("also-fit")) {
    CreepTestDescription given;
    given.width = optional_positive(options, "width");
    given.gauge_length = optional_positive(options, "gauge-length");
    std::istringstream list(options.text("also-fit"));
    for (std::string path; std::getline(list, path, ',');) {
      if (path.empty()) throw InputError("option --also-fit: an empty file name in the list");
      tests.push_back(read_creep_test_data(path, given));
    }
  }
  const CreepTestData fitted = tests.size() == 1 ? tests.front() : combine_tests(tests);
  const CreepTestData predicted = read_test(options, files.at(1), "predict");

  const ThesisEstimate start = start_estimate(fitted);
  CreepFit fit;
  SartorPetscCall(fit_creep_test(PETSC_COMM_WORLD, fitted, start.parameters, confidence, &fit));
  if (!fit.converged) {
    throw SolveFailure("the fit of " + fitted.path + " reached no certified optimum (" +
                       fit.converged_reason + "; " + fit.certification + "): nothing to validate");
  }
  const CreepPrediction prediction = predict_creep_test(predicted, fit);

  const std::string directory = options.text("output");
  if (is_root()) {
    make_output_directory(directory);
    write_json(directory + "/validate.json",
               validate_report(invocation, fitted, fit, predicted, prediction));
    write_file_atomically(directory + "/validate.csv", validate_csv(predicted, prediction));
  }
  SartorPetscCall(PetscPrintf(
      PETSC_COMM_WORLD,
      "sartor validate: fitted %s (%zu samples, RMSE %.3g), predicted %s (%zu samples)\n"
      "  prediction error: RMSE %.3g (%.3g x the fit's residual s.d.), max %.3g at %.6g s\n"
      "  %.4g%% confidence band of the prediction: half-width %.3g RMS, %.3g max\n"
      "  %.1f%% of the samples lie inside the %.4g%% prediction interval\n",
      fitted.path.c_str(), fitted.time.size(), fit.rmse, predicted.path.c_str(),
      predicted.time.size(), prediction.rmse, prediction.rmse / fit.residual_std,
      prediction.max_abs_error, prediction.time_of_max_error, 100 * confidence, prediction.band_rms,
      prediction.band_max, 100 * prediction.within_prediction_interval, 100 * confidence));
  if (!options.flag("no-plot")) make_plot("plot_validate.py", directory);
  SartorPetscCall(PetscPrintf(PETSC_COMM_WORLD, "sartor validate: wrote %s\n", directory.c_str()));
  return 0;
}

} // namespace sartor
