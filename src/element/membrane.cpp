#include "element/membrane.hpp"

#include "element/membrane_models.hpp"

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
  const Density w = membrane_model_kernels(model).density(material, k.a, k.b);
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
  const MembraneModelKernels& kernels = membrane_model_kernels(model);
  const Eigen::Vector2d strains = kernels.strains(k.a, k.b);
  const ColumnTensions tensions = kernels.tensions(material, k.a, k.b);
  MembraneStrain strain;
  strain.shear = k.a.dot(k.b);
  strain.warp = strains[0];
  strain.weft = strains[1];
  strain.tension_warp = tensions.tension[0];
  strain.tension_weft = tensions.tension[1];
  return strain;
}

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
  const MembraneModelKernels& kernels = membrane_model_kernels(model);
  const Density w = kernels.density(material, k.a, k.b);
  const ColumnTensions t = kernels.tensions(material, k.a, k.b);
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

namespace {

// How the columns a, b and their corner weights c, d move when the material
// coordinates move by delta_uv, at fixed positions and non-elastic strains
// (d M^-1 = -M^-1 dM M^-1).
struct ColumnChange {
  Vector3d a, b;
  Eigen::Vector3d c, d;
};
ColumnChange column_change(const TriangleRest& rest, const NonelasticStrain& nonelastic,
                           const Vector9& x, const std::array<Eigen::Vector2d, 3>& delta_uv) {
  const Eigen::Matrix2d unloaded =
      Eigen::Vector2d(1.0 / (1.0 + nonelastic.warp), 1.0 / (1.0 + nonelastic.weft)).asDiagonal();
  const Eigen::Matrix2d delta_b =
      -rest.inverse_material * edge_matrix(delta_uv) * rest.inverse_material * unloaded;
  ColumnChange change;
  corner_weights(delta_b, &change.c, &change.d);
  change.a =
      change.c(0) * x.segment<3>(0) + change.c(1) * x.segment<3>(3) + change.c(2) * x.segment<3>(6);
  change.b =
      change.d(0) * x.segment<3>(0) + change.d(1) * x.segment<3>(3) + change.d(2) * x.segment<3>(6);
  return change;
}

} // namespace

Vector9 membrane_rest_derivative(MembraneModel model, const MembraneMaterial& material,
                                 const std::array<Eigen::Vector2d, 3>& uv,
                                 const NonelasticStrain& nonelastic, const Vector9& x,
                                 const std::array<Eigen::Vector2d, 3>& delta_uv) {
  const TriangleRest rest = triangle_rest(uv);
  const Columns k = columns(rest, nonelastic, x);
  const Density w = membrane_model_kernels(model).density(material, k.a, k.b);
  const ColumnChange dk = column_change(rest, nonelastic, x, delta_uv);
  // The density's gradient moves with the columns: d(dW/da), d(dW/db).
  const Vector3d d_grad_a = w.haa * dk.a + w.hab * dk.b;
  const Vector3d d_grad_b = w.hab.transpose() * dk.a + w.hbb * dk.b;
  const double scale = (1.0 + nonelastic.warp) * (1.0 + nonelastic.weft);
  const double unloaded_area = rest.area * scale;
  const double d_unloaded_area =
      scale * rest.area * (rest.inverse_material * edge_matrix(delta_uv)).trace();
  Vector9 derivative;
  for (int i = 0; i < 3; ++i) {
    derivative.segment<3>(3 * i) = d_unloaded_area * (k.c(i) * w.grad_a + k.d(i) * w.grad_b) +
                                   unloaded_area * (dk.c(i) * w.grad_a + dk.d(i) * w.grad_b +
                                                    k.c(i) * d_grad_a + k.d(i) * d_grad_b);
  }
  return derivative;
}

Eigen::Vector2d membrane_tension_rest_derivative(MembraneModel model,
                                                 const MembraneMaterial& material,
                                                 const std::array<Eigen::Vector2d, 3>& uv,
                                                 const NonelasticStrain& nonelastic,
                                                 const Vector9& x,
                                                 const std::array<Eigen::Vector2d, 3>& delta_uv) {
  const TriangleRest rest = triangle_rest(uv);
  const Columns k = columns(rest, nonelastic, x);
  const ColumnTensions t = membrane_model_kernels(model).tensions(material, k.a, k.b);
  const ColumnChange dk = column_change(rest, nonelastic, x, delta_uv);
  return t.per_a * dk.a + t.per_b * dk.b;
}

} // namespace sartor::element
