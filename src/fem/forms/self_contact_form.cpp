#include "fem/forms/self_contact_form.hpp"

#include "element/penalty_law.hpp"

#include "contact/conservative_advance.hpp"
#include "fem/cloth_problem.hpp"
#include "fem/petsc_call.hpp"

#include <algorithm>
#include <cmath>

namespace sartor::fem {

namespace {

double mean_edge_length(const TriangleMesh& mesh) {
  double sum = 0.0;
  for (const auto& t : mesh.triangles) {
    for (int i = 0; i < 3; ++i)
      sum += (mesh.positions[std::size_t(t[std::size_t(i)])] -
              mesh.positions[std::size_t(t[(i + 1) % 3])])
                 .norm();
  }
  return mesh.triangles.empty() ? 0.0 : sum / double(3 * mesh.triangles.size());
}

} // namespace

SelfContactForm::SelfContactForm(const ClothProblem& problem, Vec layout,
                                 const SelfContactSettings& settings, double stiffness,
                                 std::vector<PetscInt> first_dof, std::vector<int> pin_index,
                                 std::vector<bool> assigned, std::vector<std::vector<int>> nearby)
    : problem_(problem), settings_(settings), stiffness_(stiffness),
      first_dof_(std::move(first_dof)), pin_index_(std::move(pin_index)),
      assigned_(std::move(assigned)), nearby_(std::move(nearby)) {
  const double mesh_size = mean_edge_length(problem.mesh());
  margin_ = std::max(2.0 * settings_.offset, 0.5 * mesh_size);
  reach_ = std::max(settings_.offset, 2.0 * mesh_size);
  SartorPetscCall(VecScatterCreateToAll(layout, &to_all_, &all_));
}

SelfContactForm::~SelfContactForm() {
  VecScatterDestroy(&to_all_);
  VecDestroy(&all_);
}

PetscErrorCode SelfContactForm::positions(Vec x, std::vector<Eigen::Vector3d>* all) {
  const PetscScalar* values = nullptr;
  std::vector<Eigen::Vector3d> places;
  PetscFunctionBeginUser;
  PetscCall(problem_.pin_places(&places));
  PetscCall(VecScatterBegin(to_all_, x, all_, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecScatterEnd(to_all_, x, all_, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecGetArrayRead(all_, &values));
  all->resize(first_dof_.size());
  for (std::size_t v = 0; v < first_dof_.size(); ++v) {
    const PetscInt first = first_dof_[v];
    (*all)[v] = first >= 0 ? Eigen::Vector3d(values[first], values[first + 1], values[first + 2])
                           : places[std::size_t(pin_index_[v])];
  }
  PetscCall(VecRestoreArrayRead(all_, &values));
  PetscFunctionReturn(0);
}

std::vector<contact::VertexTrianglePair>
SelfContactForm::pairs(const std::vector<Eigen::Vector3d>& all, double radius) const {
  return contact::vertex_triangle_pairs(all, problem_.mesh().triangles, nearby_, assigned_, radius);
}

element::Vector12 SelfContactForm::stacked(const std::vector<Eigen::Vector3d>& all, int vertex,
                                           int triangle) const {
  const auto& t = problem_.mesh().triangles[std::size_t(triangle)];
  element::Vector12 x;
  x << all[std::size_t(vertex)], all[std::size_t(t[0])], all[std::size_t(t[1])],
      all[std::size_t(t[2])];
  return x;
}

std::array<PetscInt, 12> SelfContactForm::rows(int vertex, int triangle) const {
  const auto& t = problem_.mesh().triangles[std::size_t(triangle)];
  const int vertices[4] = {vertex, t[0], t[1], t[2]};
  std::array<PetscInt, 12> rows;
  for (int k = 0; k < 4; ++k) {
    const PetscInt first = first_dof_[std::size_t(vertices[k])];
    for (int d = 0; d < 3; ++d)
      rows[std::size_t(3 * k + d)] = first < 0 ? -1 : first + d;
  }
  return rows;
}

bool SelfContactForm::is_candidate(int vertex, int triangle) const {
  return std::binary_search(candidates_.begin(), candidates_.end(),
                            contact::VertexTrianglePair{vertex, triangle, 0.0});
}

PetscErrorCode SelfContactForm::energy(Vec x, double* energy) {
  std::vector<Eigen::Vector3d> all;
  double local = 0.0;
  PetscFunctionBeginUser;
  PetscCall(positions(x, &all));
  for (const auto& pair : pairs(all, settings_.offset)) {
    local += element::point_triangle_penalty(stiffness_, settings_.offset,
                                             stacked(all, pair.vertex, pair.triangle),
                                             element::Want::energy, false, band())
                 .energy;
  }
  PetscCallMPI(MPIU_Allreduce(&local, energy, 1, MPI_DOUBLE, MPI_SUM, problem_.comm()));
  PetscFunctionReturn(0);
}

PetscErrorCode SelfContactForm::add_gradient(Vec x, Vec f) {
  std::vector<Eigen::Vector3d> all;
  PetscFunctionBeginUser;
  PetscCall(positions(x, &all));
  for (const auto& pair : pairs(all, settings_.offset)) {
    const element::Vector12 gradient =
        element::point_triangle_penalty(stiffness_, settings_.offset,
                                        stacked(all, pair.vertex, pair.triangle),
                                        element::Want::gradient, false, band())
            .gradient;
    // Vectors, unlike matrices, do not skip negative (pinned) rows.
    std::vector<PetscInt> free_rows;
    std::vector<PetscScalar> values;
    const std::array<PetscInt, 12> all_rows = rows(pair.vertex, pair.triangle);
    for (int i = 0; i < 12; ++i) {
      if (all_rows[std::size_t(i)] < 0) continue;
      free_rows.push_back(all_rows[std::size_t(i)]);
      values.push_back(gradient[i]);
    }
    PetscCall(
        VecSetValues(f, PetscInt(free_rows.size()), free_rows.data(), values.data(), ADD_VALUES));
  }
  PetscCall(VecAssemblyBegin(f));
  PetscCall(VecAssemblyEnd(f));
  PetscFunctionReturn(0);
}

PetscErrorCode SelfContactForm::add_hessian(Vec x, bool exact, Mat J) {
  std::vector<Eigen::Vector3d> all;
  PetscFunctionBeginUser;
  PetscCall(positions(x, &all));
  for (const auto& pair : pairs(all, settings_.offset)) {
    if (!is_candidate(pair.vertex, pair.triangle)) {
      stale_ = true;
      continue;
    }
    const Eigen::Matrix<double, 12, 12, Eigen::RowMajor> hessian =
        element::point_triangle_penalty(stiffness_, settings_.offset,
                                        stacked(all, pair.vertex, pair.triangle),
                                        element::Want::hessian, exact, band())
            .hessian;
    const std::array<PetscInt, 12> all_rows = rows(pair.vertex, pair.triangle);
    PetscCall(
        MatSetValues(J, 12, all_rows.data(), 12, all_rows.data(), hessian.data(), ADD_VALUES));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode SelfContactForm::record_couplings(Mat recording) {
  const Eigen::Matrix<double, 12, 12, Eigen::RowMajor> ones =
      Eigen::Matrix<double, 12, 12, Eigen::RowMajor>::Ones();
  PetscFunctionBeginUser;
  for (const auto& pair : candidates_) {
    const std::array<PetscInt, 12> all_rows = rows(pair.vertex, pair.triangle);
    PetscCall(
        MatSetValues(recording, 12, all_rows.data(), 12, all_rows.data(), ones.data(), ADD_VALUES));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode SelfContactForm::refresh(Vec x, bool* changed) {
  std::vector<Eigen::Vector3d> all;
  PetscFunctionBeginUser;
  PetscCall(positions(x, &all));
  std::vector<contact::VertexTrianglePair> next = pairs(all, settings_.offset + margin_);
  const auto same = [](const auto& a, const auto& b) {
    return a.vertex == b.vertex && a.triangle == b.triangle;
  };
  // A refresh only adds: pairs that drifted apart stay in the structure, so
  // that a solve whose layers part and meet again does not rebuild it.
  std::vector<contact::VertexTrianglePair> merged;
  std::set_union(candidates_.begin(), candidates_.end(), next.begin(), next.end(),
                 std::back_inserter(merged));
  merged.erase(std::unique(merged.begin(), merged.end(), same), merged.end());
  const int local = merged.size() != candidates_.size() ? 1 : 0;
  int any = 0;
  PetscCallMPI(MPIU_Allreduce(&local, &any, 1, MPI_INT, MPI_MAX, problem_.comm()));
  candidates_ = std::move(merged);
  stale_ = false;
  *changed = any != 0;
  if (*changed) ++refreshes_;
  PetscFunctionReturn(0);
}

PetscErrorCode SelfContactForm::stale(bool* stale) const {
  const int local = stale_ ? 1 : 0;
  int any = 0;
  PetscFunctionBeginUser;
  PetscCallMPI(MPIU_Allreduce(&local, &any, 1, MPI_INT, MPI_MAX, problem_.comm()));
  *stale = any != 0;
  PetscFunctionReturn(0);
}

PetscErrorCode SelfContactForm::step_bound(Vec x, Vec direction, double* bound) {
  std::vector<Eigen::Vector3d> all, motions;
  PetscFunctionBeginUser;
  PetscCall(positions(x, &all));
  PetscCall(positions(direction, &motions));
  // Pinned vertices move with their pins, not along the direction.
  for (std::size_t v = 0; v < motions.size(); ++v) {
    if (first_dof_[v] < 0) motions[v].setZero();
  }
  double largest = 0.0;
  for (const Eigen::Vector3d& m : motions)
    largest = std::max(largest, m.norm());
  // Pairs farther apart than twice the largest motion cannot meet; a step
  // that moves a vertex by more than a mesh size is cut to that first (the
  // search for pairs would reach across the garment).
  const double reach = std::min(2.0 * largest, reach_);
  double smallest = largest > 0.0 ? std::min(1.0, reach / (2.0 * largest)) : 1.0;
  const auto& triangles = problem_.mesh().triangles;
  for (const auto& pair : pairs(all, reach)) {
    const auto& t = triangles[std::size_t(pair.triangle)];
    // The distance falls no faster than the vertex moves relative to the
    // triangle's point nearest it, a convex combination of its corners: so
    // by at most the largest motion relative to a corner. A pair that moves
    // as one (a leg falling as a whole) does not bound the step.
    const auto relative = [&](int corner) {
      return (motions[std::size_t(pair.vertex)] - motions[std::size_t(corner)]).norm();
    };
    const double motion = std::max({relative(t[0]), relative(t[1]), relative(t[2])});
    const auto distance = [&](double s) {
      const auto at = [&](int v) {
        return Eigen::Vector3d(all[std::size_t(v)] + s * motions[std::size_t(v)]);
      };
      return element::closest_point_on_triangle(at(pair.vertex), at(t[0]), at(t[1]), at(t[2]))
          .distance;
    };
    const double start = distance(0.0);
    if (start > 0.0) // touching: the penalty pushes it apart
      smallest = contact::conservative_advance(
          distance, start, contact::closest_allowed(start, settings_.offset), motion, smallest);
  }
  PetscCallMPI(MPIU_Allreduce(&smallest, bound, 1, MPI_DOUBLE, MPI_MIN, problem_.comm()));
  PetscFunctionReturn(0);
}

PetscErrorCode SelfContactForm::report(Vec x, SelfContactReport* report) {
  std::vector<Eigen::Vector3d> all;
  PetscFunctionBeginUser;
  PetscCall(positions(x, &all));
  double local[2] = {0.0, 0.0}, local_min = INFINITY;
  for (const auto& pair : pairs(all, settings_.offset)) {
    local[0] += 1.0;
    local[1] += element::penalty_law(stiffness_, band(), settings_.offset - pair.distance).force;
    local_min = std::min(local_min, pair.distance);
  }
  double total[2], candidates = double(candidates_.size()), all_candidates = 0.0;
  PetscCallMPI(MPIU_Allreduce(local, total, 2, MPI_DOUBLE, MPI_SUM, problem_.comm()));
  PetscCallMPI(
      MPIU_Allreduce(&local_min, &report->min_distance, 1, MPI_DOUBLE, MPI_MIN, problem_.comm()));
  PetscCallMPI(
      MPIU_Allreduce(&candidates, &all_candidates, 1, MPI_DOUBLE, MPI_SUM, problem_.comm()));
  report->pairs = long(total[0]);
  report->normal_force = total[1];
  report->candidates = long(all_candidates);
  report->refreshes = refreshes_;
  PetscFunctionReturn(0);
}

} // namespace sartor::fem
