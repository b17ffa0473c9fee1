#pragma once
// The modified Kelvin creep law of the thesis (eqs. 5.7, 5.8), one fabric
// direction at a time. Plain C++: no PETSc, no mesh.
//
//   eps_sat = max(sigma, 0) / E
//   d eps_v/dt = lambda (tau_v - eps_v),  tau_v = (1 - alpha) eps_sat,
//                lambda = lambda_load if eps_v < tau_v else lambda_unload
//   d eps_p/dt = lambda_load (tau_p - eps_p) if eps_p < tau_p else 0,
//                tau_p = alpha eps_sat
//
// The update is exact when the tension varies linearly over the step (held
// tension is the special case used by the structural solver), so results do
// not depend on the step size.

#include <string>

namespace sartor {

struct CreepParameters {
  double creep_modulus = 0.0; // E, N/m: saturated creep strain is tension / E
  double alpha = 0.0;         // permanent share of the saturated creep, [0, 1]
  double lambda_load = 0.0;   // 1/s, rate while creeping towards saturation
  double lambda_unload = 0.0; // 1/s, rate of viscoelastic recovery
};

// Throws InputError naming the parameter, its value and `context` (e.g. the
// fabric) when a parameter is not finite or out of range.
void validate(const CreepParameters& parameters, const std::string& context);

// Non-elastic strain of one direction, as elongation over the rest length.
struct CreepState {
  double viscoelastic = 0.0; // eps_v
  double permanent = 0.0;    // eps_p
  double nonelastic() const { return viscoelastic + permanent; }
};

double saturation_strain(const CreepParameters& parameters, double tension);

// Advances `state` over `duration` seconds while the tension (N/m) goes
// linearly from `tension_begin` to `tension_end`.
CreepState advance(const CreepParameters& parameters, const CreepState& state, double tension_begin,
                   double tension_end, double duration);

// The same step, with the derivative of its non-elastic strain (eps_v + eps_p
// at the end) with respect to `tension_end`, 1/(N/m): exact, the derivative of
// the branch the step takes (the monolithic coupling's tangent).
struct CreepAdvance {
  CreepState state;
  double nonelastic_per_tension = 0.0;
};
CreepAdvance advance_with_sensitivity(const CreepParameters& parameters, const CreepState& state,
                                      double tension_begin, double tension_end, double duration);

} // namespace sartor
