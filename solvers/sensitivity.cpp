#include "solvers/sensitivity.hpp"

#include "fem/petsc_options.hpp"

#include "common/error.hpp"
#include "fem/petsc_call.hpp"

#include <petscmat.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace sartor {

namespace {

double mean_edge_length(const TriangleMesh& mesh) {
  double total = 0.0;
  for (const auto& uv : mesh.material_uv)
    total += (uv[1] - uv[0]).norm() + (uv[2] - uv[1]).norm() + (uv[0] - uv[2]).norm();
  return mesh.material_uv.empty() ? 0.0 : total / (3.0 * double(mesh.material_uv.size()));
}

} // namespace

RestChange rest_change_per_vertex(const TriangleMesh& mesh,
                                  const std::vector<Eigen::Vector2d>& delta_uv) {
  if (delta_uv.size() != mesh.vertex_count()) {
    throw InputError("rest change: " + std::to_string(delta_uv.size()) + " (u, v) changes for " +
                     std::to_string(mesh.vertex_count()) + " vertices");
  }
  RestChange change(mesh.triangle_count());
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t)
    for (std::size_t k = 0; k < 3; ++k)
      change[t][k] = delta_uv[std::size_t(mesh.triangles[t][k])];
  return change;
}

TriangleMesh moved_rest(const TriangleMesh& mesh, const RestChange& change, double scale) {
  if (change.size() != mesh.triangle_count()) {
    throw InputError("rest change: " + std::to_string(change.size()) + " triangles for a mesh of " +
                     std::to_string(mesh.triangle_count()));
  }
  TriangleMesh moved = mesh;
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t)
    for (std::size_t k = 0; k < 3; ++k)
      moved.material_uv[t][k] += scale * change[t][k];
  return moved;
}

PetscErrorCode copy_problem_state(ClothProblem& from, ClothProblem& to) {
  PetscFunctionBeginUser;
  to.loads = from.loads;
  to.load_factor = from.load_factor;
  to.time = from.time;
  to.nonelastic = from.nonelastic;
  to.nonelastic_response = from.nonelastic_response;
  to.pin_motion = from.pin_motion;
  to.pin_groups = from.pin_groups;
  to.pins_follow_time = from.pins_follow_time;
  to.hold_at_release = from.hold_at_release;
  to.bodies = from.bodies;
  to.contact = from.contact;
  to.sewing_tension = from.sewing_tension;
  to.sewing_end_time = from.sewing_end_time;
  to.sewing_stage = from.sewing_stage;
  std::vector<AnchorRow> anchors;
  PetscCall(from.anchors_everywhere(&anchors));
  to.restore_anchors(anchors);
  PetscFunctionReturn(0);
}

PetscErrorCode transfer_vector(ClothProblem& from, Vec v, ClothProblem& to, Vec w) {
  PetscFunctionBeginUser;
  std::vector<Eigen::Vector3d> values;
  PetscCall(from.gather_positions(v, &values));
  auto count = static_cast<unsigned long>(values.size());
  PetscCallMPI(MPI_Bcast(&count, 1, MPI_UNSIGNED_LONG, 0, from.comm()));
  values.resize(count);
  PetscCallMPI(
      MPI_Bcast(values.data()->data(), PetscMPIInt(3 * count), MPI_DOUBLE, 0, from.comm()));
  PetscCall(to.set_solution(values, w));
  PetscFunctionReturn(0);
}

DesignSensitivity::DesignSensitivity(ClothProblem& problem, Vec x, ProblemFactory factory,
                                     SensitivityOptions options)
    : problem_(problem), factory_(std::move(factory)), options_(options) {
  SartorPetscCall(VecDuplicate(x, &x_));
  SartorPetscCall(VecCopy(x, x_));
}

DesignSensitivity::~DesignSensitivity() {
  KSPDestroy(&ksp_);
  MatDestroy(&tangent_);
  VecDestroy(&x_);
}

double DesignSensitivity::difference_step(const RestChange& change) const {
  double largest = 0.0;
  for (const auto& corners : change)
    for (const Eigen::Vector2d& d : corners)
      largest = std::max(largest, d.norm());
  if (!(largest > 0.0)) return 0.0;
  return options_.relative_step * mean_edge_length(problem_.mesh()) / largest;
}

PetscErrorCode DesignSensitivity::residual_of_moved(const RestChange& change, double scale, Vec f) {
  PetscFunctionBeginUser;
  const TriangleMesh mesh = moved_rest(problem_.mesh(), change, scale);
  std::unique_ptr<ClothProblem> moved = factory_(problem_.comm(), mesh, 0.0);
  PetscCall(copy_problem_state(problem_, *moved));
  PetscInt size = 0;
  PetscCall(VecGetSize(x_, &size));
  if (size != moved->global_dof_count()) {
    throw std::logic_error("sensitivity: the problem factory built a problem of another size");
  }
  Vec moved_x = nullptr, moved_f = nullptr;
  PetscCall(moved->create_solution(&moved_x));
  PetscCall(VecDuplicate(moved_x, &moved_f));
  PetscCall(transfer_vector(problem_, x_, *moved, moved_x));
  PetscCall(moved->residual(moved_x, moved_f));
  PetscCall(transfer_vector(*moved, moved_f, problem_, f));
  PetscCall(VecDestroy(&moved_x));
  PetscCall(VecDestroy(&moved_f));
  PetscFunctionReturn(0);
}

bool DesignSensitivity::sums_forms_rest_derivatives() const {
  return !options_.difference_rest_derivative && problem_.has_rest_derivative();
}

PetscErrorCode DesignSensitivity::rest_derivative(const RestChange& change, Vec derivative) {
  PetscFunctionBeginUser;
  if (sums_forms_rest_derivatives()) {
    PetscCall(problem_.rest_derivative(x_, change, derivative));
    PetscFunctionReturn(0);
  }
  const double h = difference_step(change);
  PetscCall(VecZeroEntries(derivative));
  if (h == 0.0) PetscFunctionReturn(0);
  // D(s) = (R(X + s dX) - R(X - s dX)) / (2 s); (4 D(h/2) - D(h)) / 3 is
  // exact to fourth order in h.
  Vec plus = nullptr, minus = nullptr;
  PetscCall(VecDuplicate(x_, &plus));
  PetscCall(VecDuplicate(x_, &minus));
  const double steps[2] = {h, 0.5 * h};
  const double weights[2] = {-1.0 / 3.0, 4.0 / 3.0};
  for (int i = 0; i < 2; ++i) {
    PetscCall(residual_of_moved(change, steps[i], plus));
    PetscCall(residual_of_moved(change, -steps[i], minus));
    PetscCall(VecAXPY(plus, -1.0, minus));
    PetscCall(VecAXPY(derivative, weights[i] / (2.0 * steps[i]), plus));
  }
  PetscCall(VecDestroy(&plus));
  PetscCall(VecDestroy(&minus));
  PetscFunctionReturn(0);
}

PetscErrorCode DesignSensitivity::factorise_tangent(ClothProblem& problem, bool* ok) {
  PetscFunctionBeginUser;
  PetscCall(KSPDestroy(&ksp_));
  PetscCall(MatDestroy(&tangent_));
  tangent_problem_ = &problem;
  // The state in this problem's layout (a rebuilt problem may distribute
  // the vertices differently).
  Vec x = nullptr;
  PetscCall(problem.create_solution(&x));
  PetscCall(transfer_vector(problem_, x_, problem, x));
  bool changed = false;
  PetscCall(problem.refresh_couplings(x, &changed)); // every self-contact pair at x
  PetscCall(problem.create_jacobian(&tangent_));
  const bool exact = problem.exact_hessian;
  problem.exact_hessian = options_.exact_tangent;
  const PetscErrorCode assembled = problem.jacobian(x, tangent_);
  problem.exact_hessian = exact;
  PetscCall(VecDestroy(&x));
  PetscCall(assembled);
  PetscCall(KSPCreate(problem.comm(), &ksp_));
  PetscCall(KSPSetOptionsPrefix(ksp_, "sensitivity_"));
  PetscCall(set_default_direct_solver(problem.comm(), "sensitivity_"));
  PetscCall(KSPSetOperators(ksp_, tangent_, tangent_));
  PetscCall(KSPSetFromOptions(ksp_));
  PetscCall(gather_telescope_onto_one_rank(ksp_));
  PetscCall(KSPSetUp(ksp_));
  bool failed = false;
  PetscCall(direct_solver_failed(ksp_, &failed));
  *ok = !failed;
  PetscFunctionReturn(0);
}

double DesignSensitivity::stabilised_bending_stiffness() const {
  // A plate of thickness h has D / k = h^2 / 12 (k = E h its membrane
  // modulus); h is stabilised_thickness times the panels' size sqrt(A).
  const double area = material_area(problem_.mesh());
  const double modulus = problem_.force_scale() / std::sqrt(area);
  const double thickness = options_.stabilised_thickness * std::sqrt(area);
  return modulus * thickness * thickness / 12.0;
}

PetscErrorCode DesignSensitivity::factorise() {
  PetscFunctionBeginUser;
  bool ok = false;
  stabilised_ = false;
  stabilised_problem_.reset();
  PetscCall(factorise_tangent(problem_, &ok));
  factorised_ = ok;
  if (!ok && options_.stabilise) PetscCall(stabilise());
  PetscFunctionReturn(0);
}

PetscErrorCode DesignSensitivity::stabilise() {
  PetscFunctionBeginUser;
  stabilised_problem_ = factory_(problem_.comm(), problem_.mesh(), stabilised_bending_stiffness());
  PetscCall(copy_problem_state(problem_, *stabilised_problem_));
  bool ok = false;
  PetscCall(factorise_tangent(*stabilised_problem_, &ok));
  stabilised_ = true;
  factorised_ = ok;
  PetscFunctionReturn(0);
}

PetscErrorCode DesignSensitivity::solve(Vec rhs, Vec dx, bool* ok) {
  PetscFunctionBeginUser;
  // In the tangent's layout: the stabilised problem's may differ.
  Vec b = nullptr, y = nullptr, check = nullptr;
  PetscCall(MatCreateVecs(tangent_, &y, &b));
  PetscCall(transfer_vector(problem_, rhs, *tangent_problem_, b));
  PetscCall(KSPSolve(ksp_, b, y));
  KSPConvergedReason reason;
  PetscCall(KSPGetConvergedReason(ksp_, &reason));
  PetscCall(VecDuplicate(b, &check));
  PetscCall(MatMult(tangent_, y, check));
  PetscCall(VecAXPY(check, -1.0, b));
  PetscReal misfit = 0.0, size = 0.0;
  PetscCall(VecNorm(check, NORM_2, &misfit));
  PetscCall(VecNorm(b, NORM_2, &size));
  PetscCall(transfer_vector(*tangent_problem_, y, problem_, dx));
  PetscCall(VecDestroy(&check));
  PetscCall(VecDestroy(&b));
  PetscCall(VecDestroy(&y));
  last_solve_residual_ = size > 0.0 ? misfit / size : misfit;
  *ok = reason >= 0 && std::isfinite(last_solve_residual_) &&
        last_solve_residual_ <= options_.solve_tolerance;
  PetscFunctionReturn(0);
}

PetscErrorCode DesignSensitivity::apply(const RestChange& change, Vec dx) {
  PetscFunctionBeginUser;
  if (!factorised_ && !stabilised_) PetscCall(factorise());
  Vec rhs = nullptr;
  PetscCall(VecDuplicate(x_, &rhs));
  PetscCall(rest_derivative(change, rhs));
  PetscCall(VecScale(rhs, -1.0));
  bool ok = factorised_;
  if (ok) PetscCall(solve(rhs, dx, &ok));
  if (!ok && options_.stabilise && !stabilised_) {
    // Factorised, but the solve did not reproduce its right-hand side: K is
    // numerically singular.
    PetscCall(stabilise());
    ok = factorised_;
    if (ok) PetscCall(solve(rhs, dx, &ok));
  }
  PetscCall(VecDestroy(&rhs));
  if (!ok) {
    throw std::runtime_error("sensitivity: the tangent is singular" +
                             std::string(stabilised_ ? " even when stabilised" : "") +
                             " (relative solve residual " + std::to_string(last_solve_residual_) +
                             ")");
  }
  PetscFunctionReturn(0);
}

} // namespace sartor
