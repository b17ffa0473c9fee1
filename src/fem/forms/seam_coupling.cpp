#include "fem/forms/seam_coupling.hpp"

#include "element/rest_derivative.hpp"
#include "element/seam.hpp"
#include "fem/petsc_call.hpp"

#include <algorithm>
#include <cmath>

namespace sartor {

SeamCoupling::SeamCoupling(MPI_Comm comm, Vec layout, std::vector<SeamSpring> assigned,
                           std::vector<PetscInt> first_dof, std::vector<int> pin_index)
    : comm_(comm), springs_(std::move(assigned)), first_dof_(std::move(first_dof)),
      pin_index_(std::move(pin_index)) {
  // The free vertices this rank's springs touch, each fetched once.
  slot_.assign(first_dof_.size(), -1);
  std::vector<PetscInt> rows;
  for (const SeamSpring& spring : springs_) {
    for (int k = 0; k < spring.vertex_count(); ++k) {
      const auto v = std::size_t(spring.vertices[std::size_t(k)]);
      if (first_dof_[v] < 0 || slot_[v] >= 0) continue;
      slot_[v] = PetscInt(rows.size());
      for (PetscInt d = 0; d < 3; ++d)
        rows.push_back(first_dof_[v] + d);
    }
  }
  PetscInt own_start = 0, own_end = 0, crossing = 0;
  SartorPetscCall(VecGetOwnershipRange(layout, &own_start, &own_end));
  for (const SeamSpring& spring : springs_) {
    for (int k = 0; k < spring.vertex_count(); ++k) {
      const PetscInt first = first_dof_[std::size_t(spring.vertices[std::size_t(k)])];
      if (first >= 0 && (first < own_start || first >= own_end)) {
        ++crossing;
        break;
      }
    }
  }
  SartorPetscCall(MPI_Allreduce(&crossing, &cross_rank_springs_, 1, MPIU_INT, MPI_SUM, comm_));
  IS from = nullptr;
  SartorPetscCall(VecCreateSeq(PETSC_COMM_SELF, PetscInt(rows.size()), &remote_));
  SartorPetscCall(ISCreateGeneral(PETSC_COMM_SELF, PetscInt(rows.size()), rows.data(),
                                  PETSC_COPY_VALUES, &from));
  SartorPetscCall(VecScatterCreate(layout, from, remote_, nullptr, &fetch_));
  SartorPetscCall(ISDestroy(&from));
}

SeamCoupling::~SeamCoupling() {
  VecScatterDestroy(&fetch_);
  VecDestroy(&remote_);
}

PetscInt SeamCoupling::global_row(int v, int d) const {
  const PetscInt first = first_dof_[std::size_t(v)];
  return first < 0 ? -1 : first + d;
}

PetscErrorCode SeamCoupling::fetch(Vec x, const std::vector<Eigen::Vector3d>& pin_places,
                                   std::vector<double>* stacked) {
  const PetscScalar* values = nullptr;
  PetscFunctionBeginUser;
  PetscCall(VecScatterBegin(fetch_, x, remote_, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecScatterEnd(fetch_, x, remote_, INSERT_VALUES, SCATTER_FORWARD));
  stacked->clear();
  PetscCall(VecGetArrayRead(remote_, &values));
  for (const SeamSpring& spring : springs_) {
    for (int k = 0; k < spring.vertex_count(); ++k) {
      const auto v = std::size_t(spring.vertices[std::size_t(k)]);
      if (slot_[v] >= 0) {
        stacked->insert(stacked->end(), values + slot_[v], values + slot_[v] + 3);
      } else {
        const Eigen::Vector3d& p = pin_places[std::size_t(pin_index_[v])];
        stacked->insert(stacked->end(), {p.x(), p.y(), p.z()});
      }
    }
  }
  PetscCall(VecRestoreArrayRead(remote_, &values));
  PetscFunctionReturn(0);
}

void SeamCoupling::start_sewing(double tension, const std::vector<Eigen::Vector3d>& positions) {
  start_fraction_.clear();
  for (const SeamSpring& spring : springs_) {
    const double pull = spring.stiffness * seam_spring_gap(spring, positions);
    start_fraction_.push_back(pull > 0.0 ? std::min(1.0, tension * spring.length / pull) : 1.0);
  }
}

double SeamCoupling::stiffness(std::size_t index) const {
  const double k = springs_[index].stiffness;
  if (progress_ >= 1.0 || start_fraction_.empty()) return k;
  return k * std::pow(start_fraction_[index], 1.0 - progress_);
}

template <class Visit>
PetscErrorCode SeamCoupling::for_each_placed(Vec x, const std::vector<Eigen::Vector3d>& pin_places,
                                             const Visit& visit) {
  std::vector<double> stacked;
  PetscFunctionBeginUser;
  PetscCall(fetch(x, pin_places, &stacked));
  std::size_t at = 0;
  for (std::size_t index = 0; index < springs_.size(); ++index) {
    PetscCall(visit(index, springs_[index], stacked.data() + at));
    at += std::size_t(3 * springs_[index].vertex_count());
  }
  PetscFunctionReturn(0);
}

// Calls visit(spring, state) for every assigned spring with its stiffness of
// the moment and the kernel's energy and (when `want` asks) gradient.
template <class Visit>
PetscErrorCode SeamCoupling::for_each_spring(Vec x, const std::vector<Eigen::Vector3d>& pin_places,
                                             element::Want want, const Visit& visit) {
  return for_each_placed(x, pin_places,
                         [&](std::size_t index, const SeamSpring& spring, const double* positions) {
                           const double k = stiffness(index);
                           SpringState state;
                           if (spring.to_edge) {
                             const Eigen::Map<const Eigen::Matrix<double, 9, 1>> xe(positions);
                             const auto result = element::seam_vertex_edge(k, spring.s, xe, want);
                             state = {k, result.energy, result.gradient};
                           } else {
                             const Eigen::Map<const Eigen::Matrix<double, 6, 1>> xe(positions);
                             const auto result = element::seam_vertex_vertex(k, xe, want);
                             state = {k, result.energy, result.gradient};
                           }
                           return visit(spring, state);
                         });
}

PetscErrorCode SeamCoupling::energy(Vec x, const std::vector<Eigen::Vector3d>& pin_places,
                                    double* energy) {
  double local = 0.0;
  PetscFunctionBeginUser;
  PetscCall(for_each_spring(x, pin_places, element::Want::energy,
                            [&](const SeamSpring&, const SpringState& state) {
                              local += state.energy;
                              return PetscErrorCode(0);
                            }));
  PetscCallMPI(MPIU_Allreduce(&local, energy, 1, MPI_DOUBLE, MPI_SUM, comm_));
  PetscFunctionReturn(0);
}

PetscErrorCode SeamCoupling::add_forces(Vec x, const std::vector<Eigen::Vector3d>& pin_places,
                                        Vec f) {
  PetscFunctionBeginUser;
  PetscCall(for_each_spring(x, pin_places, element::Want::gradient,
                            [&](const SeamSpring& spring, const SpringState& state) {
                              return add_to_rows(spring, state.gradient, f);
                            }));
  PetscCall(VecAssemblyBegin(f));
  PetscCall(VecAssemblyEnd(f));
  PetscFunctionReturn(0);
}

PetscErrorCode SeamCoupling::add_to_rows(const SeamSpring& spring, const Eigen::VectorXd& values,
                                         Vec f) const {
  // Vectors, unlike matrices, do not skip negative (pinned) rows.
  std::vector<PetscInt> rows;
  std::vector<PetscScalar> free_values;
  PetscFunctionBeginUser;
  for (int k = 0; k < spring.vertex_count(); ++k) {
    for (int d = 0; d < 3; ++d) {
      const PetscInt row = global_row(spring.vertices[std::size_t(k)], d);
      if (row < 0) continue;
      rows.push_back(row);
      free_values.push_back(values[3 * k + d]);
    }
  }
  PetscCall(VecSetValues(f, PetscInt(rows.size()), rows.data(), free_values.data(), ADD_VALUES));
  PetscFunctionReturn(0);
}

PetscErrorCode SeamCoupling::add_rest_derivative(Vec x,
                                                 const std::vector<Eigen::Vector3d>& pin_places,
                                                 const std::vector<SeamSpringChange>& changes,
                                                 Vec f) {
  PetscFunctionBeginUser;
  PetscCheck(changes.size() == springs_.size(), comm_, PETSC_ERR_ARG_SIZ,
             "%zu seam spring changes for %zu springs", changes.size(), springs_.size());
  PetscCall(for_each_placed(
      x, pin_places, [&](std::size_t index, const SeamSpring& spring, const double* positions) {
        Eigen::VectorXd change;
        if (spring.to_edge) {
          const Eigen::Map<const Eigen::Matrix<double, 9, 1>> xe(positions);
          change = element::seam_vertex_edge_rest_derivative(
              spring.stiffness, spring.s, changes[index].stiffness, changes[index].s, xe);
        } else {
          const Eigen::Map<const Eigen::Matrix<double, 6, 1>> xe(positions);
          change = element::seam_vertex_vertex_rest_derivative(changes[index].stiffness, xe);
        }
        return add_to_rows(spring, change, f);
      }));
  PetscCall(VecAssemblyBegin(f));
  PetscCall(VecAssemblyEnd(f));
  PetscFunctionReturn(0);
}

PetscErrorCode SeamCoupling::largest_gap(Vec x, const std::vector<Eigen::Vector3d>& pin_places,
                                         double* gap) {
  double local = 0.0;
  PetscFunctionBeginUser;
  // The force on the emitting vertex is k times its gap.
  PetscCall(for_each_spring(
      x, pin_places, element::Want::gradient, [&](const SeamSpring&, const SpringState& state) {
        local = std::max(local, state.gradient.head<3>().norm() / state.stiffness);
        return PetscErrorCode(0);
      }));
  PetscCallMPI(MPIU_Allreduce(&local, gap, 1, MPI_DOUBLE, MPI_MAX, comm_));
  PetscFunctionReturn(0);
}

PetscErrorCode SeamCoupling::pinned_force(Vec x, const std::vector<Eigen::Vector3d>& pin_places,
                                          Eigen::Vector3d* force) {
  double local[3] = {0.0, 0.0, 0.0};
  PetscFunctionBeginUser;
  PetscCall(for_each_spring(x, pin_places, element::Want::gradient,
                            [&](const SeamSpring& spring, const SpringState& state) {
                              const Eigen::VectorXd& gradient = state.gradient;
                              for (int k = 0; k < spring.vertex_count(); ++k) {
                                if (first_dof_[std::size_t(spring.vertices[std::size_t(k)])] >= 0)
                                  continue;
                                for (int d = 0; d < 3; ++d)
                                  local[d] += gradient[3 * k + d];
                              }
                              return PetscErrorCode(0);
                            }));
  double total[3];
  PetscCallMPI(MPIU_Allreduce(local, total, 3, MPI_DOUBLE, MPI_SUM, comm_));
  *force = Eigen::Vector3d(total[0], total[1], total[2]);
  PetscFunctionReturn(0);
}

PetscErrorCode SeamCoupling::add_jacobian(Mat J) const {
  PetscFunctionBeginUser;
  for (std::size_t index = 0; index < springs_.size(); ++index) {
    const SeamSpring& spring = springs_[index];
    const int n = 3 * spring.vertex_count();
    Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> hessian;
    if (spring.to_edge) {
      hessian =
          element::seam_vertex_edge(stiffness(index), spring.s, Eigen::Matrix<double, 9, 1>::Zero())
              .hessian;
    } else {
      hessian = element::seam_vertex_vertex(stiffness(index), Eigen::Matrix<double, 6, 1>::Zero())
                    .hessian;
    }
    std::vector<PetscInt> rows;
    for (int k = 0; k < spring.vertex_count(); ++k) {
      for (int d = 0; d < 3; ++d)
        rows.push_back(global_row(spring.vertices[std::size_t(k)], d));
    }
    PetscCall(MatSetValues(J, n, rows.data(), n, rows.data(), hessian.data(), ADD_VALUES));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode SeamCoupling::add_pattern(Mat pattern) const {
  PetscFunctionBeginUser;
  PetscCall(add_jacobian(pattern));
  PetscFunctionReturn(0);
}

} // namespace sartor
