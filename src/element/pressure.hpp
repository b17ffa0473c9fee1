#pragma once
// Follower pressure on a triangle: p times its current area normal,
// (x1 - x0) x (x2 - x0) / 2, shared equally by the three vertices. The load
// follows the surface, so a triangle's Jacobian is not symmetric and a
// triangle has no energy of its own. Summed over a surface whose boundary is
// held (or that has none), the loads on the free vertices are the gradient
// of p times the enclosed volume, the sum of the tetrahedra each triangle
// spans with a fixed centre (docs/drape.md#pressure-as-a-potential): the
// unsymmetric parts cancel between the triangles around each free vertex.

#include <Eigen/Core>

namespace sartor::element {

struct PressureLoad {
  Eigen::Matrix<double, 9, 1> force;    // N, on (x0, x1, x2)
  Eigen::Matrix<double, 9, 9> jacobian; // d force / d x, N/m
};

// p in Pa (N/m^2), positive along the normal of the corner order given.
// jacobian(3i + r, 3j + s) = d force_(3i + r) / d x_(3j + s).
PressureLoad follower_pressure(double pressure, const Eigen::Matrix<double, 9, 1>& x);

// Signed volume of the tetrahedron (centre, x0, x1, x2), m^3: positive when
// the centre lies behind the triangle's normal side.
double spanned_volume(const Eigen::Matrix<double, 9, 1>& x, const Eigen::Vector3d& centre);

} // namespace sartor::element
