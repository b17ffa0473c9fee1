#pragma once
// A one-sided penalty on the depth g into a contact layer (bodies:
// contact/penalty.hpp; cloth on cloth: element/point_triangle.hpp). Its
// force is
//     f(g) = k g                          g >= b
//     f(g) = k (g^2 / b) (2 - g / b)      0 < g < b
// over an onset band b (0: E = k/2 max(0, g)^2), so that f and its slope
// f'(g) = k (4 - 3 g / b) g / b are continuous and E is C^2: the plain
// quadratic's Hessian jumps from 0 to k where a point enters the layer, and
// Newton's steps then chatter in and out of it. Beyond the band the force
// is the plain one, so a load deeper than k b rests at the same depth.

namespace sartor::element {

// The penalty's energy E(g), normal force f(g) = E'(g) and stiffness f'(g)
// at depth g into the contact layer (zero for g <= 0), with onset band b.
struct PenaltyLaw {
  double energy = 0.0;    // J
  double force = 0.0;     // N
  double stiffness = 0.0; // N/m
};
PenaltyLaw penalty_law(double stiffness, double band, double depth);

} // namespace sartor::element
