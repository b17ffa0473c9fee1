// ClothProblem's contact reports and step bounds: the contact form
// (fem/forms/contact_form.hpp) at the problem's state.

#include "fem/cloth_problem.hpp"
#include "fem/forms/contact_form.hpp"

namespace sartor {

PetscErrorCode ClothProblem::contact_step_bound(Vec x, Vec direction, double* bound) {
  const PetscScalar *values = nullptr, *motions = nullptr;
  Vec local_direction = nullptr;
  PetscFunctionBeginUser;
  PetscCall(to_local(x));
  PetscCall(DMGetLocalVector(dm_, &local_direction));
  PetscCall(VecSet(local_direction, 0.0));
  PetscCall(DMGlobalToLocal(dm_, direction, INSERT_VALUES, local_direction));
  PetscCall(VecGetArrayRead(local_x_, &values));
  PetscCall(VecGetArrayRead(local_direction, &motions));
  const double smallest = contact_form_->step_bound(values, motions);
  PetscCall(VecRestoreArrayRead(local_direction, &motions));
  PetscCall(VecRestoreArrayRead(local_x_, &values));
  PetscCall(DMRestoreLocalVector(dm_, &local_direction));
  PetscCallMPI(MPIU_Allreduce(&smallest, bound, 1, MPI_DOUBLE, MPI_MIN, comm_));
  PetscFunctionReturn(0);
}

PetscErrorCode ClothProblem::contact_report(Vec x, std::vector<BodyContact>* report) {
  const PetscScalar* values = nullptr;
  PetscFunctionBeginUser;
  PetscCall(to_local(x));
  PetscCall(VecGetArrayRead(local_x_, &values));
  const PetscErrorCode failed = contact_form_->report(values, report);
  PetscCall(VecRestoreArrayRead(local_x_, &values));
  PetscCall(failed);
  PetscFunctionReturn(0);
}

PetscErrorCode
ClothProblem::gather_edge_sample_loads(Vec x, std::vector<std::vector<Eigen::Vector3d>>* per_body) {
  const PetscScalar* values = nullptr;
  PetscInt size = 0;
  PetscFunctionBeginUser;
  PetscCall(to_local(x));
  PetscCall(VecGetLocalSize(local_x_, &size));
  per_body->assign(bodies.size(), {});
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    std::vector<Eigen::Vector3d> sample_loads;
    PetscCall(VecGetArrayRead(local_x_, &values));
    const PetscErrorCode failed = contact_form_->edge_sample_loads(b, values, &sample_loads);
    PetscCall(VecRestoreArrayRead(local_x_, &values));
    PetscCall(failed);
    // In the local-vector layout gather_vertex_triples reads.
    std::vector<PetscScalar> local(std::size_t(size), 0.0);
    for (std::size_t v = 0; v < mesh_.vertex_count(); ++v) {
      if (vertex_dof_[v] < 0) continue;
      for (int d = 0; d < 3; ++d)
        local[std::size_t(vertex_dof_[v] + d)] = sample_loads[v][d];
    }
    PetscCall(gather_vertex_triples(local.data(), &(*per_body)[b]));
  }
  PetscFunctionReturn(0);
}

} // namespace sartor
