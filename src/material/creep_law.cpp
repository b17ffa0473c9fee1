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

// Gap g = eps - tau of a Kelvin element whose target tau moves with constant
// `slope` (1/s), after `time` seconds at rate `rate`:
//   dg/dt = -rate g - slope.
double relaxed_gap(double gap, double slope, double rate, double time) {
  const double decay = std::exp(-rate * time);
  return gap * decay + (slope / rate) * std::expm1(-rate * time);
}

// Time at which that gap reaches zero, or `never`.
double gap_closing_time(double gap, double slope, double rate) {
  if (gap * slope <= 0.0) return never;
  return std::log1p(gap * rate / slope) / rate;
}

// Viscoelastic strain: two-rate Kelvin element, rate_below while under its
// target and rate_above at or over it. The gap is monotone within a step of
// constant slope, so it changes branch at most once.
double advance_viscoelastic(double strain, double target, double slope, double rate_below,
                            double rate_above, double duration) {
  double gap = strain - target;
  double elapsed = 0.0;
  for (int branch_change = 0; branch_change < 2; ++branch_change) {
    const bool below = gap < 0.0 || (gap == 0.0 && slope > 0.0);
    const double rate = below ? rate_below : rate_above;
    const double remaining = duration - elapsed;
    const double closing = gap_closing_time(gap, slope, rate);
    if (closing >= remaining) {
      gap = relaxed_gap(gap, slope, rate, remaining);
      break;
    }
    elapsed += closing;
    gap = 0.0;
  }
  return target + slope * duration + gap;
}

// Permanent strain: creeps up towards its target at `rate` and never recovers.
double advance_permanent(double strain, double target, double slope, double rate, double duration) {
  double elapsed = 0.0;
  for (int branch_change = 0; branch_change < 3; ++branch_change) {
    const double target_now = target + slope * elapsed;
    const double gap = strain - target_now;
    const double remaining = duration - elapsed;
    const bool creeping = gap < 0.0 || (gap == 0.0 && slope > 0.0);
    if (creeping) {
      const double closing = gap_closing_time(gap, slope, rate);
      if (closing >= remaining) {
        return target + slope * duration + relaxed_gap(gap, slope, rate, remaining);
      }
      elapsed += closing;
      strain = target + slope * elapsed;
    } else {
      const double reached = slope > 0.0 ? gap / slope : never;
      if (reached >= remaining) return strain;
      elapsed += reached;
    }
  }
  return strain;
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
