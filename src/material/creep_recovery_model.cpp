#include "material/creep_recovery_model.hpp"

#include "common/vector_math.hpp"

#include <algorithm>
#include <cmath>

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

} // namespace sartor
