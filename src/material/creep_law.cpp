#include "material/creep_law.hpp"

#include "common/error.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace sartor {

namespace {

constexpr double never = std::numeric_limits<double>::infinity();

void require(bool ok, const std::string& context, const char* name, double value,
             const char* rule) {
  if (ok) return;
  std::ostringstream message;
  message.precision(17);
  message << context << ": creep parameter " << name << " = " << value << " " << rule;
  throw InputError(message.str());
}

// x + expm1(-x) = x^2/2 - x^3/6 + ..., without cancellation for small x.
double expm1_negative_plus(double x) {
  if (x > 0.1) return std::expm1(-x) + x;
  double term = x * x / 2.0;
  double sum = term;
  for (int k = 3; k < 20 && std::abs(term) > 1e-17 * sum; ++k) {
    term *= -x / k;
    sum += term;
  }
  return sum;
}

// A Kelvin element eps' = rate (tau - eps) whose target tau starts at
// `target` and moves with `slope` (1/s), after `time` seconds. Two algebraically
// equal forms: the first keeps full precision when rate*time is small (it
// adds a small change to eps), the second when it is large (it adds a small
// remainder to the target).
double kelvin_update(double strain, double target, double slope, double rate, double time) {
  const double x = rate * time;
  const double gap = strain - target;
  if (x < std::log(2.0)) {
    return strain + gap * std::expm1(-x) + slope * expm1_negative_plus(x) / rate;
  }
  return target + slope * time + gap * std::exp(-x) + (slope / rate) * std::expm1(-x);
}

// Time at which the gap eps - tau of that element reaches zero, or `never`:
// the gap obeys g' = -rate g - slope, so it is monotone and closes at most once.
double gap_closing_time(double gap, double slope, double rate) {
  if (gap * slope <= 0.0) return never;
  return std::log1p(gap * rate / slope) / rate;
}

// Viscoelastic strain: rate_below while under its target, rate_above at or
// over it. Once the gap closes the element follows the other branch, whose gap
// moves away from zero for the rest of the step: at most one switch.
double advance_viscoelastic(double strain, double target, double slope, double rate_below,
                            double rate_above, double duration) {
  const double gap = strain - target;
  const bool below = gap < 0.0 || (gap == 0.0 && slope > 0.0);
  const double rate = below ? rate_below : rate_above;
  const double closing = gap_closing_time(gap, slope, rate);
  if (closing >= duration) return kelvin_update(strain, target, slope, rate, duration);
  const double target_at_switch = target + slope * closing;
  return kelvin_update(target_at_switch, target_at_switch, slope, below ? rate_above : rate_below,
                       duration - closing);
}

// Permanent strain: creeps up towards its target at `rate`, never recovers.
// A falling target that the strain catches freezes it for the rest of the
// step; a rising target that catches a frozen strain makes it creep for the
// rest of the step: again at most one switch.
double advance_permanent(double strain, double target, double slope, double rate, double duration) {
  const double gap = strain - target;
  const bool creeping = gap < 0.0 || (gap == 0.0 && slope > 0.0);
  if (creeping) {
    const double closing = gap_closing_time(gap, slope, rate);
    if (closing >= duration) return kelvin_update(strain, target, slope, rate, duration);
    return target + slope * closing;
  }
  const double reached = slope > 0.0 ? gap / slope : never;
  if (reached >= duration) return strain;
  const double target_at_switch = target + slope * reached;
  return kelvin_update(target_at_switch, target_at_switch, slope, rate, duration - reached);
}

CreepState advance_without_sign_change(const CreepParameters& p, const CreepState& state,
                                       double tension_begin, double tension_end, double duration) {
  if (duration <= 0.0) return state;
  const double saturation_begin = saturation_strain(p, tension_begin);
  const double saturation_slope = (saturation_strain(p, tension_end) - saturation_begin) / duration;
  CreepState next;
  next.viscoelastic = advance_viscoelastic(state.viscoelastic, (1.0 - p.alpha) * saturation_begin,
                                           (1.0 - p.alpha) * saturation_slope, p.lambda_load,
                                           p.lambda_unload, duration);
  next.permanent = advance_permanent(state.permanent, p.alpha * saturation_begin,
                                     p.alpha * saturation_slope, p.lambda_load, duration);
  return next;
}

} // namespace

void validate(const CreepParameters& p, const std::string& context) {
  require(std::isfinite(p.creep_modulus) && p.creep_modulus > 0.0, context, "E (N/m)",
          p.creep_modulus, "must be a finite number > 0");
  require(std::isfinite(p.alpha) && p.alpha >= 0.0 && p.alpha <= 1.0, context, "alpha", p.alpha,
          "must lie in [0, 1]");
  require(std::isfinite(p.lambda_load) && p.lambda_load > 0.0, context, "lambda_load (1/s)",
          p.lambda_load, "must be a finite number > 0");
  require(std::isfinite(p.lambda_unload) && p.lambda_unload > 0.0, context, "lambda_unload (1/s)",
          p.lambda_unload, "must be a finite number > 0");
}

double saturation_strain(const CreepParameters& p, double tension) {
  return std::max(tension, 0.0) / p.creep_modulus;
}

CreepState advance(const CreepParameters& p, const CreepState& state, double tension_begin,
                   double tension_end, double duration) {
  if (!(duration >= 0.0) || !std::isfinite(duration)) {
    throw std::invalid_argument("creep step duration must be finite and >= 0");
  }
  if (duration == 0.0) return state;
  // eps_sat = max(sigma, 0)/E has a kink where the tension changes sign:
  // split there so that each piece has a linear target.
  if ((tension_begin > 0.0 && tension_end < 0.0) || (tension_begin < 0.0 && tension_end > 0.0)) {
    const double zero_at = duration * tension_begin / (tension_begin - tension_end);
    const CreepState middle = advance_without_sign_change(p, state, tension_begin, 0.0, zero_at);
    return advance_without_sign_change(p, middle, 0.0, tension_end, duration - zero_at);
  }
  return advance_without_sign_change(p, state, tension_begin, tension_end, duration);
}

} // namespace sartor
