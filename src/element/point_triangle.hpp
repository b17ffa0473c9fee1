#pragma once
// Cloth self-contact between a vertex and a triangle of the cloth: the
// penalty law of element/penalty_law.hpp on the depth g = delta - d (zero
// for d >= delta), d the distance from the point p to the triangle
// (a, b, c), delta the contact offset (twice the half-thickness a layer
// keeps from another), k in N/m, over an onset band (0: E = k g^2 / 2).
//
// The distance is unsigned: which side of a layer a vertex is on is kept by
// the solver's step bound (no step may carry a vertex through a triangle),
// not by the energy. Its gradient is, on every feature of the triangle, the
// unit direction u = (p - q) / d from the closest point q = sum_i b_i x_i
// (barycentric b) times (1, -b_a, -b_b, -b_c), so it is continuous across
// the features; the Hessian is that gradient's derivative along the feature
// the closest point lies on (face, edge or vertex), by forward-mode
// differentiation of the same source.

#include "element/element.hpp"

#include <Eigen/Core>

namespace sartor::element {

using Vector12 = Eigen::Matrix<double, 12, 1>;

// Where on the triangle the closest point lies.
enum class TriangleFeature { face, edge_ab, edge_bc, edge_ca, vertex_a, vertex_b, vertex_c };

struct ClosestPoint {
  TriangleFeature feature = TriangleFeature::face;
  Eigen::Vector3d barycentric = Eigen::Vector3d::Zero(); // of q on (a, b, c)
  double distance = 0.0;                                 // |p - q|, m
};

// The closest point of the triangle (a, b, c) to p (Ericson's regions). A
// degenerate triangle (zero area) is treated by its edges.
ClosestPoint closest_point_on_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                                       const Eigen::Vector3d& b, const Eigen::Vector3d& c);

// The penalty over x = (p, a, b, c) with onset band `band` (m). Zero (and
// no Hessian) at d >= offset and at d = 0, where the direction is
// undefined; projected to PSD unless `exact`.
Result<12> point_triangle_penalty(double stiffness, double offset, const Vector12& x, Want want,
                                  bool exact = false, double band = 0.0);

} // namespace sartor::element
