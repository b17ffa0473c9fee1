#pragma once
// Element kernels: energy, gradient and Hessian of one element from one
// source, over fixed-size Eigen types. No PETSc, no mesh: assembly scatters
// the results. Positions are stacked vertex by vertex: x = (x0, x1, x2, ...).

#include <Eigen/Core>

namespace sartor::element {

template <int N>
struct Result {
  double energy = 0.0;                  // J
  Eigen::Matrix<double, N, 1> gradient; // N
  Eigen::Matrix<double, N, N> hessian;  // N/m
};

// What to compute: the Hessian is the expensive part. Each level includes the
// ones before it; the parts of a Result not asked for are set to zero.
enum class Want { energy, gradient, hessian };

// Replaces a symmetric matrix by its nearest positive semi-definite one
// (negative eigenvalues clamped to zero): Sensitive Couture's compression
// stabilisation, and an option for Newton's method on any element. A matrix
// that is already positive semi-definite is left exactly as it is. Compiled
// for N = 6, 9, 12 and 36.
template <int N>
void project_to_psd(Eigen::Matrix<double, N, N>& matrix);

} // namespace sartor::element
