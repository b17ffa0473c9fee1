#pragma once
// The contact penalty of a sample point on a cloth edge: plain Eigen, no PETSc.
//
// A point p = (1 - s) a + s b of the edge a-b (s in (0, 1), fixed in the
// material) carries the vertex penalty of penalty.hpp,
//     E = k/2 max(0, offset - d(p))^2,
// so that a coarse edge cannot cut through a curved body between its
// vertices (docs/contact.md#edges). With w = (1 - s, s), the chain rule
// gives the gradient w_i grad_p E at vertex i and the Hessian blocks
// w_i w_j hess_p E: the 6x6 Hessian is w w^T (x) hess_p E, positive
// semi-definite whenever hess_p E is, so projecting the 3x3 point Hessian
// projects the whole. Normal contact only: samples carry no friction.

#include "contact/penalty.hpp"

#include <Eigen/Core>

#include <vector>

namespace sartor::contact {

using Vector6 = Eigen::Matrix<double, 6, 1>;
using Matrix6 = Eigen::Matrix<double, 6, 6>;

struct EdgeSampleResult {
  double energy = 0.0;                             // J
  Vector6 gradient = Vector6::Zero();              // N: vertex a, then vertex b
  Matrix6 hessian = Matrix6::Zero();               // N/m
  Eigen::Vector3d force = Eigen::Vector3d::Zero(); // N: on the cloth at the sample point
};

// The sample point of edge a-b at parameter s.
inline Eigen::Vector3d edge_point(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double s) {
  return (1.0 - s) * a + s * b;
}

// The penalty of the sample at parameter s, from the body's query at the
// sample point, with the vertices' onset band; `project` PSD-projects the
// point Hessian first.
EdgeSampleResult edge_sample_penalty(double stiffness, double offset, double s,
                                     const SurfaceQuery& query, element::Want want, bool project,
                                     double band = 0.0);

// The parameters of the samples on an edge of rest length `length`: equally
// spaced, so that no two neighbouring points of the edge (vertices
// included) are further apart than `spacing`; none when the edge is no
// longer than that (or spacing <= 0).
std::vector<double> edge_sample_parameters(double length, double spacing);

} // namespace sartor::contact
