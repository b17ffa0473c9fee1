// A measured fabric's stretching table (Wang, Ramamoorthi and O'Brien
// 2011) as a function of the Green strains.
// Part of the registry of membrane models (element/membrane_models.hpp).

#include "element/membrane_models.hpp"

#include "common/error.hpp"

namespace sartor::element {

namespace {

const MeasuredStretching& table_of(const MembraneMaterial& material) {
  if (!material.stretching) {
    throw InputError("the measured membrane model needs a fabric with a stretching table "
                     "(a measured material, docs/fabrics.md)");
  }
  return *material.stretching;
}

// The measured table's W(E11, E22, E12) with E11 = (a.a - 1)/2,
// E22 = (b.b - 1)/2, E12 = a.b/2 (chain rule; the Green strain is quadratic).
Density density(const MembraneMaterial& material, const Vector3d& a, const Vector3d& b) {
  const StrainEnergy e = table_of(material).energy(0.5 * (a.squaredNorm() - 1.0),
                                                   0.5 * (b.squaredNorm() - 1.0), 0.5 * a.dot(b));
  const Eigen::Vector3d& g = e.gradient;
  const Eigen::Matrix3d& h = e.hessian;
  const Matrix3d identity = Matrix3d::Identity();
  Density w;
  w.energy = e.energy;
  w.grad_a = g[0] * a + 0.5 * g[2] * b;
  w.grad_b = g[1] * b + 0.5 * g[2] * a;
  w.haa = h(0, 0) * a * a.transpose() + 0.5 * h(0, 2) * (a * b.transpose() + b * a.transpose()) +
          0.25 * h(2, 2) * b * b.transpose() + g[0] * identity;
  w.hbb = h(1, 1) * b * b.transpose() + 0.5 * h(1, 2) * (a * b.transpose() + b * a.transpose()) +
          0.25 * h(2, 2) * a * a.transpose() + g[1] * identity;
  w.hab = h(0, 1) * a * b.transpose() + 0.5 * h(0, 2) * a * a.transpose() +
          0.5 * h(1, 2) * b * b.transpose() + 0.25 * h(2, 2) * b * a.transpose() +
          0.5 * g[2] * identity;
  return w;
}

// The Green strains E11 = (a.a - 1)/2, E22 = (b.b - 1)/2.
Eigen::Vector2d strains(const Vector3d& a, const Vector3d& b) {
  return {0.5 * (a.squaredNorm() - 1.0), 0.5 * (b.squaredNorm() - 1.0)};
}

ColumnTensions tensions(const MembraneMaterial& material, const Vector3d& a, const Vector3d& b) {
  ColumnTensions t;
  // tension_warp = W_0 |a|, tension_weft = W_1 |b|, W_m = dW/dg_m over
  // g = (E11, E22, E12); dg/da = (a, 0, b/2), dg/db = (0, b, a/2).
  const Stretch sa = stretch_of(a);
  const Stretch sb = stretch_of(b);
  const StrainEnergy e = table_of(material).energy(0.5 * (a.squaredNorm() - 1.0),
                                                   0.5 * (b.squaredNorm() - 1.0), 0.5 * a.dot(b));
  const Eigen::Matrix3d& h = e.hessian;
  t.tension << e.gradient[0] * sa.length, e.gradient[1] * sb.length;
  t.per_a.row(0) =
      ((h(0, 0) * a + 0.5 * h(0, 2) * b) * sa.length + e.gradient[0] * sa.unit).transpose();
  t.per_b.row(0) = ((h(0, 1) * b + 0.5 * h(0, 2) * a) * sa.length).transpose();
  t.per_a.row(1) = ((h(0, 1) * a + 0.5 * h(1, 2) * b) * sb.length).transpose();
  t.per_b.row(1) =
      ((h(1, 1) * b + 0.5 * h(1, 2) * a) * sb.length + e.gradient[1] * sb.unit).transpose();
  return t;
}

} // namespace

MembraneModelKernels measured_model() {
  return {"measured", &density, &strains, &tensions};
}

} // namespace sartor::element
