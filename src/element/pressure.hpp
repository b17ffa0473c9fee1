#pragma once
// Follower pressure on a triangle: p times its current area normal,
// (x1 - x0) x (x2 - x0) / 2, shared equally by the three vertices. The load
// follows the surface, so its Jacobian is not symmetric; there is no energy.

#include <Eigen/Core>

namespace sartor::element {

struct PressureLoad {
  Eigen::Matrix<double, 9, 1> force;    // N, on (x0, x1, x2)
  Eigen::Matrix<double, 9, 9> jacobian; // d force / d x, N/m
};

// p in Pa (N/m^2), positive along the normal of the corner order given.
// jacobian(3i + r, 3j + s) = d force_(3i + r) / d x_(3j + s).
PressureLoad follower_pressure(double pressure, const Eigen::Matrix<double, 9, 1>& x);

} // namespace sartor::element
