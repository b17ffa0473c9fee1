#include "element/membrane.hpp"

#include "common/error.hpp"

#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace sartor::element {

namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;

// Material triangles flatter than this (|det| relative to the longest edge
// squared) are rejected.
constexpr double degenerate_ratio = 1e-12;
// A column of F_e shorter than this has no direction (BW model).
constexpr double min_stretch = 1e-12;

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

// The columns of F_e are linear in x: a = sum_i c_i x_i, b = sum_i d_i x_i.
struct Columns {
  Vector3d a;
  Vector3d b;
  Eigen::Vector3d c; // weights of x0, x1, x2 in a, 1/m
  Eigen::Vector3d d; // weights of x0, x1, x2 in b, 1/m
};

Columns columns(const TriangleRest& rest, const NonelasticStrain& nonelastic, const Vector9& x) {
  // F_e = [x1-x0 x2-x0] M^-1 diag(1+n_warp, 1+n_weft)^-1 = [x1-x0 x2-x0] B.
  const Eigen::Matrix2d b_matrix =
      rest.inverse_material *
      Eigen::Vector2d(1.0 / (1.0 + nonelastic.warp), 1.0 / (1.0 + nonelastic.weft)).asDiagonal();
  Columns k;
  k.c << -(b_matrix(0, 0) + b_matrix(1, 0)), b_matrix(0, 0), b_matrix(1, 0);
  k.d << -(b_matrix(0, 1) + b_matrix(1, 1)), b_matrix(0, 1), b_matrix(1, 1);
  k.a = k.c(0) * x.segment<3>(0) + k.c(1) * x.segment<3>(3) + k.c(2) * x.segment<3>(6);
  k.b = k.d(0) * x.segment<3>(0) + k.d(1) * x.segment<3>(3) + k.d(2) * x.segment<3>(6);
  return k;
}

// Length of a column, its unit direction and the Hessian of the length,
// (I - u u^T)/|v|; direction and Hessian are zero below min_stretch.
struct Stretch {
  double length = 0.0;
  Vector3d unit = Vector3d::Zero();
  Matrix3d hessian = Matrix3d::Zero();
};

Stretch stretch_of(const Vector3d& v) {
  Stretch s;
  s.length = v.norm();
  if (s.length < min_stretch) return s;
  s.unit = v / s.length;
  s.hessian = (Matrix3d::Identity() - s.unit * s.unit.transpose()) / s.length;
  return s;
}

// W = W_warp(|a| - 1) + W_weft(|b| - 1) + G (a.b)^2 / 2.
Density baraff_witkin(const MembraneMaterial& material, const Vector3d& a, const Vector3d& b) {
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

// c12 = poisson sqrt(k_warp k_weft), initial moduli.
double coupling_modulus(const MembraneMaterial& material) {
  return material.poisson *
         std::sqrt(material.warp.initial_modulus() * material.weft.initial_modulus());
}

// W = W_warp(E11) + W_weft(E22) + c12 E11 E22 + G (a.b)^2 / 2, with
// E11 = (a.a - 1)/2, E22 = (b.b - 1)/2 and a.b = 2 E12.
Density saint_venant_kirchhoff(const MembraneMaterial& material, const Vector3d& a,
                               const Vector3d& b) {
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

const MeasuredStretching& table_of(const MembraneMaterial& material) {
  if (!material.stretching) {
    throw InputError("the measured membrane model needs a fabric with a stretching table "
                     "(a measured material, docs/fabrics.md)");
  }
  return *material.stretching;
}

// The measured table's W(E11, E22, E12) with E11 = (a.a - 1)/2,
// E22 = (b.b - 1)/2, E12 = a.b/2 (chain rule; the Green strain is quadratic).
Density measured(const MembraneMaterial& material, const Vector3d& a, const Vector3d& b) {
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

Density density(MembraneModel model, const MembraneMaterial& material, const Vector3d& a,
                const Vector3d& b) {
  switch (model) {
  case MembraneModel::measured:
    return measured(material, a, b);
  case MembraneModel::baraff_witkin:
    return baraff_witkin(material, a, b);
  case MembraneModel::saint_venant_kirchhoff:
    return saint_venant_kirchhoff(material, a, b);
  }
  return {};
}

std::string corners_text(const std::array<Eigen::Vector2d, 3>& uv) {
  std::ostringstream text;
  text.precision(10);
  text << "(";
  for (std::size_t i = 0; i < uv.size(); ++i) {
    text << (i ? "), (" : "") << uv[i].x() << ", " << uv[i].y();
  }
  text << ")";
  return text.str();
}

} // namespace

TriangleRest triangle_rest(const std::array<Eigen::Vector2d, 3>& uv) {
  const Eigen::Vector2d du1 = uv[1] - uv[0];
  const Eigen::Vector2d du2 = uv[2] - uv[0];
  Eigen::Matrix2d material;
  material << du1, du2;
  const double det = material.determinant();
  const double longest =
      std::max({du1.squaredNorm(), du2.squaredNorm(), (uv[2] - uv[1]).squaredNorm()});
  if (!(std::abs(det) > degenerate_ratio * longest) || !std::isfinite(det)) {
    throw InputError("degenerate triangle in material coordinates " + corners_text(uv) +
                     " m: its corners must not be collinear or coincide");
  }
  TriangleRest rest;
  rest.inverse_material = material.inverse();
  rest.area = 0.5 * std::abs(det);
  return rest;
}

Result<9> membrane(MembraneModel model, const MembraneMaterial& material, const TriangleRest& rest,
                   const NonelasticStrain& nonelastic, const Vector9& x, Want want) {
  const Columns k = columns(rest, nonelastic, x);
  const Density w = density(model, material, k.a, k.b);
  const double unloaded_area = rest.area * (1.0 + nonelastic.warp) * (1.0 + nonelastic.weft);

  Result<9> result;
  result.energy = unloaded_area * w.energy;
  result.gradient.setZero();
  result.hessian.setZero();
  if (want == Want::energy) return result;

  for (int i = 0; i < 3; ++i) {
    result.gradient.segment<3>(3 * i) = unloaded_area * (k.c(i) * w.grad_a + k.d(i) * w.grad_b);
  }
  if (want == Want::gradient) return result;

  // Block (i, j) = c_i c_j Haa + c_i d_j Hab + d_i c_j Hab^T + d_i d_j Hbb,
  // symmetrised to the last bit.
  Eigen::Matrix<double, 9, 9> h;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      h.block<3, 3>(3 * i, 3 * j) = k.c(i) * k.c(j) * w.haa + k.c(i) * k.d(j) * w.hab +
                                    k.d(i) * k.c(j) * w.hab.transpose() + k.d(i) * k.d(j) * w.hbb;
    }
  }
  result.hessian = (0.5 * unloaded_area) * (h + h.transpose());
  return result;
}

MembraneStrain membrane_strain(MembraneModel model, const MembraneMaterial& material,
                               const TriangleRest& rest, const NonelasticStrain& nonelastic,
                               const Vector9& x) {
  const Columns k = columns(rest, nonelastic, x);
  MembraneStrain strain;
  strain.shear = k.a.dot(k.b);
  switch (model) {
  case MembraneModel::baraff_witkin:
    strain.warp = k.a.norm() - 1.0;
    strain.weft = k.b.norm() - 1.0;
    strain.tension_warp = material.warp.tension(strain.warp);
    strain.tension_weft = material.weft.tension(strain.weft);
    break;
  case MembraneModel::saint_venant_kirchhoff: {
    strain.warp = 0.5 * (k.a.squaredNorm() - 1.0);
    strain.weft = 0.5 * (k.b.squaredNorm() - 1.0);
    const double c12 = coupling_modulus(material);
    strain.tension_warp = (material.warp.tension(strain.warp) + c12 * strain.weft) * k.a.norm();
    strain.tension_weft = (material.weft.tension(strain.weft) + c12 * strain.warp) * k.b.norm();
    break;
  }
  case MembraneModel::measured: {
    strain.warp = 0.5 * (k.a.squaredNorm() - 1.0);
    strain.weft = 0.5 * (k.b.squaredNorm() - 1.0);
    const StrainEnergy e = table_of(material).energy(strain.warp, strain.weft, 0.5 * strain.shear);
    strain.tension_warp = e.gradient[0] * k.a.norm();
    strain.tension_weft = e.gradient[1] * k.b.norm();
    break;
  }
  }
  return strain;
}

namespace {

// The tensions of membrane_strain as functions of the columns a and b of F_e,
// with their gradients: row r of per_a is d tension_r / d a.
struct ColumnTensions {
  Eigen::Vector2d tension;
  Eigen::Matrix<double, 2, 3> per_a = Eigen::Matrix<double, 2, 3>::Zero();
  Eigen::Matrix<double, 2, 3> per_b = Eigen::Matrix<double, 2, 3>::Zero();
};

ColumnTensions column_tensions(MembraneModel model, const MembraneMaterial& material,
                               const Vector3d& a, const Vector3d& b) {
  ColumnTensions t;
  switch (model) {
  case MembraneModel::baraff_witkin: {
    // tension_warp = T_warp(|a| - 1), tension_weft = T_weft(|b| - 1).
    const Stretch sa = stretch_of(a);
    const Stretch sb = stretch_of(b);
    t.tension << material.warp.tension(sa.length - 1.0), material.weft.tension(sb.length - 1.0);
    t.per_a.row(0) = material.warp.stiffness(sa.length - 1.0) * sa.unit.transpose();
    t.per_b.row(1) = material.weft.stiffness(sb.length - 1.0) * sb.unit.transpose();
    break;
  }
  case MembraneModel::saint_venant_kirchhoff: {
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
    break;
  }
  case MembraneModel::measured: {
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
    break;
  }
  }
  return t;
}

} // namespace

MembraneCreepSensitivity membrane_creep_sensitivity(MembraneModel model,
                                                    const MembraneMaterial& material,
                                                    const TriangleRest& rest,
                                                    const NonelasticStrain& nonelastic,
                                                    const Vector9& x) {
  // a = F e1 / (1 + n_warp) and b = F e2 / (1 + n_weft), so da/dn_warp =
  // -a / (1 + n_warp) and db/dn_weft = -b / (1 + n_weft). The force of corner
  // i is A [(1 + n_weft) c0_i dW/da + (1 + n_warp) d0_i dW/db] with the
  // weights c0 = (1 + n_warp) c, d0 = (1 + n_weft) d independent of n.
  const Columns k = columns(rest, nonelastic, x);
  const Density w = density(model, material, k.a, k.b);
  const ColumnTensions t = column_tensions(model, material, k.a, k.b);
  const double stretch_warp = 1.0 + nonelastic.warp;
  const double stretch_weft = 1.0 + nonelastic.weft;
  const Vector3d a_per_warp = -k.a / stretch_warp;
  const Vector3d b_per_weft = -k.b / stretch_weft;

  MembraneCreepSensitivity s;
  s.tension = t.tension;
  for (int i = 0; i < 3; ++i) {
    s.tension_per_position.middleCols<3>(3 * i) = k.c(i) * t.per_a + k.d(i) * t.per_b;
    // c0_i da/dn_warp = -c_i a: the 1/(1 + n_warp) cancels (and so for weft).
    s.force_per_nonelastic.block<3, 1>(3 * i, 0) =
        rest.area * stretch_weft *
        (k.d(i) * w.grad_b - (k.c(i) * w.haa + k.d(i) * w.hab.transpose()) * k.a);
    s.force_per_nonelastic.block<3, 1>(3 * i, 1) =
        rest.area * stretch_warp * (k.c(i) * w.grad_a - (k.c(i) * w.hab + k.d(i) * w.hbb) * k.b);
  }
  s.tension_per_nonelastic.col(0) = t.per_a * a_per_warp;
  s.tension_per_nonelastic.col(1) = t.per_b * b_per_weft;
  return s;
}

namespace {

// [du1 - du0, du2 - du0; dv1 - dv0, dv2 - dv0]: the change of the material
// edge matrix M.
Eigen::Matrix2d edge_matrix(const std::array<Eigen::Vector2d, 3>& uv) {
  Eigen::Matrix2d m;
  m << uv[1] - uv[0], uv[2] - uv[0];
  return m;
}

// Corner weights (c, d) of the columns a, b from B = M^-1 diag(1/(1 + n)).
void corner_weights(const Eigen::Matrix2d& b_matrix, Vector3d* c, Vector3d* d) {
  *c << -(b_matrix(0, 0) + b_matrix(1, 0)), b_matrix(0, 0), b_matrix(1, 0);
  *d << -(b_matrix(0, 1) + b_matrix(1, 1)), b_matrix(0, 1), b_matrix(1, 1);
}

} // namespace

double triangle_area_derivative(const std::array<Eigen::Vector2d, 3>& uv,
                                const std::array<Eigen::Vector2d, 3>& delta_uv) {
  const TriangleRest rest = triangle_rest(uv);
  return rest.area * (rest.inverse_material * edge_matrix(delta_uv)).trace();
}

Vector9 membrane_rest_derivative(MembraneModel model, const MembraneMaterial& material,
                                 const std::array<Eigen::Vector2d, 3>& uv,
                                 const NonelasticStrain& nonelastic, const Vector9& x,
                                 const std::array<Eigen::Vector2d, 3>& delta_uv) {
  const TriangleRest rest = triangle_rest(uv);
  const Columns k = columns(rest, nonelastic, x);
  const Density w = density(model, material, k.a, k.b);
  const Eigen::Matrix2d unloaded =
      Eigen::Vector2d(1.0 / (1.0 + nonelastic.warp), 1.0 / (1.0 + nonelastic.weft)).asDiagonal();
  const Eigen::Matrix2d delta_m = edge_matrix(delta_uv);
  const Eigen::Matrix2d delta_b =
      -rest.inverse_material * delta_m * rest.inverse_material * unloaded;
  Vector3d dc, dd;
  corner_weights(delta_b, &dc, &dd);
  const Vector3d da = dc(0) * x.segment<3>(0) + dc(1) * x.segment<3>(3) + dc(2) * x.segment<3>(6);
  const Vector3d db = dd(0) * x.segment<3>(0) + dd(1) * x.segment<3>(3) + dd(2) * x.segment<3>(6);
  // The density's gradient moves with the columns: d(dW/da), d(dW/db).
  const Vector3d d_grad_a = w.haa * da + w.hab * db;
  const Vector3d d_grad_b = w.hab.transpose() * da + w.hbb * db;
  const double scale = (1.0 + nonelastic.warp) * (1.0 + nonelastic.weft);
  const double unloaded_area = rest.area * scale;
  const double d_unloaded_area = scale * rest.area * (rest.inverse_material * delta_m).trace();
  Vector9 derivative;
  for (int i = 0; i < 3; ++i) {
    derivative.segment<3>(3 * i) = d_unloaded_area * (k.c(i) * w.grad_a + k.d(i) * w.grad_b) +
                                   unloaded_area * (dc(i) * w.grad_a + dd(i) * w.grad_b +
                                                    k.c(i) * d_grad_a + k.d(i) * d_grad_b);
  }
  return derivative;
}

} // namespace sartor::element
