#include "fem/seam_coupling.hpp"

#include "element/seam.hpp"
#include "fem/petsc_call.hpp"

#include <algorithm>

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

// Calls visit(spring, result) with the kernel's result for every assigned
// spring, the result as a dynamic-size (energy, gradient, Hessian).
template <class Visit>
PetscErrorCode SeamCoupling::for_each_spring(Vec x, const std::vector<Eigen::Vector3d>& pin_places,
                                             const Visit& visit) {
  std::vector<double> stacked;
  PetscFunctionBeginUser;
  PetscCall(fetch(x, pin_places, &stacked));
  std::size_t at = 0;
  for (const SeamSpring& spring : springs_) {
    if (spring.to_edge) {
      const Eigen::Map<const Eigen::Matrix<double, 9, 1>> xe(stacked.data() + at);
      const auto result =
          element::seam_vertex_edge(spring.stiffness, spring.s, xe, element::Want::gradient);
      PetscCall(visit(spring, result.energy, Eigen::VectorXd(result.gradient)));
      at += 9;
    } else {
      const Eigen::Map<const Eigen::Matrix<double, 6, 1>> xe(stacked.data() + at);
      const auto result =
          element::seam_vertex_vertex(spring.stiffness, xe, element::Want::gradient);
      PetscCall(visit(spring, result.energy, Eigen::VectorXd(result.gradient)));
      at += 6;
    }
  }
  PetscFunctionReturn(0);
}

PetscErrorCode SeamCoupling::energy(Vec x, const std::vector<Eigen::Vector3d>& pin_places,
                                    double* energy) {
  double local = 0.0;
  PetscFunctionBeginUser;
  PetscCall(
      for_each_spring(x, pin_places, [&](const SeamSpring&, double e, const Eigen::VectorXd&) {
        local += e;
        return PetscErrorCode(0);
      }));
  PetscCallMPI(MPIU_Allreduce(&local, energy, 1, MPI_DOUBLE, MPI_SUM, comm_));
  PetscFunctionReturn(0);
}

PetscErrorCode SeamCoupling::add_forces(Vec x, const std::vector<Eigen::Vector3d>& pin_places,
                                        Vec f) {
  PetscFunctionBeginUser;
  PetscCall(for_each_spring(
      x, pin_places, [&](const SeamSpring& spring, double, const Eigen::VectorXd& gradient) {
        // Vectors, unlike matrices, do not skip negative (pinned) rows.
        std::vector<PetscInt> rows;
        std::vector<PetscScalar> values;
        for (int k = 0; k < spring.vertex_count(); ++k) {
          for (int d = 0; d < 3; ++d) {
            const PetscInt row = global_row(spring.vertices[std::size_t(k)], d);
            if (row < 0) continue;
            rows.push_back(row);
            values.push_back(gradient[3 * k + d]);
          }
        }
        return VecSetValues(f, PetscInt(rows.size()), rows.data(), values.data(), ADD_VALUES);
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
  PetscCall(for_each_spring(x, pin_places,
                            [&](const SeamSpring& spring, double, const Eigen::VectorXd& gradient) {
                              local = std::max(local, gradient.head<3>().norm() / spring.stiffness);
                              return PetscErrorCode(0);
                            }));
  PetscCallMPI(MPIU_Allreduce(&local, gap, 1, MPI_DOUBLE, MPI_MAX, comm_));
  PetscFunctionReturn(0);
}

PetscErrorCode SeamCoupling::pinned_force(Vec x, const std::vector<Eigen::Vector3d>& pin_places,
                                          Eigen::Vector3d* force) {
  double local[3] = {0.0, 0.0, 0.0};
  PetscFunctionBeginUser;
  PetscCall(for_each_spring(x, pin_places,
                            [&](const SeamSpring& spring, double, const Eigen::VectorXd& gradient) {
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
  for (const SeamSpring& spring : springs_) {
    const int n = 3 * spring.vertex_count();
    Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> hessian;
    if (spring.to_edge) {
      hessian =
          element::seam_vertex_edge(spring.stiffness, spring.s, Eigen::Matrix<double, 9, 1>::Zero())
              .hessian;
    } else {
      hessian = element::seam_vertex_vertex(spring.stiffness, Eigen::Matrix<double, 6, 1>::Zero())
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
