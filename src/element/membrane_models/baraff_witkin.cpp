// Baraff and Witkin's membrane: tension curves of the stretches.
// Part of the registry of membrane models (element/membrane_models.hpp).

#include "element/membrane_models.hpp"

namespace sartor::element {

namespace {

// W = W_warp(|a| - 1) + W_weft(|b| - 1) + G (a.b)^2 / 2.
Density density(const MembraneMaterial& material, const Vector3d& a, const Vector3d& b) {
  const Stretch sa = stretch_of(a);
  const Stretch sb = stretch_of(b);
  const double eu = sa.length - 1.0;
  const double ev = sb.length - 1.0;
  const double g = a.dot(b);
  const double shear = material.shear_modulus;
  const double tu = material.warp.tension(eu);
  const double tv = material.weft.tension(ev);
  const double ku = material.warp.stiffness(eu);
  const double kv = material.weft.stiffness(ev);

  Density w;
  w.energy =
      material.warp.energy_density(eu) + material.weft.energy_density(ev) + 0.5 * shear * g * g;
  w.grad_a = tu * sa.unit + shear * g * b;
  w.grad_b = tv * sb.unit + shear * g * a;
  w.haa = ku * sa.unit * sa.unit.transpose() + tu * sa.hessian + shear * b * b.transpose();
  w.hbb = kv * sb.unit * sb.unit.transpose() + tv * sb.hessian + shear * a * a.transpose();
  w.hab = shear * (b * a.transpose() + g * Matrix3d::Identity());
  return w;
}

// The stretches |a| - 1, |b| - 1.
Eigen::Vector2d strains(const Vector3d& a, const Vector3d& b) {
  return {a.norm() - 1.0, b.norm() - 1.0};
}

ColumnTensions tensions(const MembraneMaterial& material, const Vector3d& a, const Vector3d& b) {
  ColumnTensions t;
  // tension_warp = T_warp(|a| - 1), tension_weft = T_weft(|b| - 1).
  const Stretch sa = stretch_of(a);
  const Stretch sb = stretch_of(b);
  t.tension << material.warp.tension(sa.length - 1.0), material.weft.tension(sb.length - 1.0);
  t.per_a.row(0) = material.warp.stiffness(sa.length - 1.0) * sa.unit.transpose();
  t.per_b.row(1) = material.weft.stiffness(sb.length - 1.0) * sb.unit.transpose();
  return t;
}

} // namespace

MembraneModelKernels baraff_witkin_model() {
  return {"baraff_witkin", &density, &strains, &tensions};
}

} // namespace sartor::element
