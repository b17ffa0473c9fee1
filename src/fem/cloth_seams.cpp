// ClothProblem's seams: the setup of the cross-partition seam coupling
// (fem/forms/seam_coupling.hpp) as a coupling form (fem/forms/seam_form.hpp).

#include "common/error.hpp"
#include "fem/cloth_problem.hpp"
#include "fem/forms/seam_form.hpp"
#include "fem/petsc_call.hpp"

#include <algorithm>

namespace sartor {

std::vector<SeamSpring> ClothProblem::set_seams(const std::vector<Seam>& seams,
                                                const SeamStiffness& stiffness) {
  std::vector<SeamSpring> springs = seam_springs(mesh_, seams, stiffness);
  set_up_seams(springs, std::make_unique<fem::SeamDesign>(fem::SeamDesign{seams, stiffness}));
  return springs;
}

void ClothProblem::set_seams(const std::vector<SeamSpring>& springs) {
  set_up_seams(springs, nullptr);
}

void ClothProblem::set_up_seams(const std::vector<SeamSpring>& springs,
                                std::unique_ptr<fem::SeamDesign> design) {
  for (std::size_t i = 0; i < pinned_.size(); ++i) {
    if (releasable(i)) throw InputError("seams and pins with a release time cannot be combined");
  }
  std::vector<int> pin_index = pin_indices();
  std::vector<PetscInt> first_dof = first_global_dofs(pin_index);

  if (self_contact_form_) throw InputError("seams must be set before self-contact");
  seam_links_.clear();
  for (const SeamSpring& spring : springs) {
    for (int k = 1; k < spring.vertex_count(); ++k)
      seam_links_.emplace_back(spring.vertices[0], spring.vertices[std::size_t(k)]);
  }
  std::vector<SeamSpring> assigned; // each spring on the rank owning its emitting vertex
  std::vector<std::size_t> assigned_index;
  for (const SeamSpring& spring : springs) {
    for (int k = 0; k < spring.vertex_count(); ++k) {
      const int v = spring.vertices[std::size_t(k)];
      if (v < 0 || std::size_t(v) >= mesh_.vertex_count()) {
        throw InputError("seam spring: vertex " + std::to_string(v) + " is not in the mesh");
      }
    }
    if (!vertex_owned_[std::size_t(spring.vertices[0])]) continue;
    assigned_index.push_back(std::size_t(&spring - springs.data()));
    assigned.push_back(spring);
  }
  Vec layout = nullptr;
  SartorPetscCall(DMGetGlobalVector(dm_, &layout));
  auto coupling = std::make_unique<SeamCoupling>(comm_, layout, std::move(assigned),
                                                 std::move(first_dof), std::move(pin_index));
  if (sewing_tension > 0.0) coupling->start_sewing(sewing_tension, mesh_.positions);
  SartorPetscCall(DMRestoreGlobalVector(dm_, &layout));
  // A second call replaces the seams.
  if (seam_form_) {
    coupling_forms_.erase(std::find_if(coupling_forms_.begin(), coupling_forms_.end(),
                                       [&](const auto& form) { return form.get() == seam_form_; }));
  }
  auto form = std::make_unique<fem::SeamForm>(*this, std::move(coupling), std::move(assigned_index),
                                              std::move(design));
  seam_form_ = form.get();
  coupling_forms_.push_back(std::move(form));
}

std::vector<int> ClothProblem::pin_indices() const {
  std::vector<int> pin_index(mesh_.vertex_count(), -1);
  for (std::size_t i = 0; i < pinned_.size(); ++i)
    pin_index[std::size_t(pinned_[i])] = int(i);
  return pin_index;
}

// The first global dof of every free vertex: its owner knows it from the
// DM's local-to-global map, everybody learns it by one Allreduce.
std::vector<PetscInt> ClothProblem::first_global_dofs(const std::vector<int>& pin_index) const {
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
  return first_dof;
}

const SeamCoupling* ClothProblem::seam_coupling() const {
  return seam_form_ ? &seam_form_->coupling() : nullptr;
}

PetscErrorCode ClothProblem::seam_gap(Vec x, double* gap) {
  PetscFunctionBeginUser;
  *gap = 0.0;
  if (seam_form_) PetscCall(seam_form_->largest_gap(x, gap));
  PetscFunctionReturn(0);
}

} // namespace sartor
