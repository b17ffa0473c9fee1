#include "element/patch_bending.hpp"

#include "common/autodiff.hpp"
#include "common/error.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <Eigen/LU>
#include <Eigen/QR>
#include <Eigen/SVD>

#include <algorithm>
#include <cmath>
#include <optional>
#include <sstream>

namespace sartor::element {

namespace {

using Eigen::Matrix3d;
using Eigen::Vector2d;
using Eigen::Vector3d;
using Matrix36 = Eigen::Matrix<double, 36, 36>;
using Jacobian9 = Eigen::Matrix<double, 3, 9>; // of a 3-vector with respect to x0, x1, x2

// As the hinges': triangles flatter than this (twice the area relative to
// the longest edge squared) have no normal.
constexpr double degenerate_ratio = 1e-12;

template <typename Scalar>
using Point = PatchPoint<Scalar>;
template <typename Scalar>
using Matrix3 = Eigen::Matrix<Scalar, 3, 3>;
template <typename Scalar>
using Vector3 = Eigen::Matrix<Scalar, 3, 1>;

template <typename Scalar>
Scalar cross2(const Point<Scalar>& a, const Point<Scalar>& b) {
  return a.x() * b.y() - a.y() * b.x();
}

Matrix3d cross(const Vector3d& v) {
  Matrix3d m;
  m << 0.0, -v.z(), v.y(), v.z(), 0.0, -v.x(), -v.y(), v.x(), 0.0;
  return m;
}

template <typename Scalar>
std::array<Vector2d, 3> triangle_values(const PatchTriangle<Scalar>& uv) {
  std::array<Vector2d, 3> values;
  for (std::size_t k = 0; k < 3; ++k)
    values[k] = {value_of(uv[k].x()), value_of(uv[k].y())};
  return values;
}

std::string point_list(const std::array<Vector2d, 3>& uv) {
  std::ostringstream text;
  text.precision(10);
  for (std::size_t k = 0; k < 3; ++k)
    text << (k ? ", (" : "(") << uv[k].x() << ", " << uv[k].y() << ")";
  return text.str();
}

// The triangle's barycentric coordinates: lambda(p) = gradients^T (p - p0) +
// (1, 0, 0) shifted; gradients.col(k) = grad lambda_k.
template <typename Scalar>
struct Barycentric {
  Point<Scalar> origin;
  Eigen::Matrix<Scalar, 2, 3> gradients;
  Vector3<Scalar> at(const Point<Scalar>& p) const {
    Vector3<Scalar> lambda = gradients.transpose() * (p - origin);
    lambda(0) += 1.0;
    return lambda;
  }
};

template <typename Scalar>
Barycentric<Scalar> barycentric(const PatchTriangle<Scalar>& uv) {
  Eigen::Matrix<Scalar, 2, 2> frame;
  frame.col(0) = uv[1] - uv[0];
  frame.col(1) = uv[2] - uv[0];
  const Eigen::Matrix<Scalar, 2, 2> inverse = frame.inverse();
  Barycentric<Scalar> b;
  b.origin = uv[0];
  b.gradients.col(1) = inverse.row(0).transpose();
  b.gradients.col(2) = inverse.row(1).transpose();
  b.gradients.col(0) = -b.gradients.col(1) - b.gradients.col(2);
  return b;
}

// (d_uu, d_vv, d_uv) of lambda_i lambda_j.
template <typename Scalar>
Vector3<Scalar> second_derivatives(const Point<Scalar>& gi, const Point<Scalar>& gj) {
  return {2.0 * gi.x() * gj.x(), 2.0 * gi.y() * gj.y(), gi.x() * gj.y() + gi.y() * gj.x()};
}

void check_rigidity(const BendingRigidity& d) {
  const Matrix3d m = d.matrix();
  const bool finite = m.allFinite();
  const bool definite = d.warp >= 0.0 && d.weft >= 0.0 && d.twist >= 0.0 &&
                        d.coupling * d.coupling <= d.warp * d.weft;
  if (!finite || !definite) {
    std::ostringstream text;
    text << "bending rigidity: warp " << d.warp << ", weft " << d.weft << ", coupling "
         << d.coupling << ", twist " << d.twist
         << " N m must be finite, non-negative, with coupling^2 <= warp * weft";
    throw InputError(text.str());
  }
}

// Row of the free-edge condition M_nn = 0 on the edge coefficients, scaled to
// order one (the node rows are of order one).
template <typename Scalar>
Eigen::Matrix<Scalar, 1, 3> free_edge_row(const Point<Scalar>& edge, const Matrix3<Scalar>& second,
                                          const Matrix3d& rigidity) {
  const Point<Scalar> normal = Point<Scalar>(edge.y(), -edge.x()).normalized();
  const Eigen::Matrix<Scalar, 1, 3> moment_nn(normal.x() * normal.x(), normal.y() * normal.y(),
                                              2.0 * normal.x() * normal.y());
  const Matrix3<Scalar> voigt = Vector3<Scalar>(1.0, 1.0, 2.0).asDiagonal() * second;
  Eigen::Matrix<Scalar, 1, 3> row = moment_nn * rigidity.cast<Scalar>() * voigt;
  // Without rigidity the condition is kappa_nn = 0.
  if (!(row.cwiseAbs().maxCoeff() > 0.0)) row = moment_nn * voigt;
  return row / row.cwiseAbs().maxCoeff();
}

template <typename Scalar>
void check_triangle(const PatchTriangle<Scalar>& uv, Scalar twice_area_of) {
  const std::array<Vector2d, 3> triangle = triangle_values(uv);
  const double twice_area = value_of(twice_area_of);
  const double longest = std::max({(triangle[1] - triangle[0]).squaredNorm(),
                                   (triangle[2] - triangle[0]).squaredNorm(),
                                   (triangle[2] - triangle[1]).squaredNorm()});
  if (!(std::abs(twice_area) > degenerate_ratio * longest) || !std::isfinite(twice_area)) {
    throw InputError("bending patch: degenerate triangle in material coordinates " +
                     point_list(triangle) + " m");
  }
}

// Unit in-plane normal of edge k (opposite corner k), pointing out of the triangle.
template <typename Scalar>
Point<Scalar> outward_normal(const PatchTriangle<Scalar>& triangle, int k) {
  const Point<Scalar> edge =
      triangle[std::size_t((k + 2) % 3)] - triangle[std::size_t((k + 1) % 3)];
  Point<Scalar> normal = Point<Scalar>(edge.y(), -edge.x()).normalized();
  if (normal.dot(triangle[std::size_t(k)] - triangle[std::size_t((k + 1) % 3)]) > 0.0)
    normal = -normal;
  return normal;
}

// Whether a patch's edge system is solved by LU (else by the Tikhonov
// filter of edge_coefficients, with tau^2 of tikhonov_tau2).
bool well_conditioned(const Eigen::JacobiSVD<Matrix3d>& svd) {
  const Vector3d& sigma = svd.singularValues();
  return sigma(2) >= ill_conditioned * sigma(0);
}

double tikhonov_tau2(const Eigen::JacobiSVD<Matrix3d>& svd) {
  return std::pow(ill_conditioned * svd.singularValues()(0), 2);
}

Eigen::Matrix<double, 3, 6> regularised_solve(const Eigen::JacobiSVD<Matrix3d>& svd,
                                              const Eigen::Matrix<double, 3, 6>& nodes) {
  const Vector3d& sigma = svd.singularValues();
  const Vector3d filter = sigma.array() / (sigma.array().square() + tikhonov_tau2(svd));
  return svd.matrixV() * filter.asDiagonal() * svd.matrixU().transpose() * nodes;
}

// The edge coefficients c of the patch quadratic, system * c = nodes (as
// weights over the six nodes): by LU, or where the system is ill-conditioned
// in the least-squares sense with a Tikhonov term tau = ill_conditioned
// sigma_max, V diag(sigma / (sigma^2 + tau^2)) U^T nodes.
Eigen::Matrix<double, 3, 6> edge_coefficients(const Matrix3d& system,
                                              const Eigen::Matrix<double, 3, 6>& nodes) {
  const Eigen::JacobiSVD<Matrix3d> svd(system, Eigen::ComputeFullU | Eigen::ComputeFullV);
  if (well_conditioned(svd)) return system.partialPivLu().solve(nodes);
  return regularised_solve(svd, nodes);
}

// Their derivative: c = A^-1 N moves by A^-1 (dN - dA c); the regularised c
// = (A^T A + tau^2)^-1 A^T N (the same as the SVD's filter) by
// (A^T A + tau^2)^-1 (dA^T N + A^T dN - (dA^T A + A^T dA + d tau^2) c), with
// d sigma_max = u_1^T dA v_1 (a simple largest singular value).
Eigen::Matrix<AutoDiff, 3, 6> edge_coefficients(const Matrix3<AutoDiff>& moving_system,
                                                const Eigen::Matrix<AutoDiff, 3, 6>& moving_nodes) {
  const Matrix3d system = values(moving_system), d_system = derivatives(moving_system);
  const Eigen::Matrix<double, 3, 6> nodes = values(moving_nodes),
                                    d_nodes = derivatives(moving_nodes);
  const Eigen::JacobiSVD<Matrix3d> svd(system, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix<double, 3, 6> c, dc;
  if (well_conditioned(svd)) {
    const Eigen::PartialPivLU<Matrix3d> lu = system.partialPivLu();
    c = lu.solve(nodes);
    dc = lu.solve(d_nodes - d_system * c);
  } else {
    c = regularised_solve(svd, nodes);
    const double tau2 = tikhonov_tau2(svd);
    const double sigma_max = svd.singularValues()(0);
    const double d_sigma = svd.matrixU().col(0).dot(d_system * svd.matrixV().col(0));
    const double d_tau2 = 2.0 * ill_conditioned * ill_conditioned * sigma_max * d_sigma;
    const Matrix3d normal = system.transpose() * system + tau2 * Matrix3d::Identity();
    const Matrix3d d_normal = d_system.transpose() * system + system.transpose() * d_system +
                              d_tau2 * Matrix3d::Identity();
    dc = normal.partialPivLu().solve(d_system.transpose() * nodes + system.transpose() * d_nodes -
                                     d_normal * c);
  }
  Eigen::Matrix<AutoDiff, 3, 6> result;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 6; ++j)
      result(i, j) = seeded(c(i, j), dc(i, j));
  return result;
}

constexpr int nodes = 12;
const Vector3d voigt_scale(1.0, 1.0, 2.0); // engineering shear: k = (k_uu, k_vv, 2 k_uv)

} // namespace

Matrix3d BendingRigidity::matrix() const {
  Matrix3d d;
  d << warp, coupling, 0.0, coupling, weft, 0.0, 0.0, 0.0, twist;
  return d;
}

template <typename Scalar>
PatchPoint<Scalar> node_across(const PatchPoint<Scalar>& a, const PatchPoint<Scalar>& b,
                               const PatchPoint<Scalar>& c, const PatchPoint<Scalar>& a_other,
                               const PatchPoint<Scalar>& b_other,
                               const PatchPoint<Scalar>& p_other) {
  using std::abs;
  const Point<Scalar> edge_other = b_other - a_other;
  const Scalar length2 = edge_other.squaredNorm();
  const Scalar along = (p_other - a_other).dot(edge_other) / length2;
  const Scalar off = abs(cross2<Scalar>(edge_other, p_other - a_other)) / length2;
  const Point<Scalar> edge = b - a;
  Point<Scalar> normal(-edge.y(), edge.x()); // |normal| = |edge|
  if (normal.dot(c - a) > 0.0) normal = -normal;
  return a + along * edge + off * normal;
}

namespace {

// The rows of the patch's edge system for the nodes across (and, for
// boundary edges, the free-edge condition), with their right-hand sides.
template <typename Scalar>
void edge_system(const PatchTriangle<Scalar>& triangle, const PatchTriangle<Scalar>& across,
                 const std::array<bool, 3>& has_node, const BendingRigidity& rigidity,
                 const Barycentric<Scalar>& lambda, Matrix3<Scalar>* system,
                 Eigen::Matrix<Scalar, 3, 6>* right_side) {
  Matrix3<Scalar> second; // column e: (d_uu, d_vv, d_uv) of the edge function of edge e
  for (int e = 0; e < 3; ++e)
    second.col(e) = second_derivatives<Scalar>(lambda.gradients.col((e + 1) % 3),
                                               lambda.gradients.col((e + 2) % 3));
  right_side->setZero();
  for (int k = 0; k < 3; ++k) {
    const int i = (k + 1) % 3, j = (k + 2) % 3;
    if (has_node[std::size_t(k)]) {
      const Vector3<Scalar> at = lambda.at(across[std::size_t(k)]);
      if (!(at(k) < 0.0)) {
        throw InputError("bending patch: the node across an edge of triangle " +
                         point_list(triangle_values(triangle)) +
                         " is not on the edge's other side");
      }
      for (int e = 0; e < 3; ++e)
        (*system)(k, e) = at((e + 1) % 3) * at((e + 2) % 3);
      (*right_side)(k, 3 + k) = 1.0;
      right_side->template block<1, 3>(k, 0) = -at.transpose();
    } else {
      system->row(k) = free_edge_row<Scalar>(triangle[std::size_t(j)] - triangle[std::size_t(i)],
                                             second, rigidity.matrix());
    }
  }
}

} // namespace

template <typename Scalar>
EdgeSlopes<Scalar>
midedge_slopes(const PatchTriangle<Scalar>& triangle, const PatchTriangle<Scalar>& across,
               const std::array<bool, 3>& has_node, const BendingRigidity& rigidity) {
  check_rigidity(rigidity);
  check_triangle(triangle, cross2<Scalar>(triangle[1] - triangle[0], triangle[2] - triangle[0]));
  const Barycentric<Scalar> lambda = barycentric(triangle);
  // system * c = right_side * x: one row per edge, c the edge coefficients.
  Matrix3<Scalar> system;
  Eigen::Matrix<Scalar, 3, 6> right_side;
  edge_system(triangle, across, has_node, rigidity, lambda, &system, &right_side);
  const Eigen::Matrix<Scalar, 3, 6> coefficients = edge_coefficients(system, right_side);
  // The quadratic's gradient at the midpoint of edge k (lambda_k = 0,
  // the others 1/2) along the edge's outward normal.
  EdgeSlopes<Scalar> slopes;
  for (int k = 0; k < 3; ++k) {
    const Point<Scalar> outward = outward_normal(triangle, k);
    Eigen::Matrix<Scalar, 1, 6> slope = Eigen::Matrix<Scalar, 1, 6>::Zero();
    for (int c = 0; c < 3; ++c)
      slope(c) = outward.dot(lambda.gradients.col(c));
    for (int e = 0; e < 3; ++e) {
      const int a = (e + 1) % 3, b = (e + 2) % 3;
      const Vector3d mid = Vector3d::Constant(0.5) - 0.5 * Vector3d::Unit(k);
      const Point<Scalar> gradient =
          mid(a) * lambda.gradients.col(b) + mid(b) * lambda.gradients.col(a);
      slope += outward.dot(gradient) * coefficients.row(e);
    }
    slopes[std::size_t(k)] = slope;
  }
  return slopes;
}

template <typename Scalar>
EdgeSlopes<Scalar> plane_slopes(const PatchTriangle<Scalar>& triangle) {
  check_triangle(triangle, cross2<Scalar>(triangle[1] - triangle[0], triangle[2] - triangle[0]));
  const Barycentric<Scalar> lambda = barycentric(triangle);
  EdgeSlopes<Scalar> slopes;
  for (int k = 0; k < 3; ++k) {
    slopes[std::size_t(k)].setZero();
    for (int c = 0; c < 3; ++c)
      slopes[std::size_t(k)](c) = outward_normal(triangle, k).dot(lambda.gradients.col(c));
  }
  return slopes;
}

template <typename Scalar>
PatchWeights<Scalar>
patch_weights(const PatchTriangle<Scalar>& triangle,
              const std::array<Eigen::Matrix<Scalar, 1, 12>, 3>& normal_slopes) {
  using std::abs;
  const Scalar twice_area = cross2<Scalar>(triangle[1] - triangle[0], triangle[2] - triangle[0]);
  check_triangle(triangle, twice_area);
  PatchWeights<Scalar> rest;
  rest.area = 0.5 * abs(twice_area);
  // H_ab = (1/A) sum_k |e_k| sym(g_k,a nu_k,b), g_k = x_,u at edge k's
  // midpoint: along the edge the chord's slope (exact for a quadratic), across
  // it the shared normal slope.
  rest.weights.setZero();
  for (int k = 0; k < 3; ++k) {
    const int i = (k + 1) % 3, j = (k + 2) % 3;
    const Point<Scalar> edge = triangle[std::size_t(j)] - triangle[std::size_t(i)];
    const Scalar length = edge.norm();
    const Point<Scalar> tangent = edge / length;
    const Point<Scalar> outward = outward_normal(triangle, k);
    // d x / d u_a = tangent_a (x_j - x_i) / |e| + outward_a slope . x
    Eigen::Matrix<Scalar, 2, 12> gradient = outward * normal_slopes[std::size_t(k)];
    gradient.col(j) += tangent / length;
    gradient.col(i) -= tangent / length;
    const Scalar scale = length / rest.area;
    rest.weights.row(0) += scale * outward.x() * gradient.row(0);
    rest.weights.row(1) += scale * outward.y() * gradient.row(1);
    rest.weights.row(2) +=
        0.5 * scale * (outward.y() * gradient.row(0) + outward.x() * gradient.row(1));
  }
  return rest;
}

PatchRest patch_rest(const std::array<Vector2d, 3>& triangle,
                     const std::array<Eigen::Matrix<double, 1, 12>, 3>& normal_slopes,
                     const BendingRigidity& rigidity, const Vector3d& rest_curvature) {
  check_rigidity(rigidity);
  if (!rest_curvature.allFinite()) throw InputError("bending patch: rest curvature not finite");
  const PatchWeights<double> geometry = patch_weights(triangle, normal_slopes);
  PatchRest rest;
  rest.area = geometry.area;
  rest.weights = geometry.weights;
  rest.rigidity = rigidity.matrix();
  rest.rest_curvature = rest_curvature;
  return rest;
}

#define SARTOR_PATCH_GEOMETRY(Scalar)                                                              \
  template PatchPoint<Scalar> node_across(const PatchPoint<Scalar>&, const PatchPoint<Scalar>&,    \
                                          const PatchPoint<Scalar>&, const PatchPoint<Scalar>&,    \
                                          const PatchPoint<Scalar>&, const PatchPoint<Scalar>&);   \
  template EdgeSlopes<Scalar> midedge_slopes(const PatchTriangle<Scalar>&,                         \
                                             const PatchTriangle<Scalar>&,                         \
                                             const std::array<bool, 3>&, const BendingRigidity&);  \
  template EdgeSlopes<Scalar> plane_slopes(const PatchTriangle<Scalar>&);                          \
  template PatchWeights<Scalar> patch_weights(const PatchTriangle<Scalar>&,                        \
                                              const std::array<Eigen::Matrix<Scalar, 1, 12>, 3>&);
SARTOR_PATCH_GEOMETRY(double)
SARTOR_PATCH_GEOMETRY(AutoDiff)
#undef SARTOR_PATCH_GEOMETRY

PatchResponse patch_response(const PatchRest& rest, const Vector3d& strain) {
  PatchResponse r;
  if (!rest.curves) {
    r.tangent = rest.rigidity;
    r.moment = rest.rigidity * strain;
    r.energy_density = 0.5 * strain.dot(r.moment);
    return r;
  }
  const std::array<const MomentCurve*, 3> curves{&rest.curves->warp, &rest.curves->weft,
                                                 &rest.curves->twist};
  const double coupling = rest.rigidity(0, 1);
  r.energy_density = coupling * strain[0] * strain[1];
  r.tangent(0, 1) = r.tangent(1, 0) = coupling;
  r.moment << coupling * strain[1], coupling * strain[0], 0.0;
  for (int i = 0; i < 3; ++i) {
    r.energy_density += curves[std::size_t(i)]->energy_density(strain[i]);
    r.moment[i] += curves[std::size_t(i)]->moment(strain[i]);
    r.tangent(i, i) = curves[std::size_t(i)]->stiffness(strain[i]);
  }
  return r;
}

namespace {

// The deformed triangle's frame and the patch's bending strain and moments.
struct PatchState {
  Vector3d e1, e2; // corners 1 and 2 relative to corner 0
  double length;   // |e1 x e2|
  Vector3d n;      // unit normal
  Matrix3d h;      // column r: H_r, relative to x0
  PatchResponse response;
};

// Absent for a triangle collapsed to zero area (no normal).
std::optional<PatchState> patch_state(const PatchRest& rest, const Vector36& x) {
  PatchState state;
  const Vector3d x0 = x.segment<3>(0);
  state.e1 = x.segment<3>(3) - x0;
  state.e2 = x.segment<3>(6) - x0;
  const Vector3d m = state.e1.cross(state.e2);
  state.length = m.norm();
  const double longest = std::max(
      {state.e1.squaredNorm(), state.e2.squaredNorm(), (state.e2 - state.e1).squaredNorm()});
  if (!(state.length > degenerate_ratio * longest)) return std::nullopt;
  state.n = m / state.length;
  // Second derivatives (rows uu, vv, uv), relative to x0: the weights of each
  // row sum to zero, and differences keep large coordinates out of round-off.
  state.h.setZero();
  for (int i = 1; i < nodes; ++i)
    state.h += (x.segment<3>(3 * i) - x0) * rest.weights.col(i).transpose();
  const Vector3d strain =
      voigt_scale.cwiseProduct(state.h.transpose() * state.n) - rest.rest_curvature;
  state.response = patch_response(rest, strain);
  return state;
}

// dm/dx over the corners (x0, x1, x2), m = e1 x e2 the unnormalised normal.
Jacobian9 normal_derivative(const PatchState& state) {
  Jacobian9 dm;
  dm.block<3, 3>(0, 0) = cross(state.e2) - cross(state.e1);
  dm.block<3, 3>(0, 3) = -cross(state.e2);
  dm.block<3, 3>(0, 6) = cross(state.e1);
  return dm;
}

// dn/dx = P dm/dx / |m|, P the projector off the normal.
Jacobian9 unit_normal_derivative(const PatchState& state, const Jacobian9& dm) {
  const Matrix3d projector = Matrix3d::Identity() - state.n * state.n.transpose();
  return projector * dm / state.length;
}

// The strain's derivative B (3 x 36) given dn/dx over the corners: node i
// carries f_r w_ri n^T, the triangle's corners also f_r H_r^T dn.
Eigen::Matrix<double, 3, 36> strain_derivative(const PatchRest& rest, const PatchState& state,
                                               const Jacobian9& dn) {
  Eigen::Matrix<double, 3, 36> b;
  for (int i = 0; i < nodes; ++i)
    b.block<3, 3>(0, 3 * i) = voigt_scale.cwiseProduct(rest.weights.col(i)) * state.n.transpose();
  b.block<3, 9>(0, 0) += voigt_scale.asDiagonal() * state.h.transpose() * dn;
  return b;
}

} // namespace

Result<36> patch_bending(const PatchRest& rest, const Vector36& x, Want want) {
  Result<36> result;
  result.energy = 0.0;
  result.gradient.setZero();
  result.hessian.setZero();
  const std::optional<PatchState> state = patch_state(rest, x);
  if (!state) return result;
  const Vector3d& n = state->n;
  const double length = state->length;
  const Matrix3d& h = state->h;
  const PatchResponse& response = state->response;
  const Vector3d& moment = response.moment;
  result.energy = rest.area * response.energy_density;
  if (want == Want::energy) return result;

  const Jacobian9 dm = normal_derivative(*state);
  const Jacobian9 dn = unit_normal_derivative(*state, dm);
  const Matrix3d projector = Matrix3d::Identity() - n * n.transpose();
  const Eigen::Matrix<double, 3, 36> b = strain_derivative(rest, *state, dn);
  result.gradient = rest.area * b.transpose() * moment;
  if (want == Want::gradient) return result;

  // sum_r M_r d^2 e_r: linear in (w, H), so with the moment-weighted sums:
  // node i's w n differentiated through n, its transpose, and h . n's Hessian.
  const Vector3d weighted = voigt_scale.cwiseProduct(moment);
  const Eigen::Matrix<double, 1, nodes> w_sum = weighted.transpose() * rest.weights;
  const Vector3d h_sum = h * weighted;
  Matrix36 second = Matrix36::Zero();
  for (int i = 0; i < nodes; ++i)
    second.block<3, 9>(3 * i, 0) += w_sum(i) * dn;
  Matrix36 cross_terms = second + second.transpose();
  // Hessian of g = h_sum . m/|m| over the corners.
  const double hn = h_sum.dot(n);
  const Matrix3d g_mm = (-(h_sum * n.transpose() + n * h_sum.transpose()) -
                         hn * (Matrix3d::Identity() - 3.0 * n * n.transpose())) /
                        (length * length);
  const Vector3d a = projector * h_sum / length;
  // a . (e1 x e2) = -e1^T [a]x e2, with e1 = x1 - x0, e2 = x2 - x0.
  const Matrix3d bilinear = -cross(a);
  Eigen::Matrix<double, 9, 9> triple = Eigen::Matrix<double, 9, 9>::Zero();
  triple.block<3, 3>(3, 6) = bilinear;
  triple.block<3, 3>(6, 3) = bilinear.transpose();
  triple.block<3, 3>(0, 0) = bilinear + bilinear.transpose();
  triple.block<3, 3>(0, 3) = -bilinear.transpose();
  triple.block<3, 3>(3, 0) = -bilinear;
  triple.block<3, 3>(0, 6) = -bilinear;
  triple.block<3, 3>(6, 0) = -bilinear.transpose();
  cross_terms.topLeftCorner<9, 9>() += (dm.transpose() * g_mm).lazyProduct(dm) + triple;
  result.hessian = rest.area * ((b.transpose() * response.tangent).lazyProduct(b) + cross_terms);
  result.hessian = 0.5 * (result.hessian + result.hessian.transpose()).eval();
  return result;
}

namespace {

// Columns u_c (x) v_c of a basis of the Hessian's range on the nine other
// nodes (u over the nodes, v in space).
struct OtherNodesBasis {
  static constexpr int size = 5;
  Eigen::Matrix<double, 9, size> u;
  Eigen::Matrix<double, 3, size> v;
};

// B^T H B for B = diag(I9, the other nodes' basis), by the Kronecker columns:
// a tenth of a dense product's cost.
template <int M>
Eigen::Matrix<double, 9 + M, 9 + M> reduce(const Matrix36& hessian,
                                           const Eigen::Matrix<double, 9, M>& u,
                                           const Eigen::Matrix<double, 3, M>& v) {
  Eigen::Matrix<double, 36, M> right; // H B's last M columns
  for (int c = 0; c < M; ++c) {
    Eigen::Matrix<double, 36, 1> column = Eigen::Matrix<double, 36, 1>::Zero();
    for (int i = 0; i < 9; ++i)
      column += hessian.middleCols<3>(9 + 3 * i) * (u(i, c) * v.col(c));
    right.col(c) = column;
  }
  Eigen::Matrix<double, 9 + M, 9 + M> reduced;
  reduced.template topLeftCorner<9, 9>() = hessian.topLeftCorner<9, 9>();
  reduced.template topRightCorner<9, M>() = right.template topRows<9>();
  reduced.template bottomLeftCorner<M, 9>() = right.template topRows<9>().transpose();
  for (int c = 0; c < M; ++c) {
    Eigen::Matrix<double, 1, M> row = Eigen::Matrix<double, 1, M>::Zero();
    for (int i = 0; i < 9; ++i)
      row += u(i, c) * v.col(c).transpose() * right.template middleRows<3>(9 + 3 * i);
    reduced.template block<1, M>(9 + c, 9) = row;
  }
  return reduced;
}

// B P B^T, the full matrix of a symmetric P given in the basis.
template <int M>
Matrix36 expand(const Eigen::Matrix<double, 9 + M, 9 + M>& p, const Eigen::Matrix<double, 9, M>& u,
                const Eigen::Matrix<double, 3, M>& v) {
  Eigen::Matrix<double, 9 + M, 36> left; // P B^T
  left.template leftCols<9>() = p.template leftCols<9>();
  for (int i = 0; i < 9; ++i) {
    left.template middleCols<3>(9 + 3 * i) =
        p.template rightCols<M>() * (u.row(i).asDiagonal() * v.transpose());
  }
  Matrix36 full;
  full.topRows<9>() = left.template topRows<9>();
  for (int i = 0; i < 9; ++i) {
    full.middleRows<3>(9 + 3 * i) = (v * u.row(i).asDiagonal()) * left.template bottomRows<M>();
  }
  return full;
}

// The Hessian's range on the nine other nodes: they enter the strains only as
// sum_i w_ri x_i . n, so through Q (x) n with Q R = W^T (Householder: span(Q)
// holds span(W^T) whatever its rank, with no rank decided), and the moments'
// turning of n only along s (x) t, s = Q^T (moment-weighted weights), t in
// the tangent plane.
OtherNodesBasis other_nodes_basis(const PatchRest& rest, const PatchState& state) {
  const Eigen::Matrix<double, 9, 3> others = rest.weights.rightCols<9>().transpose();
  const Eigen::Matrix<double, 9, 3> q =
      Eigen::HouseholderQR<Eigen::Matrix<double, 9, 3>>(others).householderQ() *
      Eigen::Matrix<double, 9, 3>::Identity();
  OtherNodesBasis basis;
  for (int j = 0; j < 3; ++j) {
    basis.u.col(j) = q.col(j);
    basis.v.col(j) = state.n;
  }
  const Vector3d weighted = voigt_scale.cwiseProduct(state.response.moment);
  const Vector3d s = q.transpose() * (rest.weights.rightCols<9>().transpose() * weighted);
  // Without moments the tangent directions have no coupling: any unit s will do.
  const Vector3d unit_s = s.squaredNorm() > 0.0 ? Vector3d(s.normalized()) : Vector3d::UnitX();
  const Vector3d t1 = state.n.unitOrthogonal();
  basis.u.col(3) = basis.u.col(4) = q * unit_s;
  basis.v.col(3) = t1;
  basis.v.col(4) = state.n.cross(t1);
  return basis;
}

} // namespace

Matrix36 patch_gauss_newton_hessian(const PatchRest& rest, const Vector36& x) {
  const std::optional<PatchState> state = patch_state(rest, x);
  if (!state) return Matrix36::Zero();
  const Jacobian9 dn = unit_normal_derivative(*state, normal_derivative(*state));
  const Eigen::Matrix<double, 3, 36> b = strain_derivative(rest, *state, dn);
  Eigen::Matrix<double, 3, 3> tangent = state->response.tangent;
  project_to_psd<3>(tangent);
  const Matrix36 hessian = rest.area * (b.transpose() * tangent).lazyProduct(b);
  return 0.5 * (hessian + hessian.transpose());
}

void project_patch_hessian_to_psd(const PatchRest& rest, const Vector36& x, Matrix36& hessian) {
  const std::optional<PatchState> state = patch_state(rest, x);
  if (!state) return; // no normal: the Hessian is zero
  constexpr int size = 9 + OtherNodesBasis::size;
  using Reduced = Eigen::Matrix<double, size, size>;
  const OtherNodesBasis basis = other_nodes_basis(rest, *state);
  Reduced reduced = reduce<OtherNodesBasis::size>(hessian, basis.u, basis.v);
  reduced = (0.5 * (reduced + reduced.transpose())).eval();
  const Eigen::SelfAdjointEigenSolver<Reduced> eigen(reduced);
  if (eigen.eigenvalues().minCoeff() >= 0.0) return;
  const Reduced scaled =
      eigen.eigenvectors() * eigen.eigenvalues().cwiseMax(0.0).cwiseSqrt().asDiagonal();
  const Reduced projected = scaled.lazyProduct(scaled.transpose());
  hessian =
      expand<OtherNodesBasis::size>(0.5 * (projected + projected.transpose()), basis.u, basis.v);
}

} // namespace sartor::element
