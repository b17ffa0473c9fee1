#include "solvers/creep_fit.hpp"

#include "common/csv.hpp"
#include "common/error.hpp"
#include "common/statistics.hpp"
#include "common/vector_math.hpp"
#include "fem/petsc_options.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <numeric>

namespace sartor {

const std::array<const char*, creep_test_parameter_count>& creep_test_parameter_names() {
  static const std::array<const char*, creep_test_parameter_count> names = {
      "elastic_modulus_N_per_m", "E_N_per_m", "alpha", "lambda_load_per_s", "lambda_unload_per_s"};
  return names;
}

namespace {

constexpr std::size_t minimum_phase_samples = 5;
constexpr double saturation_threshold = 0.99; // thesis App. A: "full saturation"
constexpr double log_parameter_range = 20.0;

std::string describe_time(double t) {
  return format_number(t) + " s";
}

double mean_of(const std::vector<double>& values, std::size_t begin, std::size_t end) {
  return std::accumulate(values.begin() + long(begin), values.begin() + long(end), 0.0) /
         double(end - begin);
}

// Samples [begin, end) of each phase; the data are sorted by time.
struct PhaseRanges {
  std::size_t load_begin, load_end, recovery_end;
};

PhaseRanges phase_ranges(const CreepTestData& data) {
  const auto& t = data.time;
  const auto first_at = [&t](double time) {
    return std::size_t(std::lower_bound(t.begin(), t.end(), time) - t.begin());
  };
  return {first_at(data.test.load_time), first_at(data.test.unload_time), t.size()};
}

void settle_times_from_tension(CreepTestData& data, const CsvTable& table, std::size_t column,
                               double scale, const std::string& what) {
  const auto& values = table.columns[column];
  const double peak = *std::max_element(values.begin(), values.end()) * scale;
  if (!(peak > 0.0)) throw InputError(data.path + ": the " + what + " column is never positive");
  std::size_t on = 0;
  while (on < values.size() && values[on] * scale < 0.5 * peak)
    ++on;
  std::size_t off = on;
  while (off < values.size() && values[off] * scale >= 0.5 * peak)
    ++off;
  if (off == values.size()) {
    throw InputError(data.path + ": the " + what +
                     " column never drops after loading; a creep-and-recovery test is needed");
  }
  std::vector<double> loaded(values.begin() + long(on), values.begin() + long(off));
  for (double& v : loaded)
    v *= scale;
  const double mean = mean_of(loaded, 0, loaded.size());
  double worst = 0.0;
  std::size_t worst_row = on;
  for (std::size_t i = 0; i < loaded.size(); ++i) {
    if (std::abs(loaded[i] - mean) > worst) {
      worst = std::abs(loaded[i] - mean);
      worst_row = on + i;
    }
  }
  if (worst > 0.05 * mean) {
    throw InputError(data.path, table.lines[worst_row],
                     "the " + what + " deviates " + format_number(100.0 * worst / mean) +
                         "% from its mean during loading; the fit needs a constant-force test");
  }
  if (!data.test.tension) {
    data.test.tension = mean;
    data.tension_origin = "mean of the " + what + " column during loading";
  }
  if (!data.load_time_origin.empty() && !data.unload_time_origin.empty()) return;
  if (data.load_time_origin.empty()) {
    data.test.load_time = data.time[on];
    data.load_time_origin =
        "first sample (line " + std::to_string(table.lines[on]) + ") where the " + what + " is on";
  }
  if (data.unload_time_origin.empty()) {
    data.test.unload_time = data.time[off];
    data.unload_time_origin = "first sample (line " + std::to_string(table.lines[off]) +
                              ") where the " + what + " is off";
  }
}

void detect_unload_from_strain(CreepTestData& data) {
  const auto& y = data.strain;
  std::vector<double> steps;
  std::size_t best = 0;
  double largest_drop = 0.0;
  for (std::size_t i = 1; i < y.size(); ++i) {
    steps.push_back(std::abs(y[i] - y[i - 1]));
    if (data.time[i] > data.test.load_time && y[i - 1] - y[i] > largest_drop) {
      largest_drop = y[i - 1] - y[i];
      best = i;
    }
  }
  std::nth_element(steps.begin(), steps.begin() + long(steps.size() / 2), steps.end());
  const double typical_step = steps[steps.size() / 2];
  if (best == 0 || largest_drop <= 10.0 * typical_step) {
    throw InputError(data.path +
                     ": cannot find the unloading (no strain drop stands out from the noise); "
                     "give --unload-time");
  }
  data.test.unload_time = data.time[best];
  data.unload_time_origin = "largest strain drop, before line " + std::to_string(data.line[best]);
}

} // namespace

CreepTestData read_creep_test_data(const std::string& path, const CreepTestDescription& given) {
  const CsvTable table = read_csv(path);
  CreepTestData data;
  data.path = path;
  const std::size_t time = table.require({"time_s", "time"}, "time in s");
  const std::size_t strain =
      table.require({"strain", "strain_total"}, "elongation over the rest length");
  require_nondecreasing(table, time);
  data.time = table.columns[time];
  data.strain = table.columns[strain];
  data.line = table.lines;
  if (data.time.size() < 2 * minimum_phase_samples) {
    throw InputError(path + ": " + std::to_string(data.time.size()) +
                     " samples are too few to fit five parameters");
  }

  if (given.load_time) {
    data.test.load_time = *given.load_time;
    data.load_time_origin = "--load-time";
  }
  if (given.unload_time) {
    data.test.unload_time = *given.unload_time;
    data.unload_time_origin = "--unload-time";
  }
  if (given.tension) {
    data.test.tension = *given.tension;
    data.tension_origin = "--tension";
  } else if (given.force && given.width) {
    data.test.tension = *given.force / *given.width;
    data.tension_origin = "--force / --width";
  } else if (given.force) {
    throw InputError("--force needs --width (m) to give the tension per unit width");
  }

  if (const auto column = table.find({"tension_n_per_m", "tension"})) {
    settle_times_from_tension(data, table, *column, 1.0, "tension");
  } else if (const auto force = table.find({"force_n", "force"})) {
    if (!given.width && !given.tension) {
      throw InputError(path + ": the force column needs --width (m), the specimen width");
    }
    // With --tension the column only tells when the load was on.
    const double to_tension = given.width ? 1.0 / *given.width : 1.0;
    settle_times_from_tension(data, table, *force, to_tension, "force / width");
  } else {
    if (!data.test.tension) {
      throw InputError(path + ": no tension: give --tension (N/m), or --force (N) and --width "
                              "(m), or a tension_N_per_m or force_N column");
    }
    if (data.load_time_origin.empty()) {
      data.test.load_time = data.time.front();
      data.load_time_origin = "first sample (default; give --load-time otherwise)";
    }
    if (data.unload_time_origin.empty()) detect_unload_from_strain(data);
  }

  if (!(data.test.tension > 0.0)) {
    throw InputError("the test tension must be > 0 N/m, got " + format_number(data.test.tension));
  }
  if (!(data.test.unload_time > data.test.load_time)) {
    throw InputError("the unload time (" + describe_time(data.test.unload_time) +
                     ") must come after the load time (" + describe_time(data.test.load_time) +
                     ")");
  }
  const PhaseRanges phases = phase_ranges(data);
  const std::size_t loading = phases.load_end - phases.load_begin;
  const std::size_t recovery = phases.recovery_end - phases.load_end;
  if (loading < minimum_phase_samples || recovery < minimum_phase_samples) {
    throw InputError(path + ": " + std::to_string(loading) + " samples during loading and " +
                     std::to_string(recovery) + " during recovery (load at " +
                     describe_time(data.test.load_time) + ", unload at " +
                     describe_time(data.test.unload_time) + "); each phase needs at least " +
                     std::to_string(minimum_phase_samples));
  }
  return data;
}

namespace {

// Least-squares rate of y = asymptote + amplitude exp(-rate tau), by
// Gauss-Newton in ln(rate) started from the half-life of the data.
double fit_exponential_rate(const std::vector<double>& tau, const std::vector<double>& y,
                            double asymptote, double amplitude) {
  double half_time = tau.back();
  for (std::size_t i = 0; i < tau.size(); ++i) {
    if ((y[i] - asymptote) / amplitude <= 0.5) {
      half_time = tau[i];
      break;
    }
  }
  const double shortest = *std::find_if(tau.begin(), tau.end(), [](double t) { return t > 0; });
  double log_rate = std::log(std::log(2.0) / std::max(half_time, shortest));
  std::vector<double> decay(tau.size());
  const auto compute_decay = [&](double rate) {
    for (std::size_t i = 0; i < tau.size(); ++i)
      decay[i] = rate * tau[i];
    exp_of_negative(decay.data(), decay.data(), decay.size());
  };
  const auto misfit = [&](double lr) {
    compute_decay(std::exp(lr));
    double sum = 0.0;
    for (std::size_t i = 0; i < tau.size(); ++i) {
      const double r = asymptote + amplitude * decay[i] - y[i];
      sum += r * r;
    }
    return sum;
  };
  double current = misfit(log_rate);
  for (int iteration = 0; iteration < 60; ++iteration) {
    const double rate = std::exp(log_rate);
    compute_decay(rate);
    double gradient = 0.0;
    double curvature = 0.0;
    for (std::size_t i = 0; i < tau.size(); ++i) {
      const double r = asymptote + amplitude * decay[i] - y[i];
      const double dr = -amplitude * tau[i] * rate * decay[i];
      gradient += r * dr;
      curvature += dr * dr;
    }
    if (curvature <= 0.0) break;
    double step = -gradient / curvature;
    double trial = misfit(log_rate + step);
    while (trial > current && std::abs(step) > 1e-12) {
      step *= 0.5;
      trial = misfit(log_rate + step);
    }
    if (trial > current) break;
    log_rate += step;
    current = trial;
    if (std::abs(step) < 1e-8) break;
  }
  return std::exp(log_rate);
}

} // namespace

ThesisEstimate thesis_estimate(const CreepTestData& data) {
  const PhaseRanges phases = phase_ranges(data);
  const auto& t = data.time;
  const auto& y = data.strain;
  const double sigma = data.test.tension;
  ThesisEstimate estimate;

  // Immediate elastic part: the jump at load application, read as the
  // intercept at the load time of a line through the first loaded samples.
  {
    const std::size_t b = phases.load_begin;
    double st = 0, sy = 0, stt = 0, sty = 0;
    const double n = 3.0;
    for (std::size_t i = b; i < b + 3; ++i) {
      const double dt = t[i] - data.test.load_time;
      st += dt;
      sy += y[i];
      stt += dt * dt;
      sty += dt * y[i];
    }
    const double denominator = n * stt - st * st;
    const double slope = denominator > 0.0 ? (n * sty - st * sy) / denominator : 0.0;
    estimate.immediate_strain = (sy - slope * st) / n;
  }
  if (!(estimate.immediate_strain > 0.0)) {
    throw InputError(data.path, data.line[phases.load_begin],
                     "no strain jump at load application (strain " +
                         format_number(estimate.immediate_strain) + " at " +
                         describe_time(data.test.load_time) + "); check --load-time");
  }

  const std::size_t loading = phases.load_end - phases.load_begin;
  const std::size_t recovery = phases.recovery_end - phases.load_end;
  const std::size_t end_window = std::clamp<std::size_t>(loading / 50, 1, 50);
  const std::size_t recovery_window = std::clamp<std::size_t>(recovery / 50, 1, 50);
  const double strain_at_unload = mean_of(y, phases.load_end - end_window, phases.load_end);
  estimate.nonelastic_at_unload = (1.0 + strain_at_unload) / (1.0 + estimate.immediate_strain) - 1;
  estimate.permanent_at_end =
      mean_of(y, phases.recovery_end - recovery_window, phases.recovery_end);
  if (!(estimate.nonelastic_at_unload > 0.0)) {
    throw InputError(data.path + ": no creep during loading (strain at the end of loading " +
                     format_number(strain_at_unload) + " is not above the immediate jump " +
                     format_number(estimate.immediate_strain) + ")");
  }

  CreepTestParameters& p = estimate.parameters;
  p.elastic_modulus = sigma / estimate.immediate_strain;
  p.alpha = estimate.permanent_at_end / estimate.nonelastic_at_unload;
  if (p.alpha <= 0.0 || p.alpha >= 1.0) {
    estimate.notes.push_back("permanent/total creep ratio " + format_number(p.alpha) +
                             " lies outside (0, 1); started the refinement from it clamped");
    p.alpha = std::clamp(p.alpha, 1e-3, 1.0 - 1e-3);
  }
  // The thesis assumes the loading reached saturation: eps_sat = creep at unload.
  p.creep_modulus = sigma / estimate.nonelastic_at_unload;

  std::vector<double> tau, z;
  for (std::size_t i = phases.load_begin; i < phases.load_end; ++i) {
    tau.push_back(t[i] - data.test.load_time);
    z.push_back((1.0 + y[i]) / (1.0 + estimate.immediate_strain) - 1.0);
  }
  const double saturation = estimate.nonelastic_at_unload;
  p.lambda_load = fit_exponential_rate(tau, z, saturation, -saturation);

  tau.clear();
  z.clear();
  for (std::size_t i = phases.load_end; i < phases.recovery_end; ++i) {
    tau.push_back(t[i] - data.test.unload_time);
    z.push_back(y[i]);
  }
  p.lambda_unload =
      fit_exponential_rate(tau, z, p.alpha * saturation, (1.0 - p.alpha) * saturation);
  return estimate;
}

namespace {

struct FitContext {
  const CreepTestData* data = nullptr;
  PetscInt begin = 0; // this rank's samples
  PetscInt end = 0;
  VecScatter to_all = nullptr;
  Vec everywhere = nullptr; // the fit variables, replicated
  // TAO asks for the residual and the Jacobian at the same points; both come
  // from one pass over the samples, kept for the last point asked.
  CreepTestVector cached_at{};
  bool cache_valid = false;
  std::vector<double> model;    // this rank's model strains
  std::vector<double> jacobian; // column-major, leading dimension end - begin
};

PetscErrorCode fit_variables_of(FitContext* context, Vec x, CreepTestVector* q) {
  const PetscScalar* values = nullptr;
  PetscFunctionBeginUser;
  PetscCall(
      VecScatterBegin(context->to_all, x, context->everywhere, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecScatterEnd(context->to_all, x, context->everywhere, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecGetArrayRead(context->everywhere, &values));
  std::copy(values, values + creep_test_parameter_count, q->begin());
  PetscCall(VecRestoreArrayRead(context->everywhere, &values));
  PetscFunctionReturn(0);
}

PetscErrorCode evaluate_model(FitContext* context, Vec x) {
  CreepTestVector q;
  PetscFunctionBeginUser;
  PetscCall(fit_variables_of(context, x, &q));
  if (context->cache_valid && q == context->cached_at) PetscFunctionReturn(0);
  const auto count = std::size_t(context->end - context->begin);
  context->model.resize(count);
  context->jacobian.resize(count * creep_test_parameter_count);
  evaluate_creep_test(context->data->test, from_fit_variables(q),
                      context->data->time.data() + context->begin, count, context->model.data(),
                      context->jacobian.data(), count);
  context->cached_at = q;
  context->cache_valid = true;
  PetscFunctionReturn(0);
}

PetscErrorCode evaluate_residual(Tao, Vec x, Vec residual, void* pointer) {
  auto* context = static_cast<FitContext*>(pointer);
  PetscScalar* r = nullptr;
  PetscFunctionBeginUser;
  PetscCall(evaluate_model(context, x));
  PetscCall(VecGetArray(residual, &r));
  const double* measured = context->data->strain.data() + context->begin;
  for (std::size_t i = 0; i < context->model.size(); ++i)
    r[i] = context->model[i] - measured[i];
  PetscCall(VecRestoreArray(residual, &r));
  PetscFunctionReturn(0);
}

PetscErrorCode evaluate_jacobian(Tao, Vec x, Mat jacobian, Mat, void* pointer) {
  auto* context = static_cast<FitContext*>(pointer);
  PetscScalar* entries = nullptr;
  PetscInt leading = 0;
  PetscFunctionBeginUser;
  PetscCall(evaluate_model(context, x));
  PetscCall(MatDenseGetLDA(jacobian, &leading));
  PetscCall(MatDenseGetArrayWrite(jacobian, &entries));
  const std::size_t count = context->model.size();
  for (std::size_t j = 0; j < creep_test_parameter_count; ++j) {
    std::copy_n(context->jacobian.data() + j * count, count, entries + j * std::size_t(leading));
  }
  PetscCall(MatDenseRestoreArrayWrite(jacobian, &entries));
  PetscCall(MatAssemblyBegin(jacobian, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(jacobian, MAT_FINAL_ASSEMBLY));
  PetscFunctionReturn(0);
}

// Sums over all samples of the quantities behind the statistics.
struct FitSums {
  Eigen::Matrix<double, creep_test_parameter_count, creep_test_parameter_count> normal;
  double squared_residual = 0.0;
  double strain = 0.0;
  double squared_strain = 0.0;
};

PetscErrorCode sum_statistics(MPI_Comm comm, FitContext* context, Vec x, FitSums* sums) {
  PetscFunctionBeginUser;
  PetscCall(evaluate_model(context, x));
  const std::size_t count = context->model.size();
  const double* measured = context->data->strain.data() + context->begin;
  const std::vector<double>& model = context->model;
  const std::vector<double>& jacobian = context->jacobian;
  constexpr std::size_t p = creep_test_parameter_count;
  double local[p * p + 3] = {};
  for (std::size_t a = 0; a < p; ++a) {
    for (std::size_t b = 0; b < p; ++b) {
      double sum = 0.0;
      for (std::size_t i = 0; i < count; ++i)
        sum += jacobian[a * count + i] * jacobian[b * count + i];
      local[a * p + b] = sum;
    }
  }
  for (std::size_t i = 0; i < count; ++i) {
    const double r = model[i] - measured[i];
    local[p * p] += r * r;
    local[p * p + 1] += measured[i];
    local[p * p + 2] += measured[i] * measured[i];
  }
  double global[p * p + 3];
  PetscCallMPI(MPIU_Allreduce(local, global, int(p * p + 3), MPI_DOUBLE, MPI_SUM, comm));
  for (std::size_t a = 0; a < p; ++a) {
    for (std::size_t b = 0; b < p; ++b)
      sums->normal(long(a), long(b)) = global[a * p + b];
  }
  sums->squared_residual = global[p * p];
  sums->strain = global[p * p + 1];
  sums->squared_strain = global[p * p + 2];
  PetscFunctionReturn(0);
}

void fill_statistics(const CreepTestData& data, const FitSums& sums, CreepFit* fit) {
  constexpr long p = long(creep_test_parameter_count);
  const long n = long(data.time.size());
  fit->samples = n;
  fit->degrees_of_freedom = n - p;
  const double variance = sums.squared_residual / double(fit->degrees_of_freedom);
  fit->residual_std = std::sqrt(variance);
  fit->rmse = std::sqrt(sums.squared_residual / double(n));
  const double total = sums.squared_strain - sums.strain * sums.strain / double(n);
  fit->r_squared = total > 0.0 ? 1.0 - sums.squared_residual / total : 0.0;

  // Covariance of the fit variables, then the delta method: for a parameter
  // fitted through its logarithm, se(value) = value * se(log value).
  const Eigen::Matrix<double, p, p> covariance =
      variance * sums.normal.completeOrthogonalDecomposition().pseudoInverse();
  const double t =
      student_t_quantile(0.5 + 0.5 * fit->confidence_level, double(fit->degrees_of_freedom));
  const CreepTestParameters& v = fit->parameters;
  const std::array<double, creep_test_parameter_count> values = {
      v.elastic_modulus, v.creep_modulus, v.alpha, v.lambda_load, v.lambda_unload};
  for (long j = 0; j < p; ++j) {
    const double q_error = std::sqrt(std::max(covariance(j, j), 0.0));
    ParameterEstimate& estimate = fit->estimates[std::size_t(j)];
    estimate.value = values[std::size_t(j)];
    const bool logarithmic = j != 2;
    estimate.std_error = logarithmic ? estimate.value * q_error : q_error;
    // Intervals are symmetric in the fit variable: positive parameters keep
    // positive limits.
    estimate.ci_low =
        logarithmic ? estimate.value * std::exp(-t * q_error) : estimate.value - t * q_error;
    estimate.ci_high =
        logarithmic ? estimate.value * std::exp(t * q_error) : estimate.value + t * q_error;
    for (long k = 0; k < p; ++k) {
      const double scale = std::sqrt(covariance(j, j) * covariance(k, k));
      fit->correlation[std::size_t(j)][std::size_t(k)] =
          scale > 0.0 ? covariance(j, k) / scale : 0.0;
    }
  }

  const double loading = data.test.unload_time - data.test.load_time;
  const double recovery = data.time.back() - data.test.unload_time;
  fit->loading_saturation = -std::expm1(-v.lambda_load * loading);
  fit->recovery_remaining = std::exp(-v.lambda_unload * recovery);
  fit->loading_saturated = fit->loading_saturation >= saturation_threshold;
  fit->recovery_relaxed = fit->recovery_remaining <= 1.0 - saturation_threshold;
  if (!fit->loading_saturated) {
    fit->warnings.push_back("the loading reached only " +
                            format_number(std::round(1000 * fit->loading_saturation) / 10) +
                            "% of saturation (lambda_load x loading time = " +
                            format_number(std::round(100 * v.lambda_load * loading) / 100) +
                            "): E and alpha rest on extrapolation of the creep curve (thesis App. "
                            "A) and are uncertain");
  }
  if (!fit->recovery_relaxed) {
    fit->warnings.push_back(
        "the recovery left " + format_number(std::round(1000 * fit->recovery_remaining) / 10) +
        "% of the viscoelastic strain (lambda_unload x recovery time = " +
        format_number(std::round(100 * v.lambda_unload * recovery) / 100) +
        "): alpha and lambda_unload rest on extrapolation (thesis App. A) and are uncertain");
  }
  for (long j = 0; j < p; ++j) {
    const ParameterEstimate& e = fit->estimates[std::size_t(j)];
    if (!(e.std_error < 0.5 * std::abs(e.value))) {
      fit->warnings.push_back(std::string(creep_test_parameter_names()[std::size_t(j)]) +
                              " is poorly determined by these data (standard error " +
                              format_number(e.std_error) + " for a value of " +
                              format_number(e.value) + ")");
    }
  }
}

} // namespace

PetscErrorCode fit_creep_test(MPI_Comm comm, const CreepTestData& data,
                              const CreepTestParameters& start, double confidence_level,
                              CreepFit* fit) {
  constexpr PetscInt p = PetscInt(creep_test_parameter_count);
  PetscMPIInt rank = 0;
  Tao tao = nullptr;
  Vec x = nullptr, lower = nullptr, upper = nullptr, residual = nullptr;
  Mat jacobian = nullptr;
  FitContext context;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  context.data = &data;
  fit->confidence_level = confidence_level;

  const PetscInt samples = PetscInt(data.time.size());
  PetscCall(VecCreateMPI(comm, PETSC_DECIDE, samples, &residual));
  PetscCall(VecGetOwnershipRange(residual, &context.begin, &context.end));
  PetscCall(VecCreateMPI(comm, rank == 0 ? p : 0, p, &x));
  PetscCall(VecDuplicate(x, &lower));
  PetscCall(VecDuplicate(x, &upper));
  PetscCall(MatCreateDense(comm, context.end - context.begin, rank == 0 ? p : 0, samples, p,
                           nullptr, &jacobian));
  PetscCall(VecScatterCreateToAll(x, &context.to_all, &context.everywhere));

  if (rank == 0) {
    const CreepTestVector q0 = to_fit_variables(start);
    for (PetscInt j = 0; j < p; ++j) {
      PetscCall(VecSetValue(x, j, q0[std::size_t(j)], INSERT_VALUES));
      // alpha lies in [0, 1]; the logarithms stay within a factor e^20 of the
      // start, which keeps trial steps from overflowing exp().
      const double q = q0[std::size_t(j)];
      PetscCall(VecSetValue(lower, j, j == 2 ? 0.0 : q - log_parameter_range, INSERT_VALUES));
      PetscCall(VecSetValue(upper, j, j == 2 ? 1.0 : q + log_parameter_range, INSERT_VALUES));
    }
  }
  for (Vec v : {x, lower, upper}) {
    PetscCall(VecAssemblyBegin(v));
    PetscCall(VecAssemblyEnd(v));
  }

  PetscCall(TaoCreate(comm, &tao));
  PetscCall(TaoSetOptionsPrefix(tao, "fit_"));
  PetscCall(TaoSetType(tao, TAOBRGN));
  PetscCall(TaoSetSolution(tao, x));
  PetscCall(TaoSetVariableBounds(tao, lower, upper));
  PetscCall(TaoSetResidualRoutine(tao, residual, evaluate_residual, &context));
  PetscCall(TaoSetJacobianResidualRoutine(tao, jacobian, jacobian, evaluate_jacobian, &context));
  // Relative to the misfit (noisy data) or to the first gradient (exact data);
  // the absolute gradient floors at round-off, which depends on the data.
  PetscCall(TaoSetTolerances(tao, 0.0, 1e-9, 1e-10));
  PetscCall(TaoSetMaximumIterations(tao, 200));
  // Exact data: stop once the misfit is round-off of the data themselves.
  double largest_strain = 0.0;
  for (double y : data.strain)
    largest_strain = std::max(largest_strain, std::abs(y));
  const double round_off = 1e-14 * largest_strain;
  const double misfit_floor = 0.5 * double(samples) * round_off * round_off;
  PetscCall(TaoSetFunctionLowerBound(tao, misfit_floor));
  // Levenberg-Marquardt damping: the default proximal term stalls the
  // line search near the optimum. With five unknowns, forming J^T J beats a
  // matrix-free Hessian by far.
  PetscCall(set_default_option("-fit_tao_brgn_regularization_type", "lm"));
  PetscCall(set_default_option("-fit_tao_brgn_mat_explicit", "true"));
  PetscCall(TaoSetFromOptions(tao));
  PetscBool is_brgn = PETSC_FALSE;
  PetscCall(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(tao), TAOBRGN, &is_brgn));
  if (is_brgn) {
    Tao subsolver = nullptr;
    PetscCall(TaoBRGNGetSubsolver(tao, &subsolver));
    PetscCall(TaoSetFunctionLowerBound(subsolver, misfit_floor));
  }
  PetscCall(TaoSolve(tao));

  TaoConvergedReason reason;
  PetscInt iterations = 0;
  TaoType type = nullptr;
  PetscCall(TaoGetConvergedReason(tao, &reason));
  PetscCall(TaoGetIterationNumber(tao, &iterations));
  PetscCall(TaoGetType(tao, &type));
  fit->converged = reason > 0;
  fit->converged_reason = TaoConvergedReasons[reason];
  fit->iterations = iterations;
  fit->solver = type;

  CreepTestVector solution;
  PetscCall(fit_variables_of(&context, x, &solution));
  fit->parameters = from_fit_variables(solution);
  FitSums sums;
  PetscCall(sum_statistics(comm, &context, x, &sums));
  PetscCallCXX(fill_statistics(data, sums, fit));

  PetscCall(TaoDestroy(&tao));
  PetscCall(VecScatterDestroy(&context.to_all));
  PetscCall(VecDestroy(&context.everywhere));
  PetscCall(MatDestroy(&jacobian));
  PetscCall(VecDestroy(&residual));
  PetscCall(VecDestroy(&lower));
  PetscCall(VecDestroy(&upper));
  PetscCall(VecDestroy(&x));
  PetscFunctionReturn(0);
}

} // namespace sartor
