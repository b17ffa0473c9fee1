// ClothProblem's contact reports and step bounds: the contact form
// (fem/forms/contact_form.hpp) at the problem's state.

#include "fem/cloth_problem.hpp"

#include "contact/bone_intervals.hpp"
#include "fem/forms/contact_form.hpp"

#include <algorithm>

namespace sartor {

namespace {

// x from positions in mesh numbering held on rank 0 (gather_positions').
PetscErrorCode set_gathered_positions(MPI_Comm comm, const ClothProblem& problem,
                                      std::vector<Eigen::Vector3d>* positions, Vec x) {
  PetscFunctionBeginUser;
  unsigned long size = positions->size();
  PetscCallMPI(MPI_Bcast(&size, 1, MPI_UNSIGNED_LONG, 0, comm));
  positions->resize(size);
  PetscCallMPI(MPI_Bcast(positions->data()->data(), int(3 * size), MPI_DOUBLE, 0, comm));
  PetscCall(problem.set_solution(*positions, x));
  PetscFunctionReturn(0);
}

} // namespace

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
  if (self_contact_form_ && !disabled(self_contact_form_->name())) {
    double self_bound = 1.0;
    PetscCall(self_contact_form_->step_bound(x, direction, &self_bound));
    *bound = std::min(*bound, self_bound);
  }
  PetscFunctionReturn(0);
}

PetscErrorCode ClothProblem::push_out_of_bodies(Vec x, PushOut* report) {
  std::vector<Eigen::Vector3d> positions;
  PetscFunctionBeginUser;
  PetscCall(gather_positions(x, &positions));
  double counts[3] = {0.0, 0.0, 0.0}; // pushed, deepest, queries
  for (Eigen::Vector3d& p : positions) {
    bool moved = false;
    for (const contact::Body& body : bodies) {
      if (body.bone_intervals &&
          !body.bone_intervals->may_be_inside(body.to_body(p, contact_clock()), contact.offset))
        continue;
      counts[2] += 1.0;
      const contact::SurfaceQuery q = body.query(p, contact_clock(), contact::QueryNeeds::normal);
      if (q.distance >= 0.0 || q.normal.norm() == 0.0) continue;
      counts[1] = std::max(counts[1], -q.distance);
      p += (0.5 * contact.offset - q.distance) * q.normal.normalized();
      moved = true;
    }
    counts[0] += moved ? 1.0 : 0.0;
  }
  PetscCallMPI(MPI_Bcast(counts, 3, MPI_DOUBLE, 0, comm_));
  PetscCall(set_gathered_positions(comm_, *this, &positions, x));
  report->pushed = long(counts[0]);
  report->deepest = counts[1];
  report->queries = long(counts[2]);
  PetscFunctionReturn(0);
}

PetscErrorCode ClothProblem::carry_with_bodies(Vec x, double to, double reach) {
  std::vector<Eigen::Vector3d> positions;
  PetscFunctionBeginUser;
  PetscCall(gather_positions(x, &positions));
  struct Carried {
    std::size_t vertex, body;
    double weight;
    Eigen::Vector3d reference;
  };
  std::vector<Carried> carried;
  for (std::size_t v = 0; v < positions.size(); ++v) {
    for (std::size_t b = 0; b < bodies.size(); ++b) {
      const double d = bodies[b].distance(positions[v], contact_clock());
      if (d >= reach) continue;
      carried.push_back({v, b, 1.0 - std::max(0.0, d) / reach,
                         bodies[b].anchor_from_world(positions[v], contact_clock())});
      break; // the first body within reach carries it
    }
  }
  time = to;
  for (const Carried& c : carried) {
    Eigen::Vector3d& p = positions[c.vertex];
    p += c.weight * (bodies[c.body].anchor_to_world(c.reference, contact_clock()) - p);
  }
  PetscCall(set_gathered_positions(comm_, *this, &positions, x));
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
ClothProblem::gather_body_vertex_forces(Vec x,
                                        std::vector<std::vector<Eigen::Vector3d>>* sample_loads,
                                        std::vector<std::vector<Eigen::Vector3d>>* own_contact) {
  const PetscScalar* values = nullptr;
  PetscInt size = 0;
  PetscFunctionBeginUser;
  PetscCall(to_local(x));
  PetscCall(VecGetLocalSize(local_x_, &size));
  sample_loads->assign(bodies.size(), {});
  own_contact->assign(bodies.size(), {});
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    std::vector<Eigen::Vector3d> per_vertex;
    // In the local-vector layout gather_vertex_triples reads.
    std::vector<PetscScalar> samples(std::size_t(size), 0.0), own(std::size_t(size), 0.0);
    PetscCall(VecGetArrayRead(local_x_, &values));
    const PetscErrorCode failed = contact_form_->edge_sample_loads(b, values, &per_vertex);
    if (!failed) contact_form_->vertex_contact_forces(b, values, own.data());
    PetscCall(VecRestoreArrayRead(local_x_, &values));
    PetscCall(failed);
    for (std::size_t v = 0; v < mesh_.vertex_count(); ++v) {
      if (vertex_dof_[v] < 0) continue;
      for (int d = 0; d < 3; ++d)
        samples[std::size_t(vertex_dof_[v] + d)] = per_vertex[v][d];
    }
    PetscCall(gather_vertex_triples(samples.data(), &(*sample_loads)[b]));
    PetscCall(gather_vertex_triples(own.data(), &(*own_contact)[b]));
  }
  PetscFunctionReturn(0);
}

} // namespace sartor
