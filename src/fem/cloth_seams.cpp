// ClothProblem's seam terms: the setup of the cross-partition seam coupling
// (fem/seam_coupling.hpp) and its calls from energy, residual and reactions.

#include "common/error.hpp"
#include "fem/cloth_problem.hpp"
#include "fem/petsc_call.hpp"

namespace sartor {

void ClothProblem::set_seams(const std::vector<SeamSpring>& springs) {
  for (std::size_t i = 0; i < pinned_.size(); ++i) {
    if (releasable(i)) throw InputError("seams and pins with a release time cannot be combined");
  }
  // The first global dof of every free vertex: its owner knows it from the
  // DM's local-to-global map, everybody learns it by one Allreduce.
  std::vector<int> pin_index(mesh_.vertex_count(), -1);
  for (std::size_t i = 0; i < pinned_.size(); ++i)
    pin_index[std::size_t(pinned_[i])] = int(i);
  ISLocalToGlobalMapping map = nullptr;
  SartorPetscCall(DMGetLocalToGlobalMapping(dm_, &map));
  std::vector<PetscInt> owned_first(mesh_.vertex_count(), -1);
  for (std::size_t v = 0; v < mesh_.vertex_count(); ++v) {
    if (!vertex_owned_[v] || pin_index[v] >= 0) continue;
    SartorPetscCall(ISLocalToGlobalMappingApply(map, 1, &vertex_dof_[v], &owned_first[v]));
  }
  std::vector<PetscInt> first_dof(mesh_.vertex_count(), -1);
  SartorPetscCall(MPI_Allreduce(owned_first.data(), first_dof.data(), int(first_dof.size()),
                                MPIU_INT, MPI_MAX, comm_));

  std::vector<SeamSpring> assigned; // each spring on the rank owning its emitting vertex
  for (const SeamSpring& spring : springs) {
    for (int k = 0; k < spring.vertex_count(); ++k) {
      const int v = spring.vertices[std::size_t(k)];
      if (v < 0 || std::size_t(v) >= mesh_.vertex_count()) {
        throw InputError("seam spring: vertex " + std::to_string(v) + " is not in the mesh");
      }
    }
    if (vertex_owned_[std::size_t(spring.vertices[0])]) assigned.push_back(spring);
  }
  Vec layout = nullptr;
  SartorPetscCall(DMGetGlobalVector(dm_, &layout));
  seams_ = std::make_unique<SeamCoupling>(comm_, layout, std::move(assigned), std::move(first_dof),
                                          std::move(pin_index));
  if (sewing_tension > 0.0) seams_->start_sewing(sewing_tension, mesh_.positions);
  SartorPetscCall(DMRestoreGlobalVector(dm_, &layout));
}

// The seam springs' stiffness of this moment.
void ClothProblem::update_sewing_progress() {
  if (!sewing()) {
    seams_->set_sewing_progress(1.0);
  } else {
    seams_->set_sewing_progress(pins_follow_time ? time / sewing_end_time : sewing_stage);
  }
}

// The pins' places, and the seam springs' stiffness of this moment.
PetscErrorCode ClothProblem::prepare_seams(std::vector<Eigen::Vector3d>* places) {
  PetscFunctionBeginUser;
  PetscCall(pin_places(places));
  update_sewing_progress();
  PetscFunctionReturn(0);
}

PetscErrorCode ClothProblem::seam_gap(Vec x, double* gap) {
  std::vector<Eigen::Vector3d> places;
  PetscFunctionBeginUser;
  *gap = 0.0;
  if (!seams_) PetscFunctionReturn(0);
  PetscCall(pin_places(&places));
  PetscCall(seams_->largest_gap(x, places, gap));
  PetscFunctionReturn(0);
}

PetscErrorCode ClothProblem::seam_energy(Vec x, double* energy) {
  std::vector<Eigen::Vector3d> places;
  PetscFunctionBeginUser;
  PetscCall(prepare_seams(&places));
  PetscCall(seams_->energy(x, places, energy));
  PetscFunctionReturn(0);
}

PetscErrorCode ClothProblem::add_seam_forces(Vec x, Vec f) {
  std::vector<Eigen::Vector3d> places;
  PetscFunctionBeginUser;
  PetscCall(prepare_seams(&places));
  PetscCall(seams_->add_forces(x, places, f));
  PetscFunctionReturn(0);
}

PetscErrorCode ClothProblem::add_seam_jacobian(Mat J) {
  PetscFunctionBeginUser;
  update_sewing_progress(); // the springs are linear: no positions needed
  PetscCall(seams_->add_jacobian(J));
  PetscFunctionReturn(0);
}

// The seam springs pull on pinned vertices too; the pins hold against that.
PetscErrorCode ClothProblem::add_seam_pin_reaction(Vec x, Eigen::Vector3d* reaction) {
  std::vector<Eigen::Vector3d> places;
  Eigen::Vector3d force = Eigen::Vector3d::Zero();
  PetscFunctionBeginUser;
  PetscCall(prepare_seams(&places));
  PetscCall(seams_->pinned_force(x, places, &force));
  *reaction += force;
  PetscFunctionReturn(0);
}

} // namespace sartor
