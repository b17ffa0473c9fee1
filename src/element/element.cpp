#include "element/element.hpp"

#include <Eigen/Eigenvalues>

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

template void project_to_psd<3>(Eigen::Matrix<double, 3, 3>&);
template void project_to_psd<6>(Eigen::Matrix<double, 6, 6>&);
template void project_to_psd<9>(Eigen::Matrix<double, 9, 9>&);
template void project_to_psd<12>(Eigen::Matrix<double, 12, 12>&);
template void project_to_psd<36>(Eigen::Matrix<double, 36, 36>&);

} // namespace sartor::element
