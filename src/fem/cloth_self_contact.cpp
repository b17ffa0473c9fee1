// ClothProblem's cloth self-contact: the setup of the self-contact form
// (fem/forms/self_contact_form.hpp), its Jacobian structure and its step bound.

#include "common/error.hpp"
#include "fem/cloth_problem.hpp"
#include "fem/petsc_call.hpp"

#include <cmath>

namespace sartor {

void ClothProblem::set_self_contact(const fem::SelfContactSettings& settings) {
  if (!(settings.offset > 0.0) || !std::isfinite(settings.offset))
    throw InputError("self-contact: the offset must be a positive length, m");
  if (!(settings.stiffness >= 0.0) || !std::isfinite(settings.stiffness))
    throw InputError("self-contact: the stiffness must be positive (or 0: automatic), N/m");
  if (settings.rings < 1) throw InputError("self-contact: rings must be at least 1");
  if (self_contact_form_) throw InputError("self-contact is already set");
  const std::vector<int> pin_index = pin_indices();
  std::vector<PetscInt> first_dof = first_global_dofs(pin_index);
  // Each vertex's pairs on its owner; a vertex no rank owns (pinned) on rank 0.
  PetscMPIInt rank = 0;
  SartorPetscCall(MPI_Comm_rank(comm_, &rank));
  std::vector<int> owned(mesh_.vertex_count()), owner_known(mesh_.vertex_count());
  for (std::size_t v = 0; v < owned.size(); ++v)
    owned[v] = vertex_owned_[v] ? 1 : 0;
  SartorPetscCall(
      MPI_Allreduce(owned.data(), owner_known.data(), int(owned.size()), MPI_INT, MPI_MAX, comm_));
  std::vector<bool> assigned(mesh_.vertex_count());
  for (std::size_t v = 0; v < assigned.size(); ++v)
    assigned[v] = owned[v] != 0 || (owner_known[v] == 0 && rank == 0);
  const double stiffness = settings.stiffness > 0.0 ? settings.stiffness : largest_modulus();
  Vec layout = nullptr;
  SartorPetscCall(DMGetGlobalVector(dm_, &layout));
  auto form = std::make_unique<fem::SelfContactForm>(
      *this, layout, settings, stiffness, std::move(first_dof), pin_index, std::move(assigned),
      contact::nearby_vertices(
          mesh_.vertex_count(), mesh_.triangles,
          [&](std::size_t t, int i) {
            const auto& uv = mesh_.material_uv[t];
            return (uv[std::size_t((i + 1) % 3)] - uv[std::size_t(i)]).norm();
          },
          seam_links_, settings.rings, fem::SelfContactSettings::near_radius * settings.offset));
  SartorPetscCall(DMRestoreGlobalVector(dm_, &layout));
  self_contact_form_ = form.get();
  coupling_forms_.push_back(std::move(form));
}

PetscErrorCode ClothProblem::refresh_couplings(Vec x, bool* changed) {
  PetscFunctionBeginUser;
  *changed = false;
  if (self_contact_form_) PetscCall(self_contact_form_->refresh(x, changed));
  PetscFunctionReturn(0);
}

PetscErrorCode ClothProblem::couplings_stale(bool* stale) const {
  PetscFunctionBeginUser;
  *stale = false;
  if (self_contact_form_) PetscCall(self_contact_form_->stale(stale));
  PetscFunctionReturn(0);
}

PetscErrorCode ClothProblem::self_contact_report(Vec x, fem::SelfContactReport* report) {
  PetscFunctionBeginUser;
  *report = fem::SelfContactReport{};
  if (self_contact_form_) PetscCall(self_contact_form_->report(x, report));
  PetscFunctionReturn(0);
}

} // namespace sartor
