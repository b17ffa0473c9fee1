#pragma once
// The registry of membrane models (element/membrane.hpp, MembraneModel).
//
// A membrane model is the elastic energy density W (J/m^2) of the columns
// a = F_e e1 and b = F_e e2 of the elastic deformation gradient (warp and
// weft), with its derivatives, and the warp and weft strains and tensions it
// reports, with the tensions' derivatives (for the monolithic creep
// coupling). The element kernels (membrane.cpp) do the rest: the element's
// energy, forces and Hessian, the creep and rest-coordinate sensitivities.
//
// A new model is one file in membrane_models/ that defines a function
// returning its MembraneModelKernels, and one line in
// register_membrane_models (membrane_models.cpp); `--membrane-model NAME`
// then selects it.

#include "element/membrane.hpp"

#include <Eigen/Core>

#include <string>

namespace sartor::element {

using Eigen::Matrix3d;
using Eigen::Vector3d;

// The elastic energy density W (J/m^2) as a function of the columns
// a = F_e e1 and b = F_e e2, with its derivatives: gradient (dW/da, dW/db)
// and the 3x3 blocks of the Hessian (Hab = d^2 W / da db^T).
struct Density {
  double energy = 0.0;
  Vector3d grad_a = Vector3d::Zero();
  Vector3d grad_b = Vector3d::Zero();
  Matrix3d haa = Matrix3d::Zero();
  Matrix3d hab = Matrix3d::Zero();
  Matrix3d hbb = Matrix3d::Zero();
};

// The tensions a model reports (MembraneStrain::tension_warp, tension_weft)
// as functions of the columns a and b of F_e, with their gradients: row r
// of per_a is d tension_r / d a.
struct ColumnTensions {
  Eigen::Vector2d tension;
  Eigen::Matrix<double, 2, 3> per_a = Eigen::Matrix<double, 2, 3>::Zero();
  Eigen::Matrix<double, 2, 3> per_b = Eigen::Matrix<double, 2, 3>::Zero();
};

struct MembraneModelKernels {
  std::string name; // as --membrane-model and case files name it
  Density (*density)(const MembraneMaterial& material, const Vector3d& a, const Vector3d& b);
  // The warp and weft strains the model's tension curves take (the
  // stretches |a| - 1, |b| - 1, or the Green strains).
  Eigen::Vector2d (*strains)(const Vector3d& a, const Vector3d& b);
  ColumnTensions (*tensions)(const MembraneMaterial& material, const Vector3d& a,
                             const Vector3d& b);
};

// The kernels of a registered model.
const MembraneModelKernels& membrane_model_kernels(MembraneModel model);

// Helpers of the models.
// Length of a column, its unit direction and the Hessian of the length,
// (I - u u^T)/|v|; direction and Hessian are zero below min_stretch.
struct Stretch {
  double length = 0.0;
  Vector3d unit = Vector3d::Zero();
  Matrix3d hessian = Matrix3d::Zero();
};

Stretch stretch_of(const Vector3d& v);

// c12 = poisson sqrt(k_warp k_weft), initial moduli.
double coupling_modulus(const MembraneMaterial& material);

// The built-in models, one file each (membrane_models/).
MembraneModelKernels baraff_witkin_model();
MembraneModelKernels saint_venant_kirchhoff_model();
MembraneModelKernels measured_model();

} // namespace sartor::element
