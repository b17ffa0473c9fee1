#pragma once
// Seam springs (Sensitive Couture §7): penalty springs of zero rest length
// that pull a vertex of one seam line onto the other line.
//
//  * vertex-to-vertex: E = k |x_a - x_b|^2 / 2, for seam lines with matching
//    vertices;
//  * vertex-to-edge:   E = k |x_a - ((1 - s) x_b + s x_c)|^2 / 2, the emitting
//    vertex a anchored at the fixed parameter s in [0, 1] of the receiving
//    edge b-c (its arc-length position on the other line), for seam lines of
//    unequal discretisation.
//
// Both are E = k |g|^2 / 2 with the gap g = sum_i w_i x_i linear in the
// positions (weights (1, -1) and (1, -(1 - s), -s)), so the gradient is
// k w_i g and the Hessian the constant k (w w^T) (x) I3: positive
// semi-definite, independent of x. k is in N/m.

#include "element/element.hpp"

#include <Eigen/Core>

namespace sartor::element {

// Positions stacked (x_a, x_b).
Result<6> seam_vertex_vertex(double stiffness, const Eigen::Matrix<double, 6, 1>& x,
                             Want want = Want::hessian);

// Positions stacked (x_a, x_b, x_c); s in [0, 1].
Result<9> seam_vertex_edge(double stiffness, double s, const Eigen::Matrix<double, 9, 1>& x,
                           Want want = Want::hessian);

} // namespace sartor::element
