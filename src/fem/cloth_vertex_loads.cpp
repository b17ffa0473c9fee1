// Per-vertex loads of a solved state for the result files: what the bodies
// and the seams do to each vertex of the cloth (docs/formats.md).

#include "fem/cloth_problem.hpp"
#include "fem/forms/contact_form.hpp"
#include "fem/forms/local_arrays.hpp"
#include "fem/forms/seam_form.hpp"

#include <algorithm>

namespace sartor {

namespace {

// The magnitudes of the per-vertex triples of the global vector `forces`,
// in the first slot of each vertex's triple of `local` (same layout as the
// local positions).
PetscErrorCode magnitudes_to_local(DM dm, Vec forces, const std::vector<PetscInt>& vertex_dof,
                                   const std::vector<bool>& owned, Vec local) {
  Vec local_forces = nullptr;
  const PetscScalar* f = nullptr;
  PetscScalar* out = nullptr;
  PetscFunctionBeginUser;
  PetscCall(DMGetLocalVector(dm, &local_forces));
  PetscCall(VecSet(local_forces, 0.0));
  PetscCall(DMGlobalToLocal(dm, forces, INSERT_VALUES, local_forces));
  PetscCall(VecGetArrayRead(local_forces, &f));
  PetscCall(VecGetArray(local, &out));
  for (std::size_t v = 0; v < vertex_dof.size(); ++v) {
    if (owned[v]) out[vertex_dof[v]] = fem::vertex_position(f, vertex_dof[v]).norm();
  }
  PetscCall(VecRestoreArray(local, &out));
  PetscCall(VecRestoreArrayRead(local_forces, &f));
  PetscCall(DMRestoreLocalVector(dm, &local_forces));
  PetscFunctionReturn(0);
}

// Rank 0's fields from the gathered triples: slot `slot` of each.
std::vector<double> slot_values(const std::vector<Eigen::Vector3d>& triples, int slot) {
  std::vector<double> values;
  for (const Eigen::Vector3d& t : triples)
    values.push_back(t[slot]);
  return values;
}

} // namespace

PetscErrorCode ClothProblem::gather_vertex_loads(Vec x, std::vector<ClothNodeField>* fields) {
  Vec contact_local = nullptr, seam_local = nullptr;
  const PetscScalar* values = nullptr;
  PetscScalar* per_vertex = nullptr;
  PetscFunctionBeginUser;
  fields->clear();
  PetscCall(to_local(x));
  PetscCall(DMGetLocalVector(dm_, &contact_local));
  PetscCall(VecSet(contact_local, 0.0));
  PetscCall(VecGetArrayRead(local_x_, &values));
  std::vector<std::vector<Eigen::Vector3d>> sample_loads(bodies.size());
  for (std::size_t b = 0; b < bodies.size(); ++b)
    PetscCall(contact_form_->edge_sample_loads(b, values, &sample_loads[b]));
  PetscCall(VecGetArray(contact_local, &per_vertex));
  // Per vertex: normal force, friction force, utilisation of the cone.
  contact_form_->add_vertex_loads(values, sample_loads, per_vertex);
  PetscCall(VecRestoreArray(contact_local, &per_vertex));
  PetscCall(VecRestoreArrayRead(local_x_, &values));
  std::vector<Eigen::Vector3d> contact_triples, seam_triples;
  PetscCall(VecGetArrayRead(contact_local, &values));
  PetscCall(gather_vertex_triples(values, &contact_triples));
  PetscCall(VecRestoreArrayRead(contact_local, &values));
  PetscCall(DMRestoreLocalVector(dm_, &contact_local));
  if (seam_form_) {
    Vec forces = nullptr;
    PetscCall(DMGetGlobalVector(dm_, &forces));
    PetscCall(VecSet(forces, 0.0));
    PetscCall(seam_form_->add_gradient(x, forces));
    PetscCall(DMGetLocalVector(dm_, &seam_local));
    PetscCall(VecSet(seam_local, 0.0));
    PetscCall(magnitudes_to_local(dm_, forces, vertex_dof_, vertex_owned_, seam_local));
    PetscCall(DMRestoreGlobalVector(dm_, &forces));
    PetscCall(VecGetArrayRead(seam_local, &values));
    PetscCall(gather_vertex_triples(values, &seam_triples));
    PetscCall(VecRestoreArrayRead(seam_local, &values));
    PetscCall(DMRestoreLocalVector(dm_, &seam_local));
  }
  if (contact_triples.empty()) PetscFunctionReturn(0); // not rank 0
  if (!bodies.empty()) {
    std::vector<double> pressure = slot_values(contact_triples, 0);
    for (std::size_t v = 0; v < pressure.size(); ++v) {
      const double area = contact_form_->vertex_area(v);
      pressure[v] = area > 0.0 ? pressure[v] / area : 0.0;
    }
    fields->push_back({"contact_pressure", pressure, "Pa"});
    fields->push_back({"contact_normal_force", slot_values(contact_triples, 0), "N"});
    fields->push_back({"friction_force", slot_values(contact_triples, 1), "N"});
    fields->push_back({"friction_utilisation", slot_values(contact_triples, 2), "1"});
  }
  if (seam_form_) fields->push_back({"seam_force", slot_values(seam_triples, 0), "N"});
  PetscFunctionReturn(0);
}

} // namespace sartor
