#include "fem/creep_coupling.hpp"

#include "common/error.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

namespace sartor {

CreepCoupling::CreepCoupling(ClothProblem& problem, std::vector<CreepMaterial> materials)
    : problem_(problem), materials_(std::move(materials)) {
  const TriangleMesh& mesh = problem.mesh();
  int largest_id = 0;
  for (int id : mesh.material_ids)
    largest_id = std::max(largest_id, id);
  if (materials_.size() <= std::size_t(largest_id)) {
    throw InputError("creep: the mesh uses material id " + std::to_string(largest_id) + " but " +
                     std::to_string(materials_.size()) + " creep material(s) are given");
  }
  for (std::size_t m = 0; m < materials_.size(); ++m) {
    const std::string context = "creep material " + std::to_string(m);
    validate(materials_[m].warp, context + " (warp)");
    validate(materials_[m].weft, context + " (weft)");
  }
  committed_.assign(mesh.triangle_count(), {});
  trial_ = committed_;
  owned_ = problem.owned_triangles();
  apply(committed_);
}

PetscErrorCode CreepCoupling::record_tensions(Vec x) {
  std::vector<std::pair<int, element::MembraneStrain>> strains;
  PetscFunctionBeginUser;
  PetscCall(problem_.owned_strains(x, &strains));
  for (const auto& [triangle, strain] : strains) {
    ElementCreep& state = committed_[std::size_t(triangle)];
    state.tension_warp = strain.tension_warp;
    state.tension_weft = strain.tension_weft;
  }
  PetscFunctionReturn(0);
}

PetscErrorCode CreepCoupling::advance(Vec x, double dt, double* increment) {
  std::vector<std::pair<int, element::MembraneStrain>> strains;
  PetscFunctionBeginUser;
  apply(committed_); // the tensions at x are those of the frozen (committed) state
  PetscCall(problem_.owned_strains(x, &strains));
  const TriangleMesh& mesh = problem_.mesh();
  double largest = 0.0;
  for (const auto& [triangle, strain] : strains) {
    const auto t = std::size_t(triangle);
    const CreepMaterial& material =
        materials_[mesh.material_ids.empty() ? 0 : std::size_t(mesh.material_ids[t])];
    const ElementCreep& from = committed_[t];
    ElementCreep& to = trial_[t];
    to.warp = sartor::advance(material.warp, from.warp, from.tension_warp, strain.tension_warp, dt);
    to.weft = sartor::advance(material.weft, from.weft, from.tension_weft, strain.tension_weft, dt);
    to.tension_warp = strain.tension_warp;
    to.tension_weft = strain.tension_weft;
    largest = std::max({largest, std::abs(to.warp.nonelastic() - from.warp.nonelastic()),
                        std::abs(to.weft.nonelastic() - from.weft.nonelastic())});
  }
  PetscCallMPI(MPIU_Allreduce(&largest, increment, 1, MPI_DOUBLE, MPI_MAX, problem_.comm()));
  apply(trial_);
  PetscFunctionReturn(0);
}

void CreepCoupling::commit() {
  for (int t : owned_)
    committed_[std::size_t(t)] = trial_[std::size_t(t)];
  apply(committed_);
}

void CreepCoupling::roll_back() {
  apply(committed_);
}

void CreepCoupling::apply(const std::vector<ElementCreep>& states) {
  for (int t : owned_) {
    const ElementCreep& state = states[std::size_t(t)];
    problem_.nonelastic[std::size_t(t)] = {state.warp.nonelastic(), state.weft.nonelastic()};
  }
}

PetscErrorCode CreepCoupling::gather(std::vector<ElementCreep>* states) const {
  constexpr std::size_t fields = 6;
  PetscFunctionBeginUser;
  std::vector<double> local(fields * committed_.size(), 0.0);
  for (int t : owned_) {
    const ElementCreep& s = committed_[std::size_t(t)];
    std::copy_n(std::array<double, fields>{s.warp.viscoelastic, s.warp.permanent,
                                           s.weft.viscoelastic, s.weft.permanent, s.tension_warp,
                                           s.tension_weft}
                    .begin(),
                fields, local.begin() + long(fields * std::size_t(t)));
  }
  PetscMPIInt rank = 0;
  PetscCallMPI(MPI_Comm_rank(problem_.comm(), &rank));
  std::vector<double> total(rank == 0 ? local.size() : 0);
  // Each triangle is owned by one rank, so the sum is that rank's values.
  PetscCallMPI(MPI_Reduce(local.data(), total.data(), int(local.size()), MPI_DOUBLE, MPI_SUM, 0,
                          problem_.comm()));
  states->clear();
  for (std::size_t i = 0; i + fields <= total.size(); i += fields) {
    ElementCreep s;
    s.warp = {total[i], total[i + 1]};
    s.weft = {total[i + 2], total[i + 3]};
    s.tension_warp = total[i + 4];
    s.tension_weft = total[i + 5];
    states->push_back(s);
  }
  PetscFunctionReturn(0);
}

void CreepCoupling::restore(const std::vector<ElementCreep>& states) {
  if (states.size() != committed_.size()) {
    throw InputError("creep state of " + std::to_string(states.size()) +
                     " triangles for a mesh of " + std::to_string(committed_.size()));
  }
  committed_ = states;
  trial_ = states;
  apply(committed_);
}

} // namespace sartor
