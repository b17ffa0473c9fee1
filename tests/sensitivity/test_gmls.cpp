// GMLS weights (common/gmls.hpp) on functions known in closed form: the
// prediction from samples' values and slopes reproduces any polynomial of
// the basis' degree, and one sample gives the linear extrapolation.

#include "common/gmls.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace sartor {
namespace {

// f(p) = 0.3 + 2 p0 - p1 + 5 p0^2 + 3 p0 p1 - 4 p1^2 and its gradient.
double quadratic(const Eigen::Vector2d& p) {
  return 0.3 + 2 * p[0] - p[1] + 5 * p[0] * p[0] + 3 * p[0] * p[1] - 4 * p[1] * p[1];
}
Eigen::Vector2d quadratic_gradient(const Eigen::Vector2d& p) {
  return {2 + 10 * p[0] + 3 * p[1], -1 + 3 * p[0] - 8 * p[1]};
}

double predict(const std::vector<Eigen::VectorXd>& samples, const Eigen::VectorXd& query,
               const GmlsOptions& options, int* degree) {
  const GmlsWeights w = gmls_weights(samples, query, options);
  double value = 0.0;
  for (std::size_t m = 0; m < samples.size(); ++m) {
    const Eigen::Vector2d p = samples[m];
    value += w.value_weight[m] * quadratic(p) + quadratic_gradient(p).dot(w.slope_direction[m]);
  }
  *degree = w.degree;
  return value;
}

TEST(Gmls, ReproducesAQuadraticFromScatteredSamples) {
  const std::vector<Eigen::VectorXd> samples{Eigen::Vector2d(0.0, 0.0), Eigen::Vector2d(0.02, 0.0),
                                             Eigen::Vector2d(0.0, 0.03),
                                             Eigen::Vector2d(0.015, 0.01)};
  const Eigen::Vector2d query(0.04, 0.02);
  int degree = 0;
  const double value = predict(samples, query, {}, &degree);
  EXPECT_EQ(degree, 2);
  EXPECT_NEAR(value, quadratic(query), 1e-9);
}

TEST(Gmls, QuadraticAlongALineOfEdits) {
  // Samples on one line: the model is quadratic along it and exact for the
  // quadratic restricted to the line.
  const Eigen::Vector2d direction(0.6, 0.8);
  std::vector<Eigen::VectorXd> samples;
  for (int k = 0; k < 3; ++k)
    samples.push_back(Eigen::VectorXd(0.01 * k * direction));
  const Eigen::Vector2d query = 0.03 * direction;
  int degree = 0;
  EXPECT_NEAR(predict(samples, query, {}, &degree), quadratic(query), 1e-9);
  EXPECT_EQ(degree, 2);
}

TEST(Gmls, OneSampleIsTheLinearPrediction) {
  const Eigen::Vector2d p(0.01, -0.02), query(0.03, 0.01);
  int degree = 0;
  const double value = predict({Eigen::VectorXd(p)}, query, {}, &degree);
  EXPECT_EQ(degree, 1);
  EXPECT_NEAR(value, quadratic(p) + quadratic_gradient(p).dot(query - p), 1e-12);
}

TEST(Gmls, DegreeOneAsSensitiveCouture) {
  // SC's linear basis is exact for an affine function.
  const std::vector<Eigen::VectorXd> samples{Eigen::Vector2d(0.0, 0.0),
                                             Eigen::Vector2d(0.02, 0.01)};
  const GmlsWeights w = gmls_weights(samples, Eigen::Vector2d(0.05, 0.0), {1, 1e-3});
  double value = 0.0;
  for (std::size_t m = 0; m < samples.size(); ++m)
    value += w.value_weight[m] * (1.0 + 2.0 * samples[m][0] - 3.0 * samples[m][1]) +
             Eigen::Vector2d(2.0, -3.0).dot(w.slope_direction[m]);
  EXPECT_NEAR(value, 1.1, 1e-12);
  EXPECT_THROW(gmls_weights({}, Eigen::Vector2d(0.0, 0.0)), std::invalid_argument);
}

} // namespace
} // namespace sartor
