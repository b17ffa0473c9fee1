#include "contact/edge_penalty.hpp"

#include <cmath>

namespace sartor::contact {

EdgeSampleResult edge_sample_penalty(double stiffness, double offset, double s,
                                     const SurfaceQuery& query, element::Want want, bool project,
                                     double band) {
  EdgeSampleResult result;
  const PointResult point = penalty(stiffness, offset, query, want, band);
  result.energy = point.energy;
  if (want == element::Want::energy) return result;
  const double w[2] = {1.0 - s, s};
  result.force = -point.gradient;
  for (int i = 0; i < 2; ++i)
    result.gradient.segment<3>(3 * i) = w[i] * point.gradient;
  if (want == element::Want::gradient) return result;
  Eigen::Matrix3d hessian = point.hessian;
  if (project) element::project_to_psd<3>(hessian);
  for (int i = 0; i < 2; ++i) {
    for (int j = 0; j < 2; ++j)
      result.hessian.block<3, 3>(3 * i, 3 * j) = w[i] * w[j] * hessian;
  }
  return result;
}

std::vector<double> edge_sample_parameters(double length, double spacing) {
  if (spacing <= 0.0 || !(length > spacing)) return {};
  // Pieces of at most `spacing`; the relative margin keeps an edge whose
  // length is a whole multiple of the spacing (up to the mesh's round-off)
  // from flipping to one more piece.
  const int pieces = int(std::ceil(length / spacing * (1.0 - 1e-9)));
  std::vector<double> parameters;
  for (int j = 1; j < pieces; ++j)
    parameters.push_back(double(j) / double(pieces));
  return parameters;
}

} // namespace sartor::contact
