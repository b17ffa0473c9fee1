#pragma once
// Fitting the creep law to a measured constant-force creep-and-recovery curve:
// the thesis' procedure (§5.2.2) for a first estimate, then a joint nonlinear
// least-squares refinement of all parameters (Levenberg-Marquardt), with standard
// errors and confidence intervals from the Jacobian. docs/theory.md has the math.

#include "material/creep_recovery_model.hpp"

#include <petscsys.h>

#include <array>
#include <optional>
#include <string>
#include <vector>

namespace sartor {

// One test of several fitted as one (combine_tests): samples [begin, end)
// under `history`, from a virgin specimen.
struct LoadSegment {
  std::size_t begin = 0;
  std::size_t end = 0;
  LoadHistory history;
};

struct CreepTestData {
  std::string path;
  std::vector<double> time;   // s, non-decreasing
  std::vector<double> strain; // elongation over the rest length
  std::vector<long> line;     // file line of each sample, for messages
  // The load: a step test (`test`) when `history` is empty, else `history`;
  // `test` then describes its largest load (peak tension, first rise to and
  // last fall from half of it) for the report and the saturation warnings.
  CreepTest test;
  LoadHistory history;
  // Several tests fitted together: each segment its own test; `history` is
  // then empty and `test` that of the first test.
  std::vector<LoadSegment> segments;
  // How the tension and the load/unload times were obtained, for the report.
  std::string tension_origin;
  std::string load_time_origin;
  std::string unload_time_origin;
};

// What the command line says about the test; anything left empty is read from
// the file's force/tension column or detected from the strain.
struct CreepTestDescription {
  std::optional<double> tension; // N/m
  std::optional<double> force;   // N, needs width
  std::optional<double> width;   // m
  std::optional<double> load_time;
  std::optional<double> unload_time;
  std::optional<double> gauge_length;      // m, turns an extension column into strain
  std::optional<std::string> load_history; // CSV of time and tension or force (with width)
};

// Several tests of the same fabric direction as one data set, each test with
// its own load (a constant-force test becomes its step history) and time axis.
CreepTestData combine_tests(const std::vector<CreepTestData>& tests);

// A load-history CSV: time and tension, or force divided by `width` (units in
// the header as in the measurement CSV). Throws InputError naming the file.
LoadHistory read_load_history_file(const std::string& path, std::optional<double> width);

// Reads the CSV (docs/formats.md) and settles the test description.
// Throws InputError with FILE:LINE for anything malformed or inconsistent.
CreepTestData read_creep_test_data(const std::string& path, const CreepTestDescription& given);

// The thesis' step-by-step determination (§5.2.2), assuming the test reached
// saturation. Throws InputError when the data cannot support it.
struct ThesisEstimate {
  CreepTestParameters parameters;
  double immediate_strain = 0.0;     // jump at load application
  double nonelastic_at_unload = 0.0; // eps_v + eps_p at the end of loading
  double permanent_at_end = 0.0;     // strain at the end of recovery
  std::vector<std::string> notes;
};
ThesisEstimate thesis_estimate(const CreepTestData& data);

// A start for any load history: over a grid of (lambda_load, lambda_unload),
// the strain is nearly linear in 1/K, (1 - alpha)/E and alpha/E (the small
// product of elastic and creep strain left out); the grid point whose linear
// least-squares fit has the least misfit gives the start. For a step test
// (`history` empty) this is thesis_estimate().
ThesisEstimate start_estimate(const CreepTestData& data);

// The model strain of samples [begin, end) of `data` (step test or history),
// with the Jacobian as evaluate_creep_test() when `jacobian` is not null.
void evaluate_model(const CreepTestData& data, const CreepTestParameters& p, std::size_t begin,
                    std::size_t end, double* strain, double* jacobian = nullptr,
                    std::size_t leading_dimension = 0);

struct ParameterEstimate {
  double value = 0.0;
  double std_error = 0.0;
  double ci_low = 0.0;
  double ci_high = 0.0;
};

// Lag-1 autocorrelation of the residuals in time order (measurement drift,
// unresolved dynamics). Independent noise gives lag1 ~ N(0, 1/n).
struct ResidualAutocorrelation {
  double lag1 = 0.0;
  double z_score = 0.0;            // lag1 sqrt(n)
  double durbin_watson = 2.0;      // 2 (1 - lag1)
  bool present = false;            // z_score > 3
  double variance_inflation = 1.0; // (1 + lag1) / (1 - lag1) when present, else 1
  double effective_samples = 0.0;  // n / variance_inflation
};

struct CreepFit {
  CreepTestParameters parameters;
  std::array<ParameterEstimate, creep_test_parameter_count> estimates; // K, E, alpha, l_l, l_u
  std::array<std::array<double, creep_test_parameter_count>, creep_test_parameter_count>
      correlation{};
  // Of the fit variables q (ln K, ln E, alpha, ln lambda_l, ln lambda_u),
  // including the autocorrelation's inflation; t_quantile draws the intervals.
  std::array<std::array<double, creep_test_parameter_count>, creep_test_parameter_count>
      covariance{};
  double t_quantile = 0.0;
  double confidence_level = 0.95;
  long samples = 0;
  long degrees_of_freedom = 0;
  double rmse = 0.0;
  double r_squared = 0.0;
  double residual_std = 0.0; // sqrt(RSS / dof)
  // When present, the covariance (and so the intervals) include its inflation.
  ResidualAutocorrelation autocorrelation;
  // Thesis App. A: how close the test came to saturation and full recovery.
  double loading_saturation = 0.0; // 1 - exp(-lambda_load * loading time)
  double recovery_remaining = 0.0; // exp(-lambda_unload * recovery time)
  bool loading_saturated = false;
  bool recovery_relaxed = false;
  std::vector<std::string> warnings;
  // The optimiser (dense Levenberg-Marquardt) and how it stopped.
  std::string solver;
  std::string converged_reason;
  bool converged = false;
  long iterations = 0;
  // How the optimum was checked after the iterations stopped (docs/theory.md §5.2).
  bool optimum_certified = false;
  std::string certification;
  double certificate_step_standard_errors = 0.0;  // length of the final Gauss-Newton step
  double certificate_descent_over_variance = 0.0; // misfit it removed / residual variance
};

// Joint refinement from `start` on `comm` (the samples are spread over the
// ranks; each iteration sums J^T J, J^T r and the misfit over them). The
// optimum is certified by a final Gauss-Newton step (docs/theory.md §5.2);
// `converged` is true only when the iterations stopped on a convergence test
// and that certificate holds.
PetscErrorCode fit_creep_test(MPI_Comm comm, const CreepTestData& data,
                              const CreepTestParameters& start, double confidence_level,
                              CreepFit* fit);

// A second uncertainty estimate that does not linearise the model: a residual
// bootstrap. Each replicate refits the model's curve at the optimum plus the
// fit's residuals resampled with replacement (centred, scaled by
// sqrt(n / (n - 5))). When the residuals are autocorrelated, their AR(1)
// innovations r_i - rho r_{i-1} are resampled instead and the correlated
// series rebuilt from them (a sieve bootstrap), which keeps the correlation.
// Intervals are the replicates' percentiles at the fit's level; std_error is
// their standard deviation. Same seed, same result, on any number of ranks.
struct BootstrapEstimate {
  long replicates = 0;          // refits that converged
  long failed = 0;              // refits that did not, left out
  double ar1_coefficient = 0.0; // rho of the resampled series (0: independent)
  std::array<ParameterEstimate, creep_test_parameter_count> estimates;
};
PetscErrorCode bootstrap_creep_fit(MPI_Comm comm, const CreepTestData& data, const CreepFit& fit,
                                   long replicates, unsigned long seed,
                                   BootstrapEstimate* bootstrap);

// The fitted model's prediction of another test (another load level or
// history) and its error there: the check `sartor validate` reports. The band
// is the confidence band of the predicted curve, t sqrt(J C J^T) with C the
// fit's covariance (delta method); a measurement is expected within the
// prediction interval t sqrt(J C J^T + s^2), s the fit's residual_std.
struct CreepPrediction {
  std::vector<double> strain;   // predicted
  std::vector<double> band;     // half-width of the confidence band of the curve
  std::vector<double> interval; // half-width of the prediction interval
  std::vector<double> error;    // measured - predicted
  double rmse = 0.0;            // of the error
  double max_abs_error = 0.0;
  double time_of_max_error = 0.0; // s
  double band_rms = 0.0;          // root mean square of the band's half-width
  double band_max = 0.0;
  double within_prediction_interval = 0.0; // fraction of the samples
};
CreepPrediction predict_creep_test(const CreepTestData& data, const CreepFit& fit);

// The names used in fit.json and fabric files, in fit-variable order.
const std::array<const char*, creep_test_parameter_count>& creep_test_parameter_names();

} // namespace sartor
