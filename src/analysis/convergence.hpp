#pragma once
// Observed orders of convergence of a scalar q computed on a sequence of
// meshes of size h_0 > h_1 > ... (a mesh-refinement study). Pure C++.
//
// With a reference value q*: the error of level k is e_k = |q_k - q*|, the
// observed order between consecutive levels
//     p_k = log(e_k / e_(k+1)) / log(h_k / h_(k+1)),
// and a least-squares fit log e = log C + p log h over every level with e > 0.
//
// Without one (self-convergence), from each three consecutive levels
// (q0, q1, q2 on h0 > h1 > h2):
//     p = log(|q1 - q0| / |q2 - q1|) / log(h0 / h1)
// (exact for q = q* + C h^p with h0 / h1 = h1 / h2), the Richardson estimate
//     q* ~ q2 + (q2 - q1) / (r^p - 1),  r = h1 / h2,
// and Roache's grid convergence index of the finest of the three,
//     GCI = 1.25 |(q2 - q1) / q2| / (r^p - 1)
// (a relative error band). All three need monotone convergence,
// (q1 - q0)(q2 - q1) > 0; otherwise they are NaN and `monotone` is false (the
// extrapolation and GCI also need p > 0). The error column of a
// self-convergence study is the change from the previous level, |q_k - q_(k-1)|,
// NaN for the first; the fit uses those changes against h_k.
//
// Undefined numbers (a zero error, fewer levels than needed) are NaN.

#include <optional>
#include <vector>

namespace sartor {

struct ConvergencePair {
  int from = 0; // level k, and k + 1
  double order = 0.0;
};

struct ConvergenceTriplet {
  int from = 0; // levels k, k + 1, k + 2
  bool monotone = false;
  double order = 0.0;
  double extrapolated = 0.0; // Richardson estimate of q*
  double gci = 0.0;          // relative
};

struct ConvergenceAnalysis {
  std::optional<double> reference;
  std::vector<double> error;                // per level (see above)
  std::vector<ConvergencePair> pairs;       // with a reference: consecutive levels
  std::vector<ConvergenceTriplet> triplets; // three consecutive levels (always)
  double fitted_order = 0.0;                // least-squares slope of log error vs log h
  double fitted_constant = 0.0;             // C of error ~ C h^p
  int fitted_points = 0;
};

// h strictly decreasing, same length as values. Throws std::invalid_argument otherwise.
ConvergenceAnalysis analyse_convergence(const std::vector<double>& h,
                                        const std::vector<double>& values,
                                        std::optional<double> reference);

} // namespace sartor
