#include "element/element.hpp"

#include <Eigen/Eigenvalues>

#include <cmath>

namespace sartor::element {

template <int N>
void project_to_psd(Eigen::Matrix<double, N, N>& matrix) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, N, N>> eigen(matrix);
  const Eigen::Matrix<double, N, 1>& values = eigen.eigenvalues();
  if (values.minCoeff() >= 0.0) return;
  const Eigen::Matrix<double, N, N>& vectors = eigen.eigenvectors();
  const Eigen::Matrix<double, N, N> projected =
      vectors * values.cwiseMax(0.0).asDiagonal() * vectors.transpose();
  matrix = 0.5 * (projected + projected.transpose());
}

template <int N>
void project_translation_free_to_psd(Eigen::Matrix<double, N, N>& matrix) {
  constexpr int points = N / 3, reduced_size = N - 3;
  // Helmert's orthonormal basis of the complement of (1, ..., 1) in
  // R^points, times the identity in each of the three directions.
  Eigen::Matrix<double, N, reduced_size> basis = Eigen::Matrix<double, N, reduced_size>::Zero();
  for (int j = 1; j < points; ++j) {
    const double scale = 1.0 / std::sqrt(double(j) * double(j + 1));
    for (int d = 0; d < 3; ++d) {
      for (int i = 0; i < j; ++i)
        basis(3 * i + d, 3 * (j - 1) + d) = scale;
      basis(3 * j + d, 3 * (j - 1) + d) = -double(j) * scale;
    }
  }
  Eigen::Matrix<double, reduced_size, reduced_size> reduced = basis.transpose() * matrix * basis;
  reduced = (0.5 * (reduced + reduced.transpose())).eval();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, reduced_size, reduced_size>> eigen(
      reduced);
  if (eigen.eigenvalues().minCoeff() >= 0.0) return;
  const Eigen::Matrix<double, N, reduced_size> vectors = basis * eigen.eigenvectors();
  const Eigen::Matrix<double, N, N> projected =
      vectors * eigen.eigenvalues().cwiseMax(0.0).asDiagonal() * vectors.transpose();
  matrix = 0.5 * (projected + projected.transpose());
}

template void project_translation_free_to_psd<9>(Eigen::Matrix<double, 9, 9>&);
template void project_translation_free_to_psd<12>(Eigen::Matrix<double, 12, 12>&);

template void project_to_psd<3>(Eigen::Matrix<double, 3, 3>&);
template void project_to_psd<6>(Eigen::Matrix<double, 6, 6>&);
template void project_to_psd<9>(Eigen::Matrix<double, 9, 9>&);
template void project_to_psd<12>(Eigen::Matrix<double, 12, 12>&);
template void project_to_psd<36>(Eigen::Matrix<double, 36, 36>&);

} // namespace sartor::element
