#include "material/creep_law.hpp"

#include "common/autodiff.hpp"
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

// The law is written once, for any scalar: double for values, AutoDiff for
// the derivative with respect to the end tension (the monolithic coupling's
// tangent). Branches follow the value. Calls name S where an argument is an
// expression (common/autodiff.hpp).

// x + expm1(-x) = x^2/2 - x^3/6 + ..., without cancellation for small x.
template <typename S>
S expm1_negative_plus(S x) {
  using std::abs;
  using std::expm1;
  if (x > 0.1) return expm1(-x) + x;
  S term = x * x / 2.0;
  S sum = term;
  for (int k = 3; k < 20 && abs(term) > 1e-17 * sum; ++k) {
    term *= -x / double(k);
    sum += term;
  }
  return sum;
}

// A Kelvin element eps' = rate (tau - eps) whose target tau starts at
// `target` and moves with `slope` (1/s), after `time` seconds. Two algebraically
// equal forms: the first keeps full precision when rate*time is small (it
// adds a small change to eps), the second when it is large (it adds a small
// remainder to the target).
template <typename S>
S kelvin_update(S strain, S target, S slope, double rate, S time) {
  using std::exp;
  using std::expm1;
  const S x = rate * time;
  const S gap = strain - target;
  if (x < std::log(2.0)) {
    return strain + gap * expm1(-x) + slope * expm1_negative_plus(x) / rate;
  }
  return target + slope * time + gap * exp(-x) + (slope / rate) * expm1(-x);
}

// Time at which the gap eps - tau of that element reaches zero, or `never`:
// the gap obeys g' = -rate g - slope, so it is monotone and closes at most once.
template <typename S>
S gap_closing_time(S gap, S slope, double rate) {
  using std::log1p;
  if (gap * slope <= 0.0) return never;
  return log1p(gap * rate / slope) / rate;
}

// Viscoelastic strain: rate_below while under its target, rate_above at or
// over it. Once the gap closes the element follows the other branch, whose gap
// moves away from zero for the rest of the step: at most one switch.
template <typename S>
S advance_viscoelastic(S strain, S target, S slope, double rate_below, double rate_above,
                       S duration) {
  const S gap = strain - target;
  const bool below = gap < 0.0 || (gap == 0.0 && slope > 0.0);
  const double rate = below ? rate_below : rate_above;
  const S closing = gap_closing_time(gap, slope, rate);
  if (closing >= duration) return kelvin_update(strain, target, slope, rate, duration);
  const S target_at_switch = target + slope * closing;
  return kelvin_update<S>(target_at_switch, target_at_switch, slope,
                          below ? rate_above : rate_below, duration - closing);
}

// Permanent strain: creeps up towards its target at `rate`, never recovers.
// A falling target that the strain catches freezes it for the rest of the
// step; a rising target that catches a frozen strain makes it creep for the
// rest of the step: again at most one switch.
template <typename S>
S advance_permanent(S strain, S target, S slope, double rate, S duration) {
  const S gap = strain - target;
  const bool creeping = gap < 0.0 || (gap == 0.0 && slope > 0.0);
  if (creeping) {
    const S closing = gap_closing_time(gap, slope, rate);
    if (closing >= duration) return kelvin_update(strain, target, slope, rate, duration);
    return target + slope * closing;
  }
  const S reached = slope > 0.0 ? gap / slope : S(never);
  if (reached >= duration) return strain;
  const S target_at_switch = target + slope * reached;
  return kelvin_update<S>(target_at_switch, target_at_switch, slope, rate, duration - reached);
}

template <typename S>
S saturation(const CreepParameters& p, S tension) {
  return tension > 0.0 ? tension / p.creep_modulus : S(0.0);
}

// eps_v, eps_p of one step.
template <typename S>
struct Strains {
  S viscoelastic;
  S permanent;
};

template <typename S>
Strains<S> advance_without_sign_change(const CreepParameters& p, Strains<S> state, S tension_begin,
                                       S tension_end, S duration) {
  if (duration <= 0.0) return state;
  const S saturation_begin = saturation(p, tension_begin);
  const S saturation_slope = (saturation(p, tension_end) - saturation_begin) / duration;
  Strains<S> next;
  next.viscoelastic = advance_viscoelastic<S>(
      state.viscoelastic, (1.0 - p.alpha) * saturation_begin, (1.0 - p.alpha) * saturation_slope,
      p.lambda_load, p.lambda_unload, duration);
  next.permanent = advance_permanent<S>(state.permanent, p.alpha * saturation_begin,
                                        p.alpha * saturation_slope, p.lambda_load, duration);
  return next;
}

template <typename S>
Strains<S> advance_step(const CreepParameters& p, const CreepState& state, double tension_begin,
                        S tension_end, double duration) {
  if (!(duration >= 0.0) || !std::isfinite(duration)) {
    throw std::invalid_argument("creep step duration must be finite and >= 0");
  }
  const Strains<S> start{S(state.viscoelastic), S(state.permanent)};
  if (duration == 0.0) return start;
  // eps_sat = max(sigma, 0)/E has a kink where the tension changes sign:
  // split there so that each piece has a linear target.
  if ((tension_begin > 0.0 && tension_end < 0.0) || (tension_begin < 0.0 && tension_end > 0.0)) {
    const S zero_at = duration * tension_begin / (tension_begin - tension_end);
    const Strains<S> middle =
        advance_without_sign_change(p, start, S(tension_begin), S(0.0), zero_at);
    return advance_without_sign_change<S>(p, middle, S(0.0), tension_end, duration - zero_at);
  }
  return advance_without_sign_change(p, start, S(tension_begin), tension_end, S(duration));
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
  return saturation(p, tension);
}

CreepState advance(const CreepParameters& p, const CreepState& state, double tension_begin,
                   double tension_end, double duration) {
  const Strains<double> next = advance_step(p, state, tension_begin, tension_end, duration);
  return {next.viscoelastic, next.permanent};
}

CreepAdvance advance_with_sensitivity(const CreepParameters& p, const CreepState& state,
                                      double tension_begin, double tension_end, double duration) {
  const Strains<AutoDiff> next =
      advance_step(p, state, tension_begin, seeded(tension_end, 1.0), duration);
  return {{next.viscoelastic.value(), next.permanent.value()},
          derivative_of(next.viscoelastic) + derivative_of(next.permanent)};
}

} // namespace sartor
