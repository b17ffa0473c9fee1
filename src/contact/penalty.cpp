#include "contact/penalty.hpp"

namespace sartor::contact {

using element::Want;

PointResult penalty(double stiffness, double offset, const SurfaceQuery& query, Want want,
                    double band) {
  PointResult result;
  const double depth = offset - query.distance; // > 0: inside the contact layer
  if (depth <= 0.0) return result;
  const PenaltyLaw law = penalty_law(stiffness, band, depth);
  result.energy = law.energy;
  if (want == Want::energy) return result;
  result.gradient = -law.force * query.normal;
  if (want == Want::gradient) return result;
  result.hessian =
      law.stiffness * (query.normal * query.normal.transpose()) - law.force * query.hessian;
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

namespace {

// u = P(x) (x - a) in the tangent plane at x, J = du/dx, and the part of
// sum_i u_i d2u_i/dx2 without the body's third derivative (which enters
// times m . r): -(M^T u) (dc/dx)^T - its transpose, c = m . r.
struct SurfaceStretch {
  Eigen::Vector3d stretch;
  Eigen::Matrix3d jacobian;
  Eigen::Matrix3d curvature;
};

SurfaceStretch surface_stretch(const Eigen::Vector3d& x, const Eigen::Vector3d& anchor,
                               const SurfaceQuery& query, bool with_jacobian) {
  const Eigen::Vector3d r = x - anchor;
  const double slope = query.normal.norm();
  if (slope == 0.0) // no plane: a plain spring
    return {r, Eigen::Matrix3d::Identity(), Eigen::Matrix3d::Zero()};
  const Eigen::Vector3d m = query.normal / slope;
  const double height = m.dot(r);
  SurfaceStretch result{r - height * m, Eigen::Matrix3d::Zero(), Eigen::Matrix3d::Zero()};
  if (!with_jacobian) return result;
  const Eigen::Matrix3d tangent = Eigen::Matrix3d::Identity() - m * m.transpose();
  const Eigen::Matrix3d turn = tangent * query.hessian / slope; // M = dm/dx
  const Eigen::Vector3d height_gradient = turn.transpose() * r + m;
  result.jacobian = tangent - m * (turn.transpose() * r).transpose() - height * turn;
  const Eigen::Matrix3d cross = (turn.transpose() * result.stretch) * height_gradient.transpose();
  result.curvature = -(cross + cross.transpose());
  return result;
}

} // namespace

PointResult surface_anchor_spring(double stiffness, const Eigen::Vector3d& x,
                                  const Eigen::Vector3d& anchor, const SurfaceQuery& query,
                                  double bound, Want want) {
  PointResult result;
  const SurfaceStretch s = surface_stretch(x, anchor, query, want != Want::energy);
  const double length = s.stretch.norm();
  const Eigen::Matrix3d& J = s.jacobian;
  if (stiffness * length <= bound) {
    result.energy = 0.5 * stiffness * length * length;
    if (want == Want::energy) return result;
    result.gradient = stiffness * J.transpose() * s.stretch;
    if (want == Want::gradient) return result;
    result.hessian = stiffness * (J.transpose() * J + s.curvature);
    return result;
  }
  const double reach = bound / stiffness;
  result.energy = bound * (length - 0.5 * reach);
  if (want == Want::energy) return result;
  const Eigen::Vector3d slip = s.stretch / length;
  result.gradient = bound * J.transpose() * slip;
  if (want == Want::gradient) return result;
  result.hessian =
      (bound / length) *
      (J.transpose() * (Eigen::Matrix3d::Identity() - slip * slip.transpose()) * J + s.curvature);
  return result;
}

Eigen::Vector3d surface_anchor_spring_stiffness_derivative(double stiffness,
                                                           const Eigen::Vector3d& x,
                                                           const Eigen::Vector3d& anchor,
                                                           const SurfaceQuery& query,
                                                           double bound) {
  const SurfaceStretch s = surface_stretch(x, anchor, query, true);
  if (stiffness * s.stretch.norm() <= bound) return s.jacobian.transpose() * s.stretch;
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
