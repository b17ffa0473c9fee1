// Saint Venant-Kirchhoff: tension curves of the Green strains, warp-weft
// coupling by the Poisson ratio.
// Part of the registry of membrane models (element/membrane_models.hpp).

#include "element/membrane_models.hpp"

namespace sartor::element {

namespace {

// W = W_warp(E11) + W_weft(E22) + c12 E11 E22 + G (a.b)^2 / 2, with
// E11 = (a.a - 1)/2, E22 = (b.b - 1)/2 and a.b = 2 E12.
Density density(const MembraneMaterial& material, const Vector3d& a, const Vector3d& b) {
  const double e11 = 0.5 * (a.squaredNorm() - 1.0);
  const double e22 = 0.5 * (b.squaredNorm() - 1.0);
  const double g = a.dot(b);
  const double shear = material.shear_modulus;
  const double c12 = coupling_modulus(material);
  const double s11 = material.warp.tension(e11) + c12 * e22;
  const double s22 = material.weft.tension(e22) + c12 * e11;
  const double ku = material.warp.stiffness(e11);
  const double kv = material.weft.stiffness(e22);
  const Matrix3d identity = Matrix3d::Identity();

  Density w;
  w.energy = material.warp.energy_density(e11) + material.weft.energy_density(e22) +
             c12 * e11 * e22 + 0.5 * shear * g * g;
  w.grad_a = s11 * a + shear * g * b;
  w.grad_b = s22 * b + shear * g * a;
  w.haa = ku * a * a.transpose() + s11 * identity + shear * b * b.transpose();
  w.hbb = kv * b * b.transpose() + s22 * identity + shear * a * a.transpose();
  w.hab = c12 * a * b.transpose() + shear * (b * a.transpose() + g * identity);
  return w;
}

// The Green strains E11 = (a.a - 1)/2, E22 = (b.b - 1)/2.
Eigen::Vector2d strains(const Vector3d& a, const Vector3d& b) {
  return {0.5 * (a.squaredNorm() - 1.0), 0.5 * (b.squaredNorm() - 1.0)};
}

ColumnTensions tensions(const MembraneMaterial& material, const Vector3d& a, const Vector3d& b) {
  ColumnTensions t;
  // tension_warp = S11 |a|, S11 = T_warp(E11) + c12 E22, and the same for weft.
  const Stretch sa = stretch_of(a);
  const Stretch sb = stretch_of(b);
  const double e11 = 0.5 * (a.squaredNorm() - 1.0);
  const double e22 = 0.5 * (b.squaredNorm() - 1.0);
  const double c12 = coupling_modulus(material);
  const double s11 = material.warp.tension(e11) + c12 * e22;
  const double s22 = material.weft.tension(e22) + c12 * e11;
  t.tension << s11 * sa.length, s22 * sb.length;
  t.per_a.row(0) = (material.warp.stiffness(e11) * sa.length * a + s11 * sa.unit).transpose();
  t.per_b.row(0) = (c12 * sa.length * b).transpose();
  t.per_a.row(1) = (c12 * sb.length * a).transpose();
  t.per_b.row(1) = (material.weft.stiffness(e22) * sb.length * b + s22 * sb.unit).transpose();
  return t;
}

} // namespace

MembraneModelKernels saint_venant_kirchhoff_model() {
  return {"stvk", &density, &strains, &tensions};
}

} // namespace sartor::element
