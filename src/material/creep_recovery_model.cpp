#include "material/creep_recovery_model.hpp"

#include "common/vector_math.hpp"
#include "material/creep_law.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace sartor {

CreepTestVector to_fit_variables(const CreepTestParameters& p) {
  return {std::log(p.elastic_modulus), std::log(p.creep_modulus), p.alpha, std::log(p.lambda_load),
          std::log(p.lambda_unload)};
}

CreepTestParameters from_fit_variables(const CreepTestVector& q) {
  return {std::exp(q[0]), std::exp(q[1]), q[2], std::exp(q[3]), std::exp(q[4])};
}

void evaluate_creep_test(const CreepTest& test, const CreepTestParameters& p, const double* times,
                         std::size_t count, double* strain, double* jacobian,
                         std::size_t leading_dimension) {
  const double elastic = test.tension / p.elastic_modulus;
  const double saturation = test.tension / p.creep_modulus;
  const double load_duration = test.unload_time - test.load_time;
  const double remaining_at_unload = std::exp(-p.lambda_load * load_duration);
  const double creep_at_unload = -saturation * std::expm1(-p.lambda_load * load_duration);
  const double d_creep_at_unload_d_log_lambda_load =
      saturation * load_duration * p.lambda_load * remaining_at_unload;

  // Times are sorted, so each phase is one range; the exponentials of a range
  // are computed in one vectorised pass, in place in `strain`.
  const double* end = times + count;
  const std::size_t load_begin = std::size_t(std::lower_bound(times, end, test.load_time) - times);
  const std::size_t load_end = std::size_t(std::lower_bound(times, end, test.unload_time) - times);
  const auto column = [&](std::size_t j) { return jacobian + j * leading_dimension; };

  std::fill(strain, strain + load_begin, 0.0);
  if (jacobian) {
    for (std::size_t j = 0; j < creep_test_parameter_count; ++j) {
      std::fill(column(j), column(j) + load_begin, 0.0);
    }
  }

  for (std::size_t i = load_begin; i < load_end; ++i) {
    strain[i] = p.lambda_load * (times[i] - test.load_time);
  }
  exp_of_negative(strain + load_begin, strain + load_begin, load_end - load_begin);
  for (std::size_t i = load_begin; i < load_end; ++i) {
    const double remaining = strain[i];
    const double creep = saturation * (1.0 - remaining);
    strain[i] = (1.0 + elastic) * (1.0 + creep) - 1.0;
    if (jacobian) {
      column(0)[i] = -elastic * (1.0 + creep);
      column(1)[i] = -(1.0 + elastic) * creep;
      column(2)[i] = 0.0;
      column(3)[i] =
          (1.0 + elastic) * saturation * (times[i] - test.load_time) * p.lambda_load * remaining;
      column(4)[i] = 0.0;
    }
  }

  for (std::size_t i = load_end; i < count; ++i) {
    strain[i] = p.lambda_unload * (times[i] - test.unload_time);
  }
  exp_of_negative(strain + load_end, strain + load_end, count - load_end);
  for (std::size_t i = load_end; i < count; ++i) {
    const double decay = strain[i];
    const double shape = p.alpha + (1.0 - p.alpha) * decay;
    strain[i] = creep_at_unload * shape;
    if (jacobian) {
      column(0)[i] = 0.0;
      column(1)[i] = -strain[i];
      column(2)[i] = creep_at_unload * (1.0 - decay);
      column(3)[i] = d_creep_at_unload_d_log_lambda_load * shape;
      column(4)[i] = -creep_at_unload * (1.0 - p.alpha) * (times[i] - test.unload_time) *
                     p.lambda_unload * decay;
    }
  }
}

double tension_at(const LoadHistory& history, double time) {
  if (history.empty()) return 0.0;
  const auto after = std::upper_bound(history.begin(), history.end(), time,
                                      [](double t, const LoadKnot& k) { return t < k.time; });
  if (after == history.begin()) return history.front().tension;
  if (after == history.end()) return history.back().tension;
  const LoadKnot& before = *(after - 1);
  const double fraction = (time - before.time) / (after->time - before.time);
  return before.tension + fraction * (after->tension - before.tension);
}

// With alpha = 1/2 one pass of the law gives both: eps_v = V / 2, eps_p = P / 2.
void unit_creep(const LoadHistory& history, double lambda_load, double lambda_unload,
                const double* times, std::size_t count, std::size_t first_stored, UnitCreep* out) {
  const CreepParameters unit{1.0, 0.5, lambda_load, lambda_unload};
  const std::size_t stored = count - first_stored;
  out->tension.resize(stored);
  out->viscoelastic.resize(stored);
  out->permanent.resize(stored);
  CreepState state;
  double now = count > 0 ? std::min(times[0], history.front().time) : history.front().time;
  // Right-continuous: a jump at the start has happened.
  double tension = tension_at(history, now);
  std::size_t knot = 0;
  while (knot < history.size() && history[knot].time <= now)
    ++knot;
  for (std::size_t i = 0; i < count; ++i) {
    for (; knot < history.size() && history[knot].time <= times[i]; ++knot) {
      state = advance(unit, state, tension, history[knot].tension, history[knot].time - now);
      now = history[knot].time;
      tension = history[knot].tension;
    }
    const double at_sample = tension_at(history, times[i]);
    state = advance(unit, state, tension, at_sample, times[i] - now);
    now = times[i];
    tension = at_sample;
    if (i < first_stored) continue;
    out->tension[i - first_stored] = tension;
    out->viscoelastic[i - first_stored] = 2.0 * state.viscoelastic;
    out->permanent[i - first_stored] = 2.0 * state.permanent;
  }
}

namespace {

// Relative step of the central differences in ln(lambda): truncation
// (~step^2) and round-off (~1e-16 / step) both near 1e-10.
constexpr double log_rate_step = 1e-5;

} // namespace

void evaluate_load_history(const LoadHistory& history, const CreepTestParameters& p,
                           const double* times, std::size_t count, std::size_t first_stored,
                           double* strain, double* jacobian, std::size_t leading_dimension) {
  if (history.empty()) throw std::invalid_argument("evaluate_load_history: empty load history");
  UnitCreep base;
  unit_creep(history, p.lambda_load, p.lambda_unload, times, count, first_stored, &base);
  const std::size_t stored = count - first_stored;
  const auto creep = [&p](const UnitCreep& u, std::size_t i) {
    return ((1.0 - p.alpha) * u.viscoelastic[i] + p.alpha * u.permanent[i]) / p.creep_modulus;
  };
  for (std::size_t i = 0; i < stored; ++i) {
    strain[i] = (1.0 + base.tension[i] / p.elastic_modulus) * (1.0 + creep(base, i)) - 1.0;
  }
  if (!jacobian) return;
  const double up = std::exp(log_rate_step), down = std::exp(-log_rate_step);
  UnitCreep load_up, load_down, unload_up, unload_down;
  unit_creep(history, p.lambda_load * up, p.lambda_unload, times, count, first_stored, &load_up);
  unit_creep(history, p.lambda_load * down, p.lambda_unload, times, count, first_stored,
             &load_down);
  unit_creep(history, p.lambda_load, p.lambda_unload * up, times, count, first_stored, &unload_up);
  unit_creep(history, p.lambda_load, p.lambda_unload * down, times, count, first_stored,
             &unload_down);
  const auto column = [&](std::size_t j) { return jacobian + j * leading_dimension; };
  for (std::size_t i = 0; i < stored; ++i) {
    const double elastic = base.tension[i] / p.elastic_modulus;
    const double creep_strain = creep(base, i);
    column(0)[i] = -elastic * (1.0 + creep_strain);
    column(1)[i] = -(1.0 + elastic) * creep_strain;
    column(2)[i] = (1.0 + elastic) * (base.permanent[i] - base.viscoelastic[i]) / p.creep_modulus;
    column(3)[i] =
        (1.0 + elastic) * (creep(load_up, i) - creep(load_down, i)) / (2.0 * log_rate_step);
    column(4)[i] =
        (1.0 + elastic) * (creep(unload_up, i) - creep(unload_down, i)) / (2.0 * log_rate_step);
  }
}

} // namespace sartor
