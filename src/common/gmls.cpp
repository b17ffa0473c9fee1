#include "common/gmls.hpp"

#include <Eigen/QR>
#include <Eigen/SVD>

#include <cmath>
#include <functional>

#include <stdexcept>

namespace sartor {

namespace {

// Exponents of the monomials of `dimension` variables up to `degree`, the
// constant first.
std::vector<std::vector<int>> monomials(int dimension, int degree) {
  std::vector<std::vector<int>> terms{std::vector<int>(std::size_t(dimension), 0)};
  for (int d = 1; d <= degree; ++d) {
    // Every exponent vector of total degree d, in lexicographic order.
    std::vector<int> e(std::size_t(dimension), 0);
    const std::function<void(int, int)> fill = [&](int variable, int left) {
      if (variable == dimension - 1) {
        e[std::size_t(variable)] = left;
        terms.push_back(e);
        return;
      }
      for (int k = left; k >= 0; --k) {
        e[std::size_t(variable)] = k;
        fill(variable + 1, left - k);
      }
    };
    if (dimension > 0) fill(0, d);
  }
  return terms;
}

double monomial(const std::vector<int>& e, const Eigen::VectorXd& t) {
  double value = 1.0;
  for (std::size_t j = 0; j < e.size(); ++j)
    for (int k = 0; k < e[j]; ++k)
      value *= t[Eigen::Index(j)];
  return value;
}

double monomial_derivative(const std::vector<int>& e, const Eigen::VectorXd& t, std::size_t j) {
  if (e[j] == 0) return 0.0;
  std::vector<int> lowered = e;
  --lowered[j];
  return e[j] * monomial(lowered, t);
}

// An orthonormal basis of the span of the columns of `offsets`.
Eigen::MatrixXd span_basis(const Eigen::MatrixXd& offsets) {
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(offsets);
  const double largest = offsets.colwise().norm().maxCoeff();
  qr.setThreshold(1e-9);
  const Eigen::Index rank = largest > 0.0 ? qr.rank() : 0;
  const Eigen::MatrixXd q = qr.householderQ();
  return q.leftCols(rank);
}

} // namespace

GmlsWeights gmls_weights(const std::vector<Eigen::VectorXd>& samples, const Eigen::VectorXd& query,
                         const GmlsOptions& options) {
  if (samples.empty()) throw std::invalid_argument("gmls_weights: no samples");
  const auto m_count = Eigen::Index(samples.size());
  Eigen::MatrixXd offsets(query.size(), m_count);
  for (Eigen::Index m = 0; m < m_count; ++m) {
    if (samples[std::size_t(m)].size() != query.size())
      throw std::invalid_argument("gmls_weights: a sample's size differs from the query's");
    offsets.col(m) = samples[std::size_t(m)] - query;
  }
  const Eigen::MatrixXd basis = span_basis(offsets);
  const int dimension = int(basis.cols());
  const Eigen::MatrixXd coordinates = basis.transpose() * offsets; // d_m per column
  double nearest = 0.0;
  for (Eigen::Index m = 0; m < m_count; ++m) {
    const double d = coordinates.col(m).norm();
    if (d > 0.0 && (nearest == 0.0 || d < nearest)) nearest = d;
  }
  const double scale = nearest > 0.0 ? nearest : 1.0; // t = d / scale
  std::vector<double> weight;
  for (Eigen::Index m = 0; m < m_count; ++m)
    weight.push_back(1.0 / (coordinates.col(m).squaredNorm() + options.epsilon * options.epsilon));

  for (int degree = dimension == 0 ? 0 : options.degree; degree >= 0; --degree) {
    const auto terms = monomials(dimension, degree);
    const auto rows = m_count * (1 + dimension);
    if (rows < Eigen::Index(terms.size())) continue;          // fewer equations than coefficients
    Eigen::MatrixXd design(rows, Eigen::Index(terms.size())); // sqrt(w) rows
    for (Eigen::Index m = 0; m < m_count; ++m) {
      const Eigen::VectorXd t = coordinates.col(m) / scale;
      const double root = std::sqrt(weight[std::size_t(m)]);
      for (std::size_t c = 0; c < terms.size(); ++c) {
        design(m * (1 + dimension), Eigen::Index(c)) = root * monomial(terms[c], t);
        for (int j = 0; j < dimension; ++j)
          design(m * (1 + dimension) + 1 + j, Eigen::Index(c)) =
              root * monomial_derivative(terms[c], t, std::size_t(j));
      }
    }
    Eigen::JacobiSVD<Eigen::MatrixXd> svd(design, Eigen::ComputeThinU | Eigen::ComputeThinV);
    const Eigen::VectorXd& sigma = svd.singularValues();
    if (sigma.size() == 0 || sigma.minCoeff() <= 1e-8 * sigma.maxCoeff()) continue;
    // The prediction is e_0 . c with c = (A^T A)^-1 A^T (sqrt(w) y): the
    // weights on the rows of sqrt(w) y are A (A^T A)^-1 e_0 = U S^-1 V^T e_0.
    const Eigen::VectorXd row_weights =
        svd.matrixU() * (svd.matrixV().row(0).transpose().cwiseQuotient(sigma));
    GmlsWeights result;
    result.degree = degree;
    result.dimension = dimension;
    for (Eigen::Index m = 0; m < m_count; ++m) {
      const double root = std::sqrt(weight[std::size_t(m)]);
      result.value_weight.push_back(root * row_weights[m * (1 + dimension)]);
      // A slope row's data is scale * S^m q_j (the derivative in t).
      Eigen::VectorXd direction = Eigen::VectorXd::Zero(query.size());
      for (int j = 0; j < dimension; ++j)
        direction += root * row_weights[m * (1 + dimension) + 1 + j] * scale * basis.col(j);
      result.slope_direction.push_back(direction);
    }
    return result;
  }
  throw std::logic_error("gmls_weights: not even a constant fits the samples");
}

} // namespace sartor
