#pragma once
// Central finite differences for the derivative checks of the element
// kernels, and the comparison they are judged by.

#include <Eigen/Core>

#include <algorithm>

namespace sartor::element::testing {

// d f / d x by central differences, f: vector -> scalar.
template <int N, class Function>
Eigen::Matrix<double, N, 1> numeric_gradient(const Function& f,
                                             const Eigen::Matrix<double, N, 1>& x, double step) {
  Eigen::Matrix<double, N, 1> gradient;
  for (int i = 0; i < N; ++i) {
    Eigen::Matrix<double, N, 1> plus = x;
    Eigen::Matrix<double, N, 1> minus = x;
    plus(i) += step;
    minus(i) -= step;
    gradient(i) = (f(plus) - f(minus)) / (2.0 * step);
  }
  return gradient;
}

// d g / d x by central differences, g: vector -> vector; column j is d g / d x_j.
template <int M, int N, class Function>
Eigen::Matrix<double, M, N> numeric_jacobian(const Function& g,
                                             const Eigen::Matrix<double, N, 1>& x, double step) {
  Eigen::Matrix<double, M, N> jacobian;
  for (int j = 0; j < N; ++j) {
    Eigen::Matrix<double, N, 1> plus = x;
    Eigen::Matrix<double, N, 1> minus = x;
    plus(j) += step;
    minus(j) -= step;
    jacobian.col(j) = (g(plus) - g(minus)) / (2.0 * step);
  }
  return jacobian;
}

// Largest difference relative to the largest entry of the exact value.
template <class Derived, class Other>
double relative_error(const Eigen::MatrixBase<Derived>& approximate,
                      const Eigen::MatrixBase<Other>& exact) {
  const double scale = std::max(exact.cwiseAbs().maxCoeff(), 1e-300);
  return (approximate - exact).cwiseAbs().maxCoeff() / scale;
}

} // namespace sartor::element::testing
