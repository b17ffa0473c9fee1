#include "element/seam.hpp"

namespace sartor::element {

namespace {

// E = k |g|^2 / 2 with g = sum_i w_i x_i: the one source of both springs.
template <int N>
Result<3 * N> zero_length_spring(double stiffness, const Eigen::Matrix<double, N, 1>& weights,
                                 const Eigen::Matrix<double, 3 * N, 1>& x, Want want) {
  Eigen::Vector3d gap = Eigen::Vector3d::Zero();
  for (int i = 0; i < N; ++i)
    gap += weights[i] * x.template segment<3>(3 * i);
  Result<3 * N> result;
  result.energy = 0.5 * stiffness * gap.squaredNorm();
  result.gradient.setZero();
  result.hessian.setZero();
  if (want == Want::energy) return result;
  for (int i = 0; i < N; ++i)
    result.gradient.template segment<3>(3 * i) = stiffness * weights[i] * gap;
  if (want == Want::gradient) return result;
  for (int i = 0; i < N; ++i) {
    for (int j = 0; j < N; ++j) {
      result.hessian.template block<3, 3>(3 * i, 3 * j) =
          stiffness * weights[i] * weights[j] * Eigen::Matrix3d::Identity();
    }
  }
  return result;
}

} // namespace

Result<6> seam_vertex_vertex(double stiffness, const Eigen::Matrix<double, 6, 1>& x, Want want) {
  return zero_length_spring<2>(stiffness, Eigen::Vector2d(1.0, -1.0), x, want);
}

Result<9> seam_vertex_edge(double stiffness, double s, const Eigen::Matrix<double, 9, 1>& x,
                           Want want) {
  return zero_length_spring<3>(stiffness, Eigen::Vector3d(1.0, -(1.0 - s), -s), x, want);
}

} // namespace sartor::element
