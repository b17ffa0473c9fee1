#pragma once
// The design sensitivity's mixed derivatives (docs/sensitivity.md) of the
// hinge, patch and seam kernels: how an element's force (its energy
// gradient) changes with its rest data at fixed positions,
//     d/de grad E(x; rest(X + e dX)) at e = 0.
// The membrane's is in element/membrane.hpp. Each is exact: the kernels'
// forces are differentiated by hand in their rest data, and the hinge's rest
// data (weight, cotangent matrix) in the material coordinates by forward-mode
// automatic differentiation (common/autodiff.hpp) through the formulas of
// hinge_rest.

#include "element/bending.hpp"
#include "element/patch_bending.hpp"

#include <Eigen/Core>

#include <array>

namespace sartor::element {

// The change of a hinge's rest data when the two triangles' material
// coordinates (as hinge_rest takes them) move by delta_first, delta_second.
// The rest angle is a property of the crease, not of the pattern: unchanged.
HingeRest hinge_rest_derivative(const std::array<Eigen::Vector2d, 3>& first,
                                const std::array<Eigen::Vector2d, 3>& second,
                                const std::array<Eigen::Vector2d, 3>& delta_first,
                                const std::array<Eigen::Vector2d, 3>& delta_second);

// The change of the hinge's force for a change `delta` of its rest data (as
// hinge_rest_derivative gives: weight, quadratic; rest_angle ignored).
Vector12 bending_rest_derivative(BendingModel model, double stiffness, const HingeRest& rest,
                                 const HingeRest& delta, const Vector12& x);

// The change of a patch's rest data: its area and its curvature weights.
struct PatchRestChange {
  double area = 0.0;                                                           // m^2
  Eigen::Matrix<double, 3, 12> weights = Eigen::Matrix<double, 3, 12>::Zero(); // 1/m^2
};

// The change of the patch triangle's force for a change `delta` of its rest
// data (rigidity, rest curvature and curves held).
Vector36 patch_bending_rest_derivative(const PatchRest& rest, const PatchRestChange& delta,
                                       const Vector36& x);

// The change of a seam spring's force when its stiffness changes by
// `delta_stiffness` and (vertex-to-edge) its edge parameter by `delta_s`.
Eigen::Matrix<double, 6, 1>
seam_vertex_vertex_rest_derivative(double delta_stiffness, const Eigen::Matrix<double, 6, 1>& x);
Eigen::Matrix<double, 9, 1> seam_vertex_edge_rest_derivative(double stiffness, double s,
                                                             double delta_stiffness, double delta_s,
                                                             const Eigen::Matrix<double, 9, 1>& x);

} // namespace sartor::element
