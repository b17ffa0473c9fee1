#pragma once
// Hencky's problem, the reference solution of the verification tests: a flat
// circular membrane of radius a, clamped at its edge (no radial displacement),
// under a uniform lateral pressure q; linear elastic, isotropic (tensile
// stiffness Eh in N/m, Poisson's ratio nu), no bending stiffness. Föppl's
// membrane theory (moderate rotations, the pressure taken vertical) reduces
// it to one ODE for the radial membrane force N_r(r) (Hencky 1915):
//
//   r^2 N_r'' + 3 r N_r' + Eh q^2 r^2 / (8 N_r^2) = 0,
//   N_r'(0) = 0,   a N_r'(a) + (1 - nu) N_r(a) = 0   (u(a) = 0),
//
// and the deflection follows from vertical equilibrium, w' = -q r / (2 N_r).
// Hencky's power series, with xi = r / a,
//
//   N_r = (1/4) (Eh q^2 a^2)^(1/3) sum_n b_n xi^(2n),
//   w   = a (q a / Eh)^(1/3) sum_n d_n (1 - xi^(2n+2)) / (n + 1),
//
// where sum d_n xi^(2n) = 1 / sum b_n xi^(2n), turns the ODE into
// B^2 (B'' + 3 B' / xi) = -8 for B = sum b_n xi^(2n): a recurrence that gives
// every b_n from b_0. The edge condition, sum (2n + 1 - nu) b_n = 0, is then
// one equation for b_0, solved here by bisection (the "shooting" problem).
// Chien (1948) corrected an arithmetic slip in Hencky's coefficients.
//
// For nu = 0.3: b_0 = 1.72440406..., and the centre deflection
// w0 = 0.65344334... a (q a / Eh)^(1/3). (The often quoted 0.662 is 1.3 %
// above it; the finite-element study in tests/verification converges to
// 0.6534, its finest mesh within 3e-5.)
//
// Pure C++, no PETSc.

#include <vector>

namespace sartor {

struct HenckySolution {
  double poisson = 0.0;
  double b0 = 0.0;                     // N_r(0) = (b0 / 4) (Eh q^2 a^2)^(1/3)
  double deflection_coefficient = 0.0; // w0 = c a (q a / Eh)^(1/3)
  std::vector<double> b;               // b_n, n = 0, 1, ... (until negligible)
  std::vector<double> d;               // d_n: 1 / sum b_n xi^2n = sum d_n xi^2n

  // w(xi) / (a (q a / Eh)^(1/3)) for 0 <= xi = r / a <= 1.
  double deflection(double xi) const;
  // N_r(xi) / (Eh q^2 a^2)^(1/3).
  double radial_force(double xi) const;
};

// Throws InputError unless -1 < poisson <= 0.5.
HenckySolution hencky_membrane(double poisson);

// The centre deflection w0 (m) of a membrane of radius `radius` (m), tensile
// stiffness `tensile_stiffness` = Eh (N/m) under `pressure` q (Pa).
double hencky_centre_deflection(double radius, double pressure, double tensile_stiffness,
                                double poisson);

} // namespace sartor
