#include "solvers/creep_fit.hpp"

#include "common/csv.hpp"
#include "common/error.hpp"
#include "common/statistics.hpp"
#include "common/vector_math.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numeric>
#include <random>
#include <stdexcept>

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

// Half the peak tension is first reached at load_time and last left at
// unload_time (interpolated between knots); a load never removed ends at
// `end_time`.
CreepTest equivalent_step(const LoadHistory& history, double end_time) {
  double peak = 0.0;
  for (const LoadKnot& k : history)
    peak = std::max(peak, k.tension);
  const double half = 0.5 * peak;
  CreepTest step{peak, history.front().time, end_time};
  bool loaded = history.front().tension >= half;
  for (std::size_t k = 1; k < history.size(); ++k) {
    const LoadKnot& a = history[k - 1];
    const LoadKnot& b = history[k];
    const auto crossing = [&] {
      return a.time + (half - a.tension) / (b.tension - a.tension) * (b.time - a.time);
    };
    if (!loaded && a.tension < half && b.tension >= half) {
      step.load_time = crossing();
      loaded = true;
    }
    if (a.tension >= half && b.tension < half) step.unload_time = crossing();
  }
  return step;
}

void settle_history(CreepTestData& data, const std::string& origin) {
  data.test = equivalent_step(data.history, data.time.back());
  if (!(data.test.tension > 0.0)) {
    throw InputError(data.path + ": the load history (" + origin + ") is never positive");
  }
  data.tension_origin = origin;
  data.load_time_origin = "first rise to half the peak tension of the load history";
  data.unload_time_origin = "last fall from half the peak tension of the load history";
}

void use_column_as_history(CreepTestData& data, const CsvTable& table, std::size_t column,
                           double scale, const std::string& what, bool values_are_tension) {
  if (!values_are_tension) {
    throw InputError(data.path + ": the " + what +
                     " column varies during loading (a ramp, several levels or cycles); give "
                     "--width (m) so that it becomes the load history");
  }
  if (!data.tension_origin.empty() || !data.load_time_origin.empty() ||
      !data.unload_time_origin.empty()) {
    throw InputError(data.path + ": the " + what +
                     " column varies during loading and is used as the load history; "
                     "--tension, --force, --load-time and --unload-time do not apply");
  }
  data.history.clear();
  for (std::size_t i = 0; i < table.columns[column].size(); ++i)
    data.history.push_back({data.time[i], table.columns[column][i] * scale});
  settle_history(data, "the " + what + " column, piecewise linear between samples");
}

void settle_times_from_tension(CreepTestData& data, const CsvTable& table, std::size_t column,
                               double scale, const std::string& what, bool values_are_tension) {
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
  for (double v : loaded)
    worst = std::max(worst, std::abs(v - mean));
  const bool reloaded = std::any_of(values.begin() + long(off), values.end(),
                                    [&](double v) { return v * scale >= 0.5 * peak; });
  // Ramps, several levels or cycles: the column is the load history.
  if (worst > 0.05 * mean || reloaded) {
    use_column_as_history(data, table, column, scale, what, values_are_tension);
    return;
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

// Column names with units, as instrument exports write them: "time (s)",
// "strain [%]", "force (kgf)"; also Sartor's own time_s, force_N,
// tension_N_per_m. A quantity's units map to factors to SI (s, strain, m, N,
// N/m).
struct Quantity {
  std::vector<std::string> names;
  std::vector<std::pair<std::string, double>> units; // "" = the name alone
  std::string meaning;
};

const Quantity time_quantity{{"time"},
                             {{"", 1.0},
                              {"s", 1.0},
                              {"sec", 1.0},
                              {"ms", 1e-3},
                              {"min", 60.0},
                              {"h", 3600.0},
                              {"hr", 3600.0}},
                             "time (s, ms, min, h)"};
const Quantity strain_quantity{{"strain", "strain_total"},
                               {{"", 1.0}, {"-", 1.0}, {"mm/mm", 1.0}, {"m/m", 1.0}, {"%", 0.01}},
                               "elongation over the rest length (fraction or %)"};
const Quantity extension_quantity{{"extension", "elongation", "displacement"},
                                  {{"mm", 1e-3}, {"cm", 1e-2}, {"m", 1.0}},
                                  "extension of the gauge length (mm, cm, m)"};
const Quantity tension_quantity{
    {"tension"}, {{"", 1.0}, {"n/m", 1.0}, {"n/mm", 1e3}, {"n/cm", 1e2}, {"kn/m", 1e3}}, "N/m"};
const Quantity force_quantity{
    {"force", "load"},
    {{"", 1.0}, {"n", 1.0}, {"kn", 1e3}, {"kgf", 9.80665}, {"lbf", 4.4482216152605}},
    "N"};

struct NamedUnit {
  std::string name, unit;
};

NamedUnit split_column_name(const std::string& column) {
  for (const auto& [legacy, split] :
       std::vector<std::pair<std::string, NamedUnit>>{{"time_s", {"time", "s"}},
                                                      {"force_n", {"force", "n"}},
                                                      {"tension_n_per_m", {"tension", "n/m"}}}) {
    if (column == legacy) return split;
  }
  const char close = column.empty() ? ' ' : column.back();
  const auto open = column.find_last_of(close == ')' ? '(' : '[');
  if ((close == ')' || close == ']') && open != std::string::npos) {
    const auto trimmed = [](std::string text) {
      text.erase(0, text.find_first_not_of(' '));
      text.erase(text.find_last_not_of(' ') + 1);
      return text;
    };
    return {trimmed(column.substr(0, open)),
            trimmed(column.substr(open + 1, column.size() - open - 2))};
  }
  return {column, ""};
}

// The column of `quantity` and its factor to SI; throws on a unit it does not know.
std::optional<std::pair<std::size_t, double>> find_quantity(const CsvTable& table,
                                                            const Quantity& quantity) {
  for (std::size_t c = 0; c < table.names.size(); ++c) {
    const NamedUnit column = split_column_name(table.names[c]);
    if (std::find(quantity.names.begin(), quantity.names.end(), column.name) ==
        quantity.names.end()) {
      continue;
    }
    // A bare name where a unit is needed (an extension) is some other column.
    if (column.unit.empty() && quantity.units.front().first != "") continue;
    std::string known;
    for (const auto& [unit, factor] : quantity.units) {
      if (unit == column.unit) return std::make_pair(c, factor);
      if (!unit.empty()) known += (known.empty() ? "" : ", ") + unit;
    }
    throw InputError(table.path, table.header_line,
                     "column '" + table.names[c] + "': unknown unit '" + column.unit + "' for " +
                         column.name + " (known: " + known + ")");
  }
  return std::nullopt;
}

// Time and strain in SI, from a strain column or an extension column over
// --gauge-length.
void read_time_and_strain(const CsvTable& table, const CreepTestDescription& given,
                          CreepTestData& data) {
  const auto time = find_quantity(table, time_quantity);
  if (!time) table.require({"time_s", "time"}, "time in s");
  require_nondecreasing(table, time->first);
  data.time = table.columns[time->first];
  for (double& t : data.time)
    t *= time->second;
  if (const auto strain = find_quantity(table, strain_quantity)) {
    data.strain = table.columns[strain->first];
    for (double& e : data.strain)
      e *= strain->second;
  } else if (const auto extension = find_quantity(table, extension_quantity)) {
    if (!given.gauge_length) {
      throw InputError(table.path, table.header_line,
                       "column '" + table.names[extension->first] +
                           "' is an extension: give --gauge-length (m) to turn it into strain");
    }
    data.strain = table.columns[extension->first];
    for (double& e : data.strain)
      e *= extension->second / *given.gauge_length;
  } else {
    table.require({"strain", "strain_total"}, "elongation over the rest length");
  }
  data.line = table.lines;
}

// --load-history FILE: time and tension (or force over --width) knots.
void read_load_history(const std::string& path, const CreepTestDescription& given,
                       CreepTestData& data) {
  if (given.tension || given.force || given.load_time || given.unload_time) {
    throw InputError("--load-history " + path +
                     " gives the load; --tension, --force, --load-time and --unload-time do "
                     "not apply");
  }
  data.history = read_load_history_file(path, given.width);
  settle_history(data, "--load-history " + path + ", piecewise linear between its rows");
}

} // namespace

LoadHistory read_load_history_file(const std::string& path, std::optional<double> width) {
  const CsvTable table = read_csv(path);
  const auto time = find_quantity(table, time_quantity);
  if (!time) table.require({"time_s", "time"}, "time in s");
  require_nondecreasing(table, time->first);
  double scale = 1.0;
  auto load = find_quantity(table, tension_quantity);
  if (!load) {
    load = find_quantity(table, force_quantity);
    if (!load) table.require({"tension_N_per_m", "force_N"}, "the load");
    if (!width) {
      throw InputError(path + ": the force column needs --width (m), the specimen width");
    }
    scale = 1.0 / *width;
  }
  LoadHistory history;
  for (std::size_t i = 0; i < table.columns[time->first].size(); ++i) {
    history.push_back({table.columns[time->first][i] * time->second,
                       table.columns[load->first][i] * load->second * scale});
  }
  if (history.empty()) throw InputError(path + ": the load history has no rows");
  return history;
}

CreepTestData read_creep_test_data(const std::string& path, const CreepTestDescription& given) {
  const CsvTable table = read_csv(path);
  CreepTestData data;
  data.path = path;
  read_time_and_strain(table, given, data);
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

  const auto tension_column = find_quantity(table, tension_quantity);
  const auto force_column = find_quantity(table, force_quantity);
  if (given.load_history) {
    if (tension_column || force_column) {
      throw InputError(path + ": has a " + (tension_column ? "tension" : "force") +
                       " column, and --load-history gives the load too; give one of them");
    }
    read_load_history(*given.load_history, given, data);
  } else if (const auto column = tension_column) {
    settle_times_from_tension(data, table, column->first, column->second, "tension", true);
  } else if (const auto force = force_column) {
    if (!given.width && !given.tension) {
      throw InputError(path + ": the force column needs --width (m), the specimen width");
    }
    // With --tension the column only tells when the load was on.
    const double to_tension = force->second / (given.width ? *given.width : 1.0);
    settle_times_from_tension(data, table, force->first, to_tension, "force / width",
                              given.width.has_value());
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
  // A history is fitted as a whole; the phases are those of a step test.
  if (!data.history.empty()) return data;
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
  // intercept at the load time of a line through the first loaded samples:
  // those in the first 1e-4 of the loading, and at least three. (Three
  // samples alone are too close together on log-spaced data: the line's
  // slope is then noise.)
  {
    const std::size_t b = phases.load_begin;
    const double window = 1e-4 * (data.test.unload_time - data.test.load_time);
    std::size_t e = b + 3;
    while (e < phases.load_end && t[e] - data.test.load_time <= window)
      ++e;
    double st = 0, sy = 0, stt = 0, sty = 0;
    const double n = double(e - b);
    for (std::size_t i = b; i < e; ++i) {
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

  // The plateaus: the last samples of each phase, at most 50 and within its
  // last 2% (log-spaced data have few samples there).
  const auto samples_in_last = [&t](std::size_t begin, std::size_t end, double from) {
    const std::size_t count = std::clamp<std::size_t>((end - begin) / 50, 1, 50);
    std::size_t first = end - count;
    while (first < end - 1 && t[first] < from)
      ++first;
    return end - first;
  };
  const double load_duration = data.test.unload_time - data.test.load_time;
  const std::size_t end_window = samples_in_last(phases.load_begin, phases.load_end,
                                                 data.test.unload_time - 0.02 * load_duration);
  const std::size_t recovery_window = samples_in_last(
      phases.load_end, phases.recovery_end, t.back() - 0.02 * (t.back() - data.test.unload_time));
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

CreepTestData combine_tests(const std::vector<CreepTestData>& tests) {
  if (tests.empty()) throw std::logic_error("combine_tests: no tests");
  CreepTestData combined;
  for (const CreepTestData& test : tests) {
    if (!test.segments.empty()) throw std::logic_error("combine_tests: nested combination");
    combined.path += (combined.path.empty() ? "" : " + ") + test.path;
    LoadSegment segment{combined.time.size(), combined.time.size() + test.time.size(),
                        test.history};
    if (segment.history.empty()) {
      const CreepTest& step = test.test;
      segment.history = {{step.load_time, 0.0},
                         {step.load_time, step.tension},
                         {step.unload_time, step.tension},
                         {step.unload_time, 0.0}};
    }
    combined.segments.push_back(segment);
    combined.time.insert(combined.time.end(), test.time.begin(), test.time.end());
    combined.strain.insert(combined.strain.end(), test.strain.begin(), test.strain.end());
    combined.line.insert(combined.line.end(), test.line.begin(), test.line.end());
  }
  combined.test = tests.front().test;
  combined.tension_origin = "each test's own load";
  combined.load_time_origin = combined.unload_time_origin = "the first test's";
  return combined;
}

namespace {

// The tests of `data`: its segments, or the whole data under its history.
std::vector<LoadSegment> segments_of(const CreepTestData& data) {
  if (!data.segments.empty()) return data.segments;
  return {{0, data.time.size(), data.history}};
}

} // namespace

void evaluate_model(const CreepTestData& data, const CreepTestParameters& p, std::size_t begin,
                    std::size_t end, double* strain, double* jacobian,
                    std::size_t leading_dimension) {
  if (!data.segments.empty()) {
    for (const LoadSegment& segment : data.segments) {
      const std::size_t first = std::max(begin, segment.begin);
      const std::size_t last = std::min(end, segment.end);
      if (first >= last) continue;
      const std::size_t offset = first - begin;
      evaluate_load_history(segment.history, p, data.time.data() + segment.begin,
                            last - segment.begin, first - segment.begin, strain + offset,
                            jacobian ? jacobian + offset : nullptr, leading_dimension);
    }
    return;
  }
  if (data.history.empty()) {
    evaluate_creep_test(data.test, p, data.time.data() + begin, end - begin, strain, jacobian,
                        leading_dimension);
  } else {
    evaluate_load_history(data.history, p, data.time.data(), end, begin, strain, jacobian,
                          leading_dimension);
  }
}

namespace {

// The grid of the history start: rates from 0.1 / span to 1e4 / span, three
// per decade; a coarse grid is enough, the refinement works in ln(lambda).
constexpr int start_grid_points = 16;
constexpr double start_grid_points_per_decade = 3.0;
// The linear fits of the grid use at most about this many samples.
constexpr std::size_t start_grid_samples = 500;

struct GridPoint {
  double misfit = std::numeric_limits<double>::infinity();
  double lambda_load = 0.0, lambda_unload = 0.0;
  Eigen::Vector3d amplitudes = Eigen::Vector3d::Zero(); // 1/K, (1 - alpha)/E, alpha/E
};

// The (thinned) samples of one test.
struct GridSamples {
  const LoadHistory* history;
  std::vector<double> times, strain;
  UnitCreep unit;
};

GridPoint linear_fit_at(std::vector<GridSamples>& tests, double lambda_load, double lambda_unload) {
  Eigen::Matrix3d normal = Eigen::Matrix3d::Zero();
  Eigen::Vector3d right = Eigen::Vector3d::Zero();
  for (GridSamples& test : tests) {
    unit_creep(*test.history, lambda_load, lambda_unload, test.times.data(), test.times.size(), 0,
               &test.unit);
    for (std::size_t i = 0; i < test.times.size(); ++i) {
      const Eigen::Vector3d row(test.unit.tension[i], test.unit.viscoelastic[i],
                                test.unit.permanent[i]);
      normal += row * row.transpose();
      right += row * test.strain[i];
    }
  }
  GridPoint point;
  point.lambda_load = lambda_load;
  point.lambda_unload = lambda_unload;
  point.amplitudes = normal.completeOrthogonalDecomposition().solve(right);
  const Eigen::Vector3d& c = point.amplitudes;
  if (!(c(0) > 0.0 && c(1) + c(2) > 0.0)) return point; // no physical start here
  double misfit = 0.0;
  for (const GridSamples& test : tests) {
    const UnitCreep& unit = test.unit;
    for (std::size_t i = 0; i < test.times.size(); ++i) {
      const double r = c(0) * unit.tension[i] + c(1) * unit.viscoelastic[i] +
                       c(2) * unit.permanent[i] - test.strain[i];
      misfit += r * r;
    }
  }
  point.misfit = misfit;
  return point;
}

ThesisEstimate history_start(const CreepTestData& data) {
  const std::size_t stride = std::max<std::size_t>(1, data.time.size() / start_grid_samples);
  const std::vector<LoadSegment> segments = segments_of(data);
  std::vector<GridSamples> tests;
  double span = 0.0;
  for (const LoadSegment& segment : segments) {
    GridSamples test{&segment.history, {}, {}, {}};
    for (std::size_t i = segment.begin; i < segment.end; i += stride) {
      test.times.push_back(data.time[i]);
      test.strain.push_back(data.strain[i]);
    }
    span = std::max(span, data.time[segment.end - 1] -
                              std::min(data.time[segment.begin], segment.history.front().time));
    tests.push_back(std::move(test));
  }
  const auto rate = [span](int k) {
    return 0.1 / span * std::pow(10.0, double(k) / start_grid_points_per_decade);
  };
  GridPoint best;
  for (int k = 0; k < start_grid_points; ++k) {
    for (int l = 0; l < start_grid_points; ++l) {
      const GridPoint point = linear_fit_at(tests, rate(k), rate(l));
      if (point.misfit < best.misfit) best = point;
    }
  }
  if (!std::isfinite(best.misfit)) {
    throw InputError(data.path + ": no start for the fit: on no rates of the grid do the data "
                                 "show a positive immediate and creep strain");
  }
  const Eigen::Vector3d& c = best.amplitudes;
  ThesisEstimate estimate;
  CreepTestParameters& p = estimate.parameters;
  p.elastic_modulus = 1.0 / c(0);
  p.creep_modulus = 1.0 / (c(1) + c(2));
  p.alpha = std::clamp(c(2) / (c(1) + c(2)), 1e-3, 1.0 - 1e-3);
  p.lambda_load = best.lambda_load;
  p.lambda_unload = best.lambda_unload;
  estimate.notes.push_back("load history: the start is the best of linear fits on a " +
                           std::to_string(start_grid_points) + " x " +
                           std::to_string(start_grid_points) +
                           " grid of (lambda_load, lambda_unload) from " + format_number(rate(0)) +
                           " to " + format_number(rate(start_grid_points - 1)) + " 1/s");
  return estimate;
}

} // namespace

ThesisEstimate start_estimate(const CreepTestData& data) {
  return data.history.empty() && data.segments.empty() ? thesis_estimate(data)
                                                       : history_start(data);
}

namespace {

constexpr std::size_t parameter_count = creep_test_parameter_count;
using NormalMatrix = Eigen::Matrix<double, long(parameter_count), long(parameter_count)>;
using ParameterVector = Eigen::Matrix<double, long(parameter_count), 1>;

// This rank's block of the samples and the model evaluated there.
struct SampleShare {
  const CreepTestData* data = nullptr;
  std::size_t begin = 0;
  std::size_t end = 0;
  std::vector<double> model;      // model strains
  std::vector<double> jacobian;   // column-major, leading dimension end - begin
  CreepTestVector evaluated_at{}; // where model and jacobian were computed
};

// Sums over all ranks' samples at one point of the fit variables.
struct FitSums {
  NormalMatrix normal = NormalMatrix::Zero();         // J^T J
  ParameterVector gradient = ParameterVector::Zero(); // J^T r (half the gradient of the RSS)
  double squared_residual = 0.0;
  double strain = 0.0;
  double squared_strain = 0.0;
};

PetscErrorCode sum_at(MPI_Comm comm, SampleShare* share, const CreepTestVector& q, FitSums* sums) {
  PetscFunctionBeginUser;
  const std::size_t count = share->end - share->begin;
  share->model.resize(count);
  share->jacobian.resize(count * parameter_count);
  evaluate_model(*share->data, from_fit_variables(q), share->begin, share->end, share->model.data(),
                 share->jacobian.data(), count);
  share->evaluated_at = q;
  const Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, long(parameter_count)>> jacobian(
      share->jacobian.data(), long(count), long(parameter_count));
  const Eigen::Map<const Eigen::VectorXd> model(share->model.data(), long(count));
  const Eigen::Map<const Eigen::VectorXd> measured(share->data->strain.data() + share->begin,
                                                   long(count));
  const Eigen::VectorXd residual = model - measured;
  constexpr std::size_t p = parameter_count;
  std::array<double, p * p + p + 3> local{};
  Eigen::Map<NormalMatrix>(local.data()) = jacobian.transpose() * jacobian;
  Eigen::Map<ParameterVector>(local.data() + p * p) = jacobian.transpose() * residual;
  local[p * p + p] = residual.squaredNorm();
  local[p * p + p + 1] = measured.sum();
  local[p * p + p + 2] = measured.squaredNorm();
  std::array<double, p * p + p + 3> global{};
  PetscCallMPI(
      MPIU_Allreduce(local.data(), global.data(), int(global.size()), MPI_DOUBLE, MPI_SUM, comm));
  sums->normal = Eigen::Map<const NormalMatrix>(global.data());
  sums->gradient = Eigen::Map<const ParameterVector>(global.data() + p * p);
  sums->squared_residual = global[p * p + p];
  sums->strain = global[p * p + p + 1];
  sums->squared_strain = global[p * p + p + 2];
  PetscFunctionReturn(0);
}

// The fit variables stay in their domain: alpha in [0, 1], the logarithms
// within a factor e^20 of the start (which keeps exp() finite).
CreepTestVector kept_in_bounds(CreepTestVector q, const CreepTestVector& start) {
  for (std::size_t j = 0; j < parameter_count; ++j) {
    q[j] = j == 2
               ? std::clamp(q[j], 0.0, 1.0)
               : std::clamp(q[j], start[j] - log_parameter_range, start[j] + log_parameter_range);
  }
  return q;
}

// The Gauss-Newton step from the point of `sums` and its length in standard
// errors: sqrt(step^T J^T J step / s^2), with s^2 = RSS / dof. This is the
// distance to the optimum of the linearised problem in the units the
// confidence intervals are drawn in.
struct GaussNewtonStep {
  ParameterVector step;
  double standard_errors = 0.0;
};

GaussNewtonStep gauss_newton_step(const FitSums& sums, double degrees_of_freedom) {
  GaussNewtonStep gn;
  gn.step = -sums.normal.completeOrthogonalDecomposition().solve(sums.gradient);
  const double variance = sums.squared_residual / degrees_of_freedom;
  const double length = std::max(0.0, -sums.gradient.dot(gn.step));
  gn.standard_errors = variance > 0.0 ? std::sqrt(length / variance) : 0.0;
  return gn;
}

CreepTestVector moved(const CreepTestVector& q, const ParameterVector& step,
                      const CreepTestVector& start) {
  CreepTestVector trial = q;
  for (std::size_t j = 0; j < parameter_count; ++j)
    trial[j] += step(long(j));
  return kept_in_bounds(trial, start);
}

constexpr double converged_step_standard_errors = 1e-4;
constexpr double certified_step_standard_errors = 1e-3;
constexpr double negligible_descent_of_variance = 1e-6;
constexpr long maximum_iterations = 200;
// The lag-1 autocorrelation of independent noise scatters by 1/sqrt(n):
// beyond 3 of that, the residuals are taken as correlated.
constexpr double autocorrelation_z_threshold = 3.0;

struct Solution {
  CreepTestVector q{};
  FitSums sums;
  long iterations = 0;
  bool converged = false;
  std::string reason;
};

// Levenberg-Marquardt with Moré's column scaling (the damping acts on J D^-1,
// D = the running maximum of the columns' norms) and Nielsen's damping update.
// It stops when the misfit reaches the data's round-off, when the remaining
// Gauss-Newton step is below 1e-4 standard errors, or when an accepted step
// changes neither the misfit (relative 1e-14) nor any variable (1e-10).
PetscErrorCode levenberg_marquardt(MPI_Comm comm, SampleShare* share, const CreepTestVector& start,
                                   double misfit_floor, Solution* solution) {
  PetscFunctionBeginUser;
  const double dof = double(share->data->time.size()) - double(parameter_count);
  solution->q = start;
  PetscCall(sum_at(comm, share, solution->q, &solution->sums));
  ParameterVector scale = ParameterVector::Constant(std::numeric_limits<double>::min());
  double damping = 1e-3, growth = 2.0;
  for (long iteration = 0; iteration < maximum_iterations; ++iteration) {
    const FitSums& current = solution->sums;
    solution->iterations = iteration;
    if (current.squared_residual <= misfit_floor) {
      solution->converged = true;
      solution->reason = "misfit at the round-off of the data";
      PetscFunctionReturn(0);
    }
    if (gauss_newton_step(current, dof).standard_errors < converged_step_standard_errors) {
      solution->converged = true;
      solution->reason = "Gauss-Newton step below 1e-4 standard errors";
      PetscFunctionReturn(0);
    }
    scale = scale.cwiseMax(current.normal.diagonal().cwiseSqrt());
    const NormalMatrix scaled =
        scale.cwiseInverse().asDiagonal() * current.normal * scale.cwiseInverse().asDiagonal();
    const ParameterVector scaled_step =
        -(scaled + damping * NormalMatrix::Identity())
             .ldlt()
             .solve(scale.cwiseInverse().cwiseProduct(current.gradient));
    const CreepTestVector trial =
        moved(solution->q, scale.cwiseInverse().cwiseProduct(scaled_step), start);
    ParameterVector step;
    for (std::size_t j = 0; j < parameter_count; ++j)
      step(long(j)) = trial[j] - solution->q[j];
    const double predicted = -(2.0 * current.gradient.dot(step) + step.dot(current.normal * step));
    FitSums at_trial;
    PetscCall(sum_at(comm, share, trial, &at_trial));
    const double reduction = current.squared_residual - at_trial.squared_residual;
    if (!(reduction > 0.0)) { // also rejects a NaN misfit
      damping *= growth;
      growth *= 2.0;
      if (damping > 1e16) {
        solution->reason = "no damped step reduces the misfit";
        PetscFunctionReturn(0);
      }
      continue;
    }
    const double ratio = predicted > 0.0 ? reduction / predicted : 0.0;
    damping *= std::max(1.0 / 3.0, 1.0 - std::pow(2.0 * ratio - 1.0, 3));
    growth = 2.0;
    const bool stalled =
        reduction < 1e-14 * current.squared_residual && step.lpNorm<Eigen::Infinity>() < 1e-10;
    solution->q = trial;
    solution->sums = at_trial;
    if (stalled) {
      solution->converged = true;
      solution->reason = "step and relative reduction below 1e-10 and 1e-14";
      PetscFunctionReturn(0);
    }
  }
  solution->iterations = maximum_iterations;
  solution->reason = "iteration limit (200)";
  PetscFunctionReturn(0);
}

// After the iterations: the full Gauss-Newton step from the solution must be
// short (in standard errors) and, taken, must not lower the misfit by more
// than a millionth of the noise variance. A step that does lower it is kept.
PetscErrorCode certify_optimum(MPI_Comm comm, SampleShare* share, const CreepTestVector& start,
                               double misfit_floor, Solution* solution, CreepFit* fit) {
  PetscFunctionBeginUser;
  if (solution->sums.squared_residual <= misfit_floor) {
    fit->optimum_certified = true;
    fit->certification = "the misfit is at the round-off of the data (exact data)";
    PetscFunctionReturn(0);
  }
  const double dof = double(share->data->time.size()) - double(parameter_count);
  const double variance = solution->sums.squared_residual / dof;
  const GaussNewtonStep gn = gauss_newton_step(solution->sums, dof);
  FitSums at_step;
  const CreepTestVector stepped = moved(solution->q, gn.step, start);
  PetscCall(sum_at(comm, share, stepped, &at_step));
  const double descent = solution->sums.squared_residual - at_step.squared_residual;
  fit->certificate_step_standard_errors = gn.standard_errors;
  fit->certificate_descent_over_variance = descent / variance;
  fit->optimum_certified = gn.standard_errors < certified_step_standard_errors &&
                           descent < negligible_descent_of_variance * variance;
  if (descent > 0.0) {
    solution->q = stepped;
    solution->sums = at_step;
  }
  char text[300];
  std::snprintf(text, sizeof text,
                "a final Gauss-Newton step of %.2g standard errors changes the misfit by %.2g of "
                "the residual variance (certified when below %g standard errors and a descent "
                "below %g)",
                gn.standard_errors, -descent / variance, certified_step_standard_errors,
                negligible_descent_of_variance);
  fit->certification = text;
  PetscFunctionReturn(0);
}

// Lag-1 autocorrelation of the residuals in time order. Each rank's block
// needs the first residual of the next rank's block.
PetscErrorCode residual_autocorrelation(MPI_Comm comm, const SampleShare& share, double rss,
                                        ResidualAutocorrelation* result) {
  PetscMPIInt rank = 0, size = 1;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCallMPI(MPI_Comm_size(comm, &size));
  const std::size_t count = share.end - share.begin;
  const double* measured = share.data->strain.data() + share.begin;
  const auto residual = [&](std::size_t i) { return share.model[i] - measured[i]; };
  double first = count > 0 ? residual(0) : 0.0, next_first = 0.0;
  const PetscMPIInt previous = rank > 0 ? rank - 1 : MPI_PROC_NULL;
  const PetscMPIInt next = rank + 1 < size ? rank + 1 : MPI_PROC_NULL;
  PetscCallMPI(MPI_Sendrecv(&first, 1, MPI_DOUBLE, previous, 0, &next_first, 1, MPI_DOUBLE, next, 0,
                            comm, MPI_STATUS_IGNORE));
  double local = 0.0;
  for (std::size_t i = 0; i + 1 < count; ++i)
    local += residual(i) * residual(i + 1);
  if (count > 0 && next != MPI_PROC_NULL) local += residual(count - 1) * next_first;
  double lagged = 0.0;
  PetscCallMPI(MPIU_Allreduce(&local, &lagged, 1, MPI_DOUBLE, MPI_SUM, comm));
  const double n = double(share.data->time.size());
  result->lag1 = rss > 0.0 ? lagged / rss : 0.0;
  result->z_score = result->lag1 * std::sqrt(n);
  result->durbin_watson = 2.0 * (1.0 - result->lag1);
  result->present = result->z_score > autocorrelation_z_threshold;
  result->variance_inflation =
      result->present ? (1.0 + result->lag1) / std::max(1.0 - result->lag1, 1e-3) : 1.0;
  result->effective_samples = n / result->variance_inflation;
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
  // Autocorrelated residuals (AR(1) with lag-1 correlation rho) carry the
  // information of n (1 - rho) / (1 + rho) independent samples: the
  // covariance grows by the inverse of that ratio.
  const ResidualAutocorrelation& correlated = fit->autocorrelation;
  const Eigen::Matrix<double, p, p> covariance =
      correlated.variance_inflation * variance *
      sums.normal.completeOrthogonalDecomposition().pseudoInverse();
  const double t = student_t_quantile(0.5 + 0.5 * fit->confidence_level,
                                      std::max(correlated.effective_samples - double(p), 1.0));
  fit->t_quantile = t;
  if (correlated.present) {
    fit->warnings.push_back(
        "the residuals are autocorrelated (lag-1 correlation " +
        format_number(std::round(1000 * correlated.lag1) / 1000) + ", " +
        format_number(std::round(correlated.z_score)) +
        " times its spread for independent noise): the intervals are widened by " +
        format_number(std::round(100 * std::sqrt(correlated.variance_inflation)) / 100) +
        " (effective sample size " + format_number(std::round(correlated.effective_samples)) +
        " of " + std::to_string(n) + ")");
  }
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
      fit->covariance[std::size_t(j)][std::size_t(k)] = covariance(j, k);
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

// Exact data: the misfit cannot fall below the round-off of the data.
double misfit_floor(const CreepTestData& data) {
  double largest_strain = 0.0;
  for (double y : data.strain)
    largest_strain = std::max(largest_strain, std::abs(y));
  const double round_off = 1e-14 * largest_strain;
  return double(data.strain.size()) * round_off * round_off;
}

} // namespace

PetscErrorCode fit_creep_test(MPI_Comm comm, const CreepTestData& data,
                              const CreepTestParameters& start, double confidence_level,
                              CreepFit* fit) {
  PetscMPIInt rank = 0, size = 1;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCallMPI(MPI_Comm_size(comm, &size));
  fit->confidence_level = confidence_level;
  // Each rank takes a contiguous block of the samples.
  SampleShare share;
  share.data = &data;
  const std::size_t samples = data.time.size();
  share.begin = samples * std::size_t(rank) / std::size_t(size);
  share.end = samples * std::size_t(rank + 1) / std::size_t(size);

  const double floor = misfit_floor(data);

  const CreepTestVector q0 = to_fit_variables(start);
  Solution solution;
  PetscCall(levenberg_marquardt(comm, &share, q0, floor, &solution));
  PetscCall(certify_optimum(comm, &share, q0, floor, &solution, fit));
  fit->converged = solution.converged && fit->optimum_certified;
  fit->converged_reason = solution.reason;
  fit->iterations = solution.iterations;
  fit->solver = "levenberg-marquardt";
  fit->parameters = from_fit_variables(solution.q);
  // The autocorrelation needs the residuals at the solution (the sums there are kept).
  if (share.evaluated_at != solution.q) {
    evaluate_model(data, fit->parameters, share.begin, share.end, share.model.data());
  }
  // On exact data the residuals are round-off, with no noise to correlate.
  fit->autocorrelation.effective_samples = double(samples);
  if (solution.sums.squared_residual > floor) {
    PetscCall(residual_autocorrelation(comm, share, solution.sums.squared_residual,
                                       &fit->autocorrelation));
  }
  PetscCallCXX(fill_statistics(data, solution.sums, fit));
  PetscFunctionReturn(0);
}

namespace {

// Residuals of the fit, centred and scaled to the residual variance.
std::vector<double> bootstrap_residuals(const CreepTestData& data, const CreepFit& fit,
                                        std::vector<double>* model) {
  const std::size_t n = data.time.size();
  model->resize(n);
  evaluate_model(data, fit.parameters, 0, n, model->data());
  std::vector<double> residual(n);
  for (std::size_t i = 0; i < n; ++i)
    residual[i] = data.strain[i] - (*model)[i];
  const double mean = mean_of(residual, 0, n);
  const double scale = std::sqrt(double(n) / double(n - creep_test_parameter_count));
  for (double& r : residual)
    r = (r - mean) * scale;
  return residual;
}

// Linear interpolation between order statistics.
double percentile(std::vector<double> values, double fraction) {
  std::sort(values.begin(), values.end());
  const double position = fraction * double(values.size() - 1);
  const auto below = std::size_t(position);
  const std::size_t above = std::min(below + 1, values.size() - 1);
  return values[below] + (position - double(below)) * (values[above] - values[below]);
}

void summarise_replicates(const std::array<std::vector<double>, creep_test_parameter_count>& q,
                          const CreepFit& fit, BootstrapEstimate* bootstrap) {
  const double tail = 0.5 * (1.0 - fit.confidence_level);
  for (std::size_t j = 0; j < creep_test_parameter_count; ++j) {
    const bool logarithmic = j != 2;
    const auto value = [logarithmic](double x) { return logarithmic ? std::exp(x) : x; };
    std::vector<double> values;
    for (double x : q[j])
      values.push_back(value(x));
    const double mean = mean_of(values, 0, values.size());
    double squares = 0.0;
    for (double v : values)
      squares += (v - mean) * (v - mean);
    ParameterEstimate& e = bootstrap->estimates[j];
    e.value = fit.estimates[j].value;
    e.std_error = std::sqrt(squares / double(values.size() - 1));
    e.ci_low = value(percentile(q[j], tail));
    e.ci_high = value(percentile(q[j], 1.0 - tail));
  }
}

} // namespace

PetscErrorCode bootstrap_creep_fit(MPI_Comm comm, const CreepTestData& data, const CreepFit& fit,
                                   long replicates, unsigned long seed,
                                   BootstrapEstimate* bootstrap) {
  PetscMPIInt rank = 0, size = 1;
  PetscFunctionBeginUser;
  PetscCheck(replicates >= 20, comm, PETSC_ERR_ARG_OUTOFRANGE,
             "a bootstrap needs at least 20 replicates, got %ld", replicates);
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCallMPI(MPI_Comm_size(comm, &size));
  std::vector<double> model;
  const std::vector<double> residual = bootstrap_residuals(data, fit, &model);
  const std::size_t n = residual.size();
  // Correlated residuals: resample the AR(1) innovations instead and rebuild
  // the correlated series from them.
  const double lag1 = fit.autocorrelation.present ? fit.autocorrelation.lag1 : 0.0;
  bootstrap->ar1_coefficient = lag1;
  std::vector<double> innovation(residual);
  for (std::size_t i = 1; i < n; ++i)
    innovation[i] = residual[i] - lag1 * residual[i - 1];
  const double innovation_mean = mean_of(innovation, 1, n);
  for (double& u : innovation)
    u -= innovation_mean;

  CreepTestData replicate = data;
  SampleShare share;
  share.data = &replicate;
  share.begin = n * std::size_t(rank) / std::size_t(size);
  share.end = n * std::size_t(rank + 1) / std::size_t(size);
  const CreepTestVector optimum = to_fit_variables(fit.parameters);
  std::mt19937_64 generator(seed);
  std::uniform_int_distribution<std::size_t> any_sample(1, n - 1);
  std::array<std::vector<double>, creep_test_parameter_count> q;
  bootstrap->failed = 0;
  for (long r = 0; r < replicates; ++r) {
    double error = residual[any_sample(generator)];
    for (std::size_t i = 0; i < n; ++i) {
      replicate.strain[i] = model[i] + error;
      error = lag1 * error + innovation[any_sample(generator)];
    }
    Solution solution;
    PetscCall(levenberg_marquardt(comm, &share, optimum, misfit_floor(replicate), &solution));
    if (!solution.converged) {
      ++bootstrap->failed;
      continue;
    }
    for (std::size_t j = 0; j < creep_test_parameter_count; ++j)
      q[j].push_back(solution.q[j]);
  }
  bootstrap->replicates = replicates - bootstrap->failed;
  PetscCheck(bootstrap->replicates >= 20, comm, PETSC_ERR_NOT_CONVERGED,
             "only %ld of %ld bootstrap refits converged", bootstrap->replicates, replicates);
  PetscCallCXX(summarise_replicates(q, fit, bootstrap));
  PetscFunctionReturn(0);
}

CreepPrediction predict_creep_test(const CreepTestData& data, const CreepFit& fit) {
  const std::size_t n = data.time.size();
  constexpr std::size_t p = creep_test_parameter_count;
  CreepPrediction prediction;
  prediction.strain.resize(n);
  std::vector<double> jacobian(n * p);
  evaluate_model(data, fit.parameters, 0, n, prediction.strain.data(), jacobian.data(), n);
  prediction.band.resize(n);
  prediction.interval.resize(n);
  prediction.error.resize(n);
  double squared_error = 0.0, squared_band = 0.0;
  long within = 0;
  for (std::size_t i = 0; i < n; ++i) {
    double variance = 0.0;
    for (std::size_t j = 0; j < p; ++j) {
      for (std::size_t k = 0; k < p; ++k)
        variance += jacobian[j * n + i] * fit.covariance[j][k] * jacobian[k * n + i];
    }
    variance = std::max(variance, 0.0);
    prediction.band[i] = fit.t_quantile * std::sqrt(variance);
    const double error = data.strain[i] - prediction.strain[i];
    prediction.error[i] = error;
    squared_error += error * error;
    squared_band += prediction.band[i] * prediction.band[i];
    prediction.band_max = std::max(prediction.band_max, prediction.band[i]);
    if (std::abs(error) > prediction.max_abs_error) {
      prediction.max_abs_error = std::abs(error);
      prediction.time_of_max_error = data.time[i];
    }
    prediction.interval[i] =
        fit.t_quantile * std::sqrt(variance + fit.residual_std * fit.residual_std);
    if (std::abs(error) <= prediction.interval[i]) ++within;
  }
  prediction.rmse = std::sqrt(squared_error / double(n));
  prediction.band_rms = std::sqrt(squared_band / double(n));
  prediction.within_prediction_interval = double(within) / double(n);
  return prediction;
}

} // namespace sartor
