// The projection onto positive semi-definite matrices.

#include "element/element.hpp"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>

#include <random>

namespace sartor::element {
namespace {

template <int N>
Eigen::Matrix<double, N, N> random_matrix(std::mt19937& random) {
  std::normal_distribution<double> normal;
  Eigen::Matrix<double, N, N> m;
  for (int i = 0; i < N; ++i) {
    for (int j = 0; j < N; ++j)
      m(i, j) = normal(random);
  }
  return m;
}

template <int N>
void check_projection(std::mt19937& random) {
  using Matrix = Eigen::Matrix<double, N, N>;
  for (int sample = 0; sample < 20; ++sample) {
    const Matrix b = random_matrix<N>(random);
    const Matrix indefinite = b + b.transpose();
    const Eigen::SelfAdjointEigenSolver<Matrix> before(indefinite);
    ASSERT_LT(before.eigenvalues().minCoeff(), 0.0);
    Matrix projected = indefinite;
    project_to_psd<N>(projected);
    EXPECT_EQ(projected, projected.transpose());
    // The same eigenvectors, the negative eigenvalues replaced by zero.
    const Matrix expected = before.eigenvectors() *
                            before.eigenvalues().cwiseMax(0.0).asDiagonal() *
                            before.eigenvectors().transpose();
    EXPECT_LT((projected - expected).cwiseAbs().maxCoeff(), 1e-12 * indefinite.norm());
    const Eigen::SelfAdjointEigenSolver<Matrix> after(projected);
    EXPECT_GT(after.eigenvalues().minCoeff(), -1e-12 * indefinite.norm());
    // Projecting again changes nothing that matters.
    Matrix twice = projected;
    project_to_psd<N>(twice);
    EXPECT_LT((twice - projected).cwiseAbs().maxCoeff(), 1e-12 * indefinite.norm());

    // A positive semi-definite matrix (nearly of rank N - 2) is left as it is.
    Matrix low_rank = random_matrix<N>(random);
    low_rank.col(0).setZero();
    low_rank.col(1).setZero();
    Matrix psd = low_rank * low_rank.transpose() + 1e-6 * Matrix::Identity();
    const Matrix original = psd;
    project_to_psd<N>(psd);
    EXPECT_EQ(psd, original);
  }
}

TEST(ProjectToPsd, Size6) {
  std::mt19937 random(1);
  check_projection<6>(random);
}

TEST(ProjectToPsd, Size9) {
  std::mt19937 random(2);
  check_projection<9>(random);
}

TEST(ProjectToPsd, Size12) {
  std::mt19937 random(3);
  check_projection<12>(random);
}

} // namespace
} // namespace sartor::element
