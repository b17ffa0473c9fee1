#pragma once
// Generalised moving least squares (GMLS) over solved designs (Sensitive
// Couture §4; docs/sensitivity.md#gmls-prediction). Each sample is a design
// p^m (a vector of pattern parameters) whose equilibrium x^m and sensitivity
// S^m = dx/dp are known. The response at a query design p is modelled by a
// polynomial a q(p - p) in the local coordinates of the samples, its
// coefficients minimising
//     J(a) = sum_m w_m |a q(d_m) - x^m|^2 + sum_m w_m l^2 sum_j |a dq/dd_j(d_m) - S^m e_j|^2,
// d_m the sample's coordinates relative to the query, w_m = 1 / (|d_m|^2 +
// eps^2) (SC's weight), l the distance to the nearest sample (so that value
// and slope equations weigh alike: a slope times a step is a change of x).
// The minimiser is linear in the data, so the prediction is
//     x(p) = sum_m value_weight[m] x^m + sum_m S^m slope_direction[m],
// one sensitivity application per sample. The local coordinates span the
// samples' offsets from the query (a sequence of edits along one direction
// is one coordinate), and the basis is complete to `degree` (1: SC's
// (1, d); 2 adds the quadratic terms), lowered while the samples cannot
// determine it.

#include <Eigen/Core>

#include <vector>

namespace sartor {

struct GmlsOptions {
  int degree = 2;        // of the polynomial basis: 1 (Sensitive Couture) or 2
  double epsilon = 1e-3; // of the weight, in the parameters' units (m for outline moves)
};

struct GmlsWeights {
  std::vector<double> value_weight;             // per sample, for x^m
  std::vector<Eigen::VectorXd> slope_direction; // per sample, a parameter change for S^m
  int degree = 0;                               // of the basis used
  int dimension = 0;                            // of the local coordinates
};

// The weights of the prediction at `query` from `samples` (at least one,
// all of the query's size). Throws std::invalid_argument for no samples or
// mismatched sizes.
GmlsWeights gmls_weights(const std::vector<Eigen::VectorXd>& samples, const Eigen::VectorXd& query,
                         const GmlsOptions& options = {});

} // namespace sartor
