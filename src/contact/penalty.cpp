#include "contact/penalty.hpp"

namespace sartor::contact {

using element::Want;

PointResult penalty(double stiffness, double offset, const SurfaceQuery& query, Want want) {
  PointResult result;
  const double gap = offset - query.distance; // > 0: inside the contact layer
  if (gap <= 0.0) return result;
  result.energy = 0.5 * stiffness * gap * gap;
  if (want == Want::energy) return result;
  result.gradient = -stiffness * gap * query.normal;
  if (want == Want::gradient) return result;
  result.hessian =
      stiffness * (query.normal * query.normal.transpose()) - stiffness * gap * query.hessian;
  return result;
}

PointResult anchor_spring(double stiffness, const Eigen::Vector3d& x, const Eigen::Vector3d& anchor,
                          const Eigen::Vector3d& normal, double bound, Want want) {
  PointResult result;
  const Eigen::Matrix3d tangent = Eigen::Matrix3d::Identity() - normal * normal.transpose();
  const Eigen::Vector3d stretch = tangent * (x - anchor);
  const double length = stretch.norm();
  if (stiffness * length <= bound) {
    result.energy = 0.5 * stiffness * length * length;
    if (want == Want::energy) return result;
    result.gradient = stiffness * stretch;
    if (want == Want::gradient) return result;
    result.hessian = stiffness * tangent;
    return result;
  }
  // Sliding: the force keeps its bound along the stretch; the Hessian has
  // no stiffness along the slip, bound / length across it in the plane.
  const double reach = bound / stiffness;
  result.energy = bound * (length - 0.5 * reach);
  if (want == Want::energy) return result;
  const Eigen::Vector3d slip = stretch / length;
  result.gradient = bound * slip;
  if (want == Want::gradient) return result;
  result.hessian = (bound / length) * (tangent - slip * slip.transpose());
  return result;
}

Eigen::Vector3d anchor_spring_stiffness_derivative(double stiffness, const Eigen::Vector3d& x,
                                                   const Eigen::Vector3d& anchor,
                                                   const Eigen::Vector3d& normal, double bound) {
  // anchor_spring's arithmetic, so that both take the same branch.
  const Eigen::Matrix3d tangent = Eigen::Matrix3d::Identity() - normal * normal.transpose();
  const Eigen::Vector3d stretch = tangent * (x - anchor);
  if (stiffness * stretch.norm() <= bound) return stretch;
  return Eigen::Vector3d::Zero();
}

AnchorUpdate slide_anchor(double stiffness, const Eigen::Vector3d& x, const Eigen::Vector3d& anchor,
                          const Eigen::Vector3d& normal, double normal_force,
                          double static_coefficient, double kinetic_coefficient) {
  const Eigen::Vector3d stretch = (x - anchor) - normal.dot(x - anchor) * normal;
  const double force = stiffness * stretch.norm();
  if (force <= static_coefficient * normal_force) return {anchor, false};
  // Move the anchor along the stretch so that k_t |P (x - a')| = mu_k f_n.
  const double keep = kinetic_coefficient * normal_force / force;
  return {anchor + (1.0 - keep) * stretch, true};
}

double penalty_stiffness(double factor, double modulus, double vertex_area, double h) {
  return factor * modulus * vertex_area / (h * h);
}

} // namespace sartor::contact
