#include "fem/creep_coupling.hpp"

#include "common/error.hpp"

#include <Eigen/LU>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
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
  PetscFunctionBeginUser;
  PetscCall(problem_.visit_owned_triangles(x, [&](int triangle, const ClothMaterial& material,
                                                  const element::TriangleRest& rest,
                                                  const element::Vector9& xe) {
    const element::MembraneStrain strain =
        element::membrane_strain(material.membrane_model, material.membrane, rest,
                                 problem_.nonelastic[std::size_t(triangle)], xe);
    ElementCreep& state = committed_[std::size_t(triangle)];
    state.tension_warp = strain.tension_warp;
    state.tension_weft = strain.tension_weft;
  }));
  PetscFunctionReturn(0);
}

const CreepMaterial& CreepCoupling::material_of(int triangle) const {
  const std::vector<int>& ids = problem_.mesh().material_ids;
  return materials_[ids.empty() ? 0 : std::size_t(ids[std::size_t(triangle)])];
}

namespace {

// The largest change of a non-elastic strain from `from` to `to`.
double nonelastic_change(const ElementCreep& from, const ElementCreep& to) {
  return std::max(std::abs(to.warp.nonelastic() - from.warp.nonelastic()),
                  std::abs(to.weft.nonelastic() - from.weft.nonelastic()));
}

} // namespace

PetscErrorCode CreepCoupling::advance(Vec x, double dt, double* increment) {
  PetscFunctionBeginUser;
  apply(committed_); // the tensions at x are those of the frozen (committed) state
  double largest = 0.0;
  PetscCall(problem_.visit_owned_triangles(x, [&](int triangle, const ClothMaterial& material,
                                                  const element::TriangleRest& rest,
                                                  const element::Vector9& xe) {
    const auto t = std::size_t(triangle);
    const element::MembraneStrain strain = element::membrane_strain(
        material.membrane_model, material.membrane, rest, problem_.nonelastic[t], xe);
    const CreepMaterial& creep = material_of(triangle);
    const ElementCreep& from = committed_[t];
    ElementCreep& to = trial_[t];
    to.warp = sartor::advance(creep.warp, from.warp, from.tension_warp, strain.tension_warp, dt);
    to.weft = sartor::advance(creep.weft, from.weft, from.tension_weft, strain.tension_weft, dt);
    to.tension_warp = strain.tension_warp;
    to.tension_weft = strain.tension_weft;
    largest = std::max(largest, nonelastic_change(from, to));
  }));
  PetscCallMPI(MPIU_Allreduce(&largest, increment, 1, MPI_DOUBLE, MPI_MAX, problem_.comm()));
  apply(trial_);
  PetscFunctionReturn(0);
}

void CreepCoupling::couple(double dt) {
  coupled_dt_ = dt;
  holding_trial_ = false;
  problem_.nonelastic_response = this;
  apply(committed_);
}

void CreepCoupling::uncouple() {
  coupled_dt_ = 0.0;
  holding_trial_ = false;
  problem_.nonelastic_response = nullptr;
}

PetscErrorCode CreepCoupling::advance_coupled(Vec x, double* increment) {
  PetscFunctionBeginUser;
  double largest = 0.0;
  PetscCall(problem_.visit_owned_triangles(x, [&](int triangle, const ClothMaterial& material,
                                                  const element::TriangleRest& rest,
                                                  const element::Vector9& xe) {
    const auto t = std::size_t(triangle);
    trial_[t] =
        coupled_step(committed_[t], coupled_dt_, material_of(triangle), material, rest, xe, false)
            .state;
    const double change = nonelastic_change(committed_[t], trial_[t]);
    largest = std::isfinite(change) ? std::max(largest, change) : INFINITY;
  }));
  PetscCallMPI(MPIU_Allreduce(&largest, increment, 1, MPI_DOUBLE, MPI_MAX, problem_.comm()));
  holding_trial_ = true;
  apply(trial_);
  PetscFunctionReturn(0);
}

NonelasticResponse::Answer CreepCoupling::respond(int triangle, const ClothMaterial& material,
                                                  const element::TriangleRest& rest,
                                                  const element::Vector9& x,
                                                  bool want_derivative) const {
  const auto t = std::size_t(triangle);
  if (holding_trial_ || coupled_dt_ == 0.0) {
    const ElementCreep& held = holding_trial_ ? trial_[t] : committed_[t];
    Answer answer;
    answer.strain = {held.warp.nonelastic(), held.weft.nonelastic()};
    return answer;
  }
  const CoupledStep step = coupled_step(committed_[t], coupled_dt_, material_of(triangle), material,
                                        rest, x, want_derivative);
  return {{step.state.warp.nonelastic(), step.state.weft.nonelastic()},
          step.per_position,
          step.per_tension};
}

CreepCoupling::CoupledStep
CreepCoupling::coupled_step(const ElementCreep& from, double dt, const CreepMaterial& creep,
                            const ClothMaterial& material, const element::TriangleRest& rest,
                            const element::Vector9& x, bool want_derivative) const {
  // n = N(T(x, n)) by Newton from the committed strains. N falls as n grows
  // (a longer unloaded length carries less tension), so the root is unique;
  // the mismatch reaches round-off of the strains in a few iterations.
  constexpr int max_iterations = 50;
  constexpr double tolerance = 1e-15;
  Eigen::Vector2d n(from.warp.nonelastic(), from.weft.nonelastic());
  CoupledStep step;
  for (int iteration = 0; iteration <= max_iterations; ++iteration) {
    const element::MembraneCreepSensitivity membrane = element::membrane_creep_sensitivity(
        material.membrane_model, material.membrane, rest, {n(0), n(1)}, x);
    const CreepAdvance warp = sartor::advance_with_sensitivity(
        creep.warp, from.warp, from.tension_warp, membrane.tension(0), dt);
    const CreepAdvance weft = sartor::advance_with_sensitivity(
        creep.weft, from.weft, from.tension_weft, membrane.tension(1), dt);
    const Eigen::Vector2d mismatch =
        n - Eigen::Vector2d(warp.state.nonelastic(), weft.state.nonelastic());
    const Eigen::Matrix2d law =
        Eigen::Vector2d(warp.nonelastic_per_tension, weft.nonelastic_per_tension).asDiagonal();
    const Eigen::PartialPivLU<Eigen::Matrix2d> jacobian(Eigen::Matrix2d::Identity() -
                                                        law * membrane.tension_per_nonelastic);
    if (mismatch.cwiseAbs().maxCoeff() <= tolerance) {
      step.state = {warp.state, weft.state, membrane.tension(0), membrane.tension(1)};
      if (want_derivative) {
        step.per_tension = jacobian.solve(law);
        step.per_position = step.per_tension * membrane.tension_per_position;
      }
      return step;
    }
    n -= jacobian.solve(mismatch);
  }
  const double nan = std::numeric_limits<double>::quiet_NaN();
  step.state = {{nan, nan}, {nan, nan}, nan, nan};
  return step;
}

void CreepCoupling::commit() {
  for (int t : owned_)
    committed_[std::size_t(t)] = trial_[std::size_t(t)];
  holding_trial_ = false;
  coupled_dt_ = 0.0;
  apply(committed_);
}

void CreepCoupling::roll_back() {
  holding_trial_ = false;
  coupled_dt_ = 0.0;
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
