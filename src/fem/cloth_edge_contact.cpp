// ClothProblem's contact of cloth edges with rigid bodies: sample points on
// every edge longer than ContactSettings::edge_sample_spacing carry the
// vertex penalty (contact/edge_penalty.hpp), so that a coarse edge cannot cut
// through a curved body between its vertices (docs/contact.md#edges). Normal
// contact only: friction stays with the vertices' anchors. Each edge is
// assembled by the rank that owns the lowest-numbered triangle holding it,
// so the sums over ranks count every sample once.

#include "contact/edge_penalty.hpp"
#include "fem/cloth_problem.hpp"

#include <algorithm>
#include <limits>
#include <map>

namespace sartor {

namespace {

Eigen::Vector3d position(const PetscScalar* x, PetscInt offset) {
  return {x[offset], x[offset + 1], x[offset + 2]};
}

} // namespace

const std::vector<ClothProblem::EdgeSample>& ClothProblem::edge_samples() const {
  if (edge_samples_spacing_ == contact.edge_sample_spacing) return edge_samples_;
  edge_samples_spacing_ = contact.edge_sample_spacing;
  edge_samples_.clear();
  sample_queried_.clear();
  std::vector<bool> moves(mesh_.vertex_count(), true); // a free or releasable vertex
  for (std::size_t i = 0; i < pinned_.size(); ++i)
    moves[std::size_t(pinned_[i])] = releasable(i);
  std::vector<bool> owned(mesh_.triangle_count(), false);
  for (const LocalTriangle& t : triangles_)
    owned[std::size_t(t.index)] = true;
  // Each edge once, with the lowest-numbered triangle that holds it.
  std::map<std::pair<int, int>, std::size_t> first_triangle;
  for (std::size_t t = 0; t < mesh_.triangle_count(); ++t) {
    const auto& corners = mesh_.triangles[t];
    for (std::size_t c = 0; c < 3; ++c) {
      const int a = corners[c], b = corners[(c + 1) % 3];
      first_triangle.emplace(std::make_pair(std::min(a, b), std::max(a, b)), t);
    }
  }
  for (const auto& [edge, t] : first_triangle) {
    const auto [a, b] = edge;
    if (!owned[t] || !(moves[std::size_t(a)] || moves[std::size_t(b)])) continue;
    // The edge's rest length, from the triangle's material coordinates.
    const auto& corners = mesh_.triangles[t];
    const auto corner = [&](int v) {
      return std::size_t(std::find(corners.begin(), corners.end(), v) - corners.begin());
    };
    const double length =
        (mesh_.material_uv[t][corner(b)] - mesh_.material_uv[t][corner(a)]).norm();
    for (double s : contact::edge_sample_parameters(length, contact.edge_sample_spacing))
      edge_samples_.push_back({a, b, s});
  }
  return edge_samples_;
}

double ClothProblem::edge_sample_stiffness(const EdgeSample& sample) const {
  return 0.5 * (contact_stiffness(sample.a) + contact_stiffness(sample.b));
}

contact::EdgeSampleResult ClothProblem::edge_sample_contact(std::size_t body, std::size_t index,
                                                            const PetscScalar* x,
                                                            element::Want want) const {
  const EdgeSample& sample = edge_samples()[index];
  const Eigen::Vector3d p =
      contact::edge_point(position(x, vertex_dof_[std::size_t(sample.a)]),
                          position(x, vertex_dof_[std::size_t(sample.b)]), sample.s);
  if (sample_queried_.size() != bodies.size())
    sample_queried_.assign(bodies.size(), std::vector<QueriedPlace>(edge_samples().size()));
  QueriedPlace& last = sample_queried_[body][index];
  const contact::Body& b = bodies[body];
  // As for vertices (surely_apart): a sample that cannot have reached the
  // offset layer since its last query has no penalty, and is not queried.
  if (last.clock == contact_clock() &&
      last.distance - b.shape().slope_bound() * (p - last.point).norm() > contact.offset)
    return {};
  const contact::SurfaceQuery query = b.query(p, contact_clock(), contact::query_needs(want));
  last = {p, query.distance, contact_clock()};
  return contact::edge_sample_penalty(edge_sample_stiffness(sample), contact.offset, sample.s,
                                      query, want, contact.project_hessian && !exact_hessian);
}

double ClothProblem::edge_contact_energy(const PetscScalar* x) const {
  double energy = 0.0;
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    for (std::size_t i = 0; i < edge_samples().size(); ++i)
      energy += edge_sample_contact(b, i, x, element::Want::energy).energy;
  }
  return energy;
}

void ClothProblem::add_edge_contact_forces(const PetscScalar* x, PetscScalar* f) const {
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    for (std::size_t i = 0; i < edge_samples().size(); ++i) {
      const contact::EdgeSampleResult r = edge_sample_contact(b, i, x, element::Want::gradient);
      if (r.energy == 0.0) continue;
      const EdgeSample& sample = edge_samples_[i];
      const PetscInt offsets[2] = {vertex_dof_[std::size_t(sample.a)],
                                   vertex_dof_[std::size_t(sample.b)]};
      for (int k = 0; k < 2; ++k) {
        for (int d = 0; d < 3; ++d)
          f[offsets[k] + d] += r.gradient[3 * k + d];
      }
    }
  }
}

PetscErrorCode ClothProblem::add_edge_contact_jacobian(const PetscScalar* x, Mat J) const {
  PetscFunctionBeginUser;
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    for (std::size_t i = 0; i < edge_samples().size(); ++i) {
      const contact::EdgeSampleResult r = edge_sample_contact(b, i, x, element::Want::hessian);
      if (r.energy == 0.0) continue; // outside the offset layer
      const EdgeSample& sample = edge_samples_[i];
      const PetscInt a = vertex_dof_[std::size_t(sample.a)], c = vertex_dof_[std::size_t(sample.b)];
      const PetscInt dofs[6] = {a, a + 1, a + 2, c, c + 1, c + 2};
      const Eigen::Matrix<double, 6, 6, Eigen::RowMajor> block = r.hessian;
      PetscCall(MatSetValuesLocal(J, 6, dofs, 6, dofs, block.data(), ADD_VALUES));
    }
  }
  PetscFunctionReturn(0);
}

double ClothProblem::edge_step_bound(const PetscScalar* x, const PetscScalar* motions) const {
  double smallest = 1.0;
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    const double slope = bodies[b].shape().slope_bound();
    for (std::size_t i = 0; i < edge_samples().size(); ++i) {
      const EdgeSample& sample = edge_samples_[i];
      const PetscInt a = vertex_dof_[std::size_t(sample.a)], c = vertex_dof_[std::size_t(sample.b)];
      const Eigen::Vector3d p = contact::edge_point(position(x, a), position(x, c), sample.s);
      const Eigen::Vector3d motion =
          contact::edge_point(position(motions, a), position(motions, c), sample.s);
      // The cached distance bounds the current one from below: far samples need no query.
      if (sample_queried_.size() == bodies.size()) {
        const QueriedPlace& last = sample_queried_[b][i];
        const double lower = last.distance - slope * (p - last.point).norm();
        if (last.clock == contact_clock() && lower - slope * motion.norm() > contact.offset)
          continue;
      }
      smallest = std::min(smallest, vertex_step_bound(b, p, motion));
    }
  }
  return smallest;
}

PetscErrorCode ClothProblem::edge_sample_loads(std::size_t body, const PetscScalar* x,
                                               std::vector<Eigen::Vector3d>* per_vertex) {
  Vec local = nullptr, global = nullptr;
  PetscScalar* values = nullptr;
  PetscFunctionBeginUser;
  PetscCall(DMGetLocalVector(dm_, &local));
  PetscCall(DMGetGlobalVector(dm_, &global));
  PetscCall(VecSet(local, 0.0));
  PetscCall(VecGetArray(local, &values));
  const contact::Body& b = bodies[body];
  for (const EdgeSample& sample : edge_samples()) {
    const PetscInt offsets[2] = {vertex_dof_[std::size_t(sample.a)],
                                 vertex_dof_[std::size_t(sample.b)]};
    const Eigen::Vector3d p =
        contact::edge_point(position(x, offsets[0]), position(x, offsets[1]), sample.s);
    const contact::SurfaceQuery q = b.query(p, contact_clock());
    const double gap = contact.offset - q.distance;
    if (gap <= 0.0) continue;
    const Eigen::Vector3d force = edge_sample_stiffness(sample) * gap * q.normal;
    const double weights[2] = {1.0 - sample.s, sample.s};
    for (int k = 0; k < 2; ++k) {
      for (int d = 0; d < 3; ++d)
        values[offsets[k] + d] += weights[k] * force[d];
    }
  }
  PetscCall(VecRestoreArray(local, &values));
  // Sums over the ranks that assemble a vertex's edges, back to every copy.
  PetscCall(VecSet(global, 0.0));
  PetscCall(DMLocalToGlobal(dm_, local, ADD_VALUES, global));
  PetscCall(DMGlobalToLocal(dm_, global, INSERT_VALUES, local));
  PetscCall(VecGetArray(local, &values));
  per_vertex->assign(mesh_.vertex_count(), Eigen::Vector3d::Zero());
  for (std::size_t v = 0; v < mesh_.vertex_count(); ++v) {
    if (vertex_dof_[v] >= 0) (*per_vertex)[v] = position(values, vertex_dof_[v]);
  }
  PetscCall(VecRestoreArray(local, &values));
  PetscCall(DMRestoreGlobalVector(dm_, &global));
  PetscCall(DMRestoreLocalVector(dm_, &local));
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
    const PetscErrorCode failed = edge_sample_loads(b, values, &sample_loads);
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

void ClothProblem::add_edge_contact_report(std::size_t body, const PetscScalar* x,
                                           double normal_force[3], double* contacting,
                                           double* deepest) const {
  const contact::Body& b = bodies[body];
  for (const EdgeSample& sample : edge_samples()) {
    const Eigen::Vector3d p =
        contact::edge_point(position(x, vertex_dof_[std::size_t(sample.a)]),
                            position(x, vertex_dof_[std::size_t(sample.b)]), sample.s);
    const contact::SurfaceQuery q = b.query(p, contact_clock());
    const double gap = contact.offset - q.distance;
    if (gap <= 0.0) continue;
    const double k = edge_sample_stiffness(sample);
    for (int d = 0; d < 3; ++d)
      normal_force[d] += k * gap * q.normal[d];
    *contacting += 1.0;
    *deepest = std::max(*deepest, gap);
  }
}

} // namespace sartor
