// ClothProblem's contact with rigid bodies: penalty on the signed distance and
// Coulomb friction by moving anchors (docs/contact.md). Each owned free vertex
// meets each body on the rank that owns it, so the sums over ranks count every
// vertex once and results do not depend on the partition.

#include "fem/cloth_problem.hpp"

#include <algorithm>
#include <limits>

namespace sartor {

namespace {

Eigen::Vector3d position(const PetscScalar* x, PetscInt offset) {
  return {x[offset], x[offset + 1], x[offset + 2]};
}

} // namespace

void ClothProblem::set_up_contact() {
  std::vector<bool> free(mesh_.vertex_count(), true);
  for (std::size_t i = 0; i < pinned_.size(); ++i)
    free[std::size_t(pinned_[i])] = releasable(i); // held ones touch bodies once let go
  for (std::size_t v = 0; v < mesh_.vertex_count(); ++v) {
    if (vertex_owned_[v] && free[v]) contact_vertices_.push_back(int(v));
  }
  vertex_area_.assign(mesh_.vertex_count(), 0.0);
  for (std::size_t t = 0; t < mesh_.triangle_count(); ++t) {
    const auto& uv = mesh_.material_uv[t];
    const Eigen::Vector2d a = uv[1] - uv[0], b = uv[2] - uv[0];
    const double area = 0.5 * std::abs(a.x() * b.y() - a.y() * b.x());
    for (std::size_t k = 0; k < 3; ++k) {
      vertex_area_[std::size_t(mesh_.triangles[t][k])] += area / 3.0;
      mesh_size_ = std::max(mesh_size_, (uv[(k + 1) % 3] - uv[k]).norm());
    }
  }
}

double ClothProblem::contact_stiffness(int vertex) const {
  if (contact.stiffness > 0.0) return contact.stiffness_scale * contact.stiffness;
  return contact.stiffness_scale *
         contact::penalty_stiffness(contact.stiffness_factor, largest_modulus(),
                                    vertex_area_[std::size_t(vertex)], mesh_size_);
}

bool ClothProblem::surely_apart(std::size_t body, int vertex, const Eigen::Vector3d& x) const {
  if (queried_.size() != bodies.size())
    queried_.assign(bodies.size(), std::vector<QueriedPlace>(mesh_.vertex_count()));
  const QueriedPlace& last = queried_[body][std::size_t(vertex)];
  const double slope = bodies[body].shape().slope_bound();
  return last.clock == contact_clock() &&
         last.distance - slope * (x - last.point).norm() > contact.offset;
}

contact::PointResult ClothProblem::vertex_contact(std::size_t body, int vertex,
                                                  const Eigen::Vector3d& x,
                                                  element::Want want) const {
  const contact::Body& b = bodies[body];
  const double k = contact_stiffness(vertex);
  contact::PointResult result;
  if (!surely_apart(body, vertex, x)) {
    const contact::SurfaceQuery query = b.query(x, contact_clock(), contact::query_needs(want));
    queried_[body][std::size_t(vertex)] = {x, query.distance, contact_clock()};
    result = contact::penalty(k, contact.offset, query, want);
  }
  if (anchors_.size() == bodies.size()) {
    const FrictionAnchor& anchor = anchors_[body][std::size_t(vertex)];
    if (anchor.active) {
      const contact::PointResult spring = contact::anchor_spring(
          k, x, b.to_world(anchor.point, contact_clock()),
          b.direction_to_world(anchor.normal, contact_clock()),
          friction_bound(anchor, b.friction, contact.bounded_friction), want);
      result.energy += spring.energy;
      result.gradient += spring.gradient;
      result.hessian += spring.hessian;
    }
  }
  return result;
}

double ClothProblem::contact_energy(const PetscScalar* x) const {
  double energy = 0.0;
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    for (int v : contact_vertices_) {
      energy +=
          vertex_contact(b, v, position(x, vertex_dof_[std::size_t(v)]), element::Want::energy)
              .energy;
    }
  }
  return energy + edge_contact_energy(x);
}

void ClothProblem::add_contact_forces(const PetscScalar* x, PetscScalar* f) const {
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    for (int v : contact_vertices_) {
      const PetscInt offset = vertex_dof_[std::size_t(v)];
      const Eigen::Vector3d g =
          vertex_contact(b, v, position(x, offset), element::Want::gradient).gradient;
      for (int d = 0; d < 3; ++d)
        f[offset + d] += g[d];
    }
  }
  add_edge_contact_forces(x, f);
}

PetscErrorCode ClothProblem::add_contact_jacobian(const PetscScalar* x, Mat J) const {
  PetscFunctionBeginUser;
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    for (int v : contact_vertices_) {
      const PetscInt offset = vertex_dof_[std::size_t(v)];
      const contact::PointResult result =
          vertex_contact(b, v, position(x, offset), element::Want::hessian);
      if (result.hessian.isZero(0.0)) continue; // out of contact and unanchored
      const PetscInt dofs[3] = {offset, offset + 1, offset + 2};
      Eigen::Matrix<double, 3, 3, Eigen::RowMajor> block = result.hessian;
      if (contact.project_hessian && !exact_hessian) {
        Eigen::Matrix3d projected = result.hessian;
        element::project_to_psd<3>(projected);
        block = projected;
      }
      PetscCall(MatSetValuesLocal(J, 3, dofs, 3, dofs, block.data(), ADD_VALUES));
    }
  }
  PetscCall(add_edge_contact_jacobian(x, J));
  PetscFunctionReturn(0);
}

double ClothProblem::vertex_step_bound(std::size_t body, const Eigen::Vector3d& p,
                                       const Eigen::Vector3d& motion) const {
  const contact::Body& b = bodies[body];
  const double length = motion.norm();
  const double slope = b.shape().slope_bound();
  if (length == 0.0) return 1.0;
  double distance = b.distance(p, contact_clock());
  if (distance <= 0.0) return 1.0; // inside: the penalty pushes it out
  // Never closer than a tenth of the offset in one step (nor than half its
  // distance when it is closer already): the penalty, which acts within the
  // offset, has the room to hold it.
  const double level = std::min(0.5 * distance, 0.1 * contact.offset);
  // Conservative advancement: the distance falls by at most slope * |motion|
  // per unit of t, so t may advance by (distance - level) / (slope |motion|)
  // at a time without crossing the level. The advances shrink towards the
  // first time the level is reached; stopping only once they are below
  // round-off, or after a fixed count, keeps t a continuous function of the
  // position and the motion (a coarser stopping rule would make the step
  // jump where a vertex needs one advance more, and so the iterates of two
  // machines part at round-off).
  double t = 0.0;
  for (int k = 0; k < 50; ++k) {
    const double room = std::max(0.0, distance - level) / (slope * length);
    if (t + room >= 1.0) return 1.0;
    t += room;
    if (room <= 1e-14) break;
    distance = b.distance(p + t * motion, contact_clock());
  }
  return t;
}

PetscErrorCode ClothProblem::contact_step_bound(Vec x, Vec direction, double* bound) {
  const PetscScalar *values = nullptr, *motions = nullptr;
  Vec local_direction = nullptr;
  PetscFunctionBeginUser;
  double smallest = 1.0;
  PetscCall(to_local(x));
  PetscCall(DMGetLocalVector(dm_, &local_direction));
  PetscCall(VecSet(local_direction, 0.0));
  PetscCall(DMGlobalToLocal(dm_, direction, INSERT_VALUES, local_direction));
  PetscCall(VecGetArrayRead(local_x_, &values));
  PetscCall(VecGetArrayRead(local_direction, &motions));
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    const double slope = bodies[b].shape().slope_bound();
    for (int v : contact_vertices_) {
      const PetscInt offset = vertex_dof_[std::size_t(v)];
      const Eigen::Vector3d p = position(values, offset), motion = position(motions, offset);
      // The cached distance bounds the current one from below (surely_apart):
      // far vertices need no query.
      if (queried_.size() == bodies.size()) {
        const QueriedPlace& last = queried_[b][std::size_t(v)];
        const double lower = last.distance - slope * (p - last.point).norm();
        if (last.clock == contact_clock() && lower - slope * motion.norm() > contact.offset)
          continue;
      }
      smallest = std::min(smallest, vertex_step_bound(b, p, motion));
    }
  }
  smallest = std::min(smallest, edge_step_bound(values, motions));
  PetscCall(VecRestoreArrayRead(local_direction, &motions));
  PetscCall(VecRestoreArrayRead(local_x_, &values));
  PetscCall(DMRestoreLocalVector(dm_, &local_direction));
  PetscCallMPI(MPIU_Allreduce(&smallest, bound, 1, MPI_DOUBLE, MPI_MIN, comm_));
  PetscFunctionReturn(0);
}

namespace {
// The fraction of its stretch an anchor must slide by to count as sliding
// (far above round-off, far below the certificate's 5 % cone tolerance).
constexpr double sliding_margin = 1e-3;
} // namespace

PetscErrorCode ClothProblem::update_contact(Vec x) {
  const PetscScalar* values = nullptr;
  PetscFunctionBeginUser;
  if (anchors_.size() != bodies.size()) {
    anchors_.assign(bodies.size(), std::vector<FrictionAnchor>(mesh_.vertex_count()));
  }
  solved_anchors_ = anchors_;
  solved_bounded_ = contact.bounded_friction;
  sliding_.assign(bodies.size(), 0);
  PetscCall(to_local(x));
  PetscCall(VecGetArrayRead(local_x_, &values));
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    const contact::Body& body = bodies[b];
    // Panels slide into place while they are sewn: friction starts after.
    if (!body.friction.active() || sewing()) continue;
    // The edge samples' normal forces are frictionless; the anchors of their
    // vertices carry friction for them: a vertex whose edges' samples press
    // on the body is in contact (on a convex body the samples hold it off,
    // outside the offset layer), and its share of their force counts in the
    // normal force that bounds its spring.
    std::vector<Eigen::Vector3d> sample_loads;
    PetscCall(edge_sample_loads(b, values, &sample_loads));
    for (int v : contact_vertices_) {
      const Eigen::Vector3d p = position(values, vertex_dof_[std::size_t(v)]);
      const contact::SurfaceQuery q = body.query(p, contact_clock());
      FrictionAnchor& anchor = anchors_[b][std::size_t(v)];
      const double gap = contact.offset - q.distance;
      // A smooth body's gradient is not always of unit length (shape.hpp).
      const double slope = q.normal.norm();
      const double k = contact_stiffness(v);
      const Eigen::Vector3d normal = slope > 0.0 ? Eigen::Vector3d(q.normal / slope) : q.normal;
      const double normal_force =
          k * std::max(0.0, gap) * slope + std::max(0.0, normal.dot(sample_loads[std::size_t(v)]));
      if (slope == 0.0 || normal_force <= 0.0) {
        anchor.active = false; // left the body: released
        continue;
      }
      if (!anchor.active) { // a new contact sticks where it touched
        anchor = {true, body.to_body(q.closest, contact_clock()),
                  body.direction_to_body(normal, contact_clock()), normal_force, false};
        continue;
      }
      const Eigen::Vector3d held = body.to_world(anchor.point, contact_clock());
      const Eigen::Vector3d plane = body.direction_to_world(anchor.normal, contact_clock());
      // Coulomb's law on the force the solve applied (in its tangent plane),
      // against the cone of the normal force now.
      const contact::AnchorUpdate update = contact::slide_anchor(
          k, p, held, plane, normal_force,
          anchor.sliding ? body.friction.kinetic_coefficient : body.friction.static_coefficient,
          body.friction.kinetic_coefficient);
      anchor.normal_force = normal_force;
      anchor.sliding = update.slid;
      if (!update.slid) continue; // sticks: anchor and plane stay
      // The return mapping, in the tangent plane at p now: the anchor goes
      // where the spring pulls with the sliding force mu_k f_n along the slip.
      const Eigen::Vector3d along = (p - update.anchor) - normal.dot(p - update.anchor) * normal;
      const double reach = body.friction.kinetic_coefficient * normal_force / k;
      Eigen::Vector3d place = update.anchor;
      if (along.norm() > 0.0)
        place = p - normal.dot(p - q.closest) * normal - reach * along.normalized();
      // An anchor that slid last time sits on the cone (mu_k = mu_s): it
      // slides again by round-off. It moves (continuously), but counts as
      // sliding only when it moved by more than sliding_margin of its reach.
      if ((place - held).norm() > sliding_margin * reach) ++sliding_[b];
      anchor.point = body.to_body(place, contact_clock());
      anchor.normal = body.direction_to_body(normal, contact_clock());
    }
  }
  PetscCall(VecRestoreArrayRead(local_x_, &values));
  PetscFunctionReturn(0);
}

PetscErrorCode ClothProblem::contact_report(Vec x, std::vector<BodyContact>* report) {
  const PetscScalar* values = nullptr;
  PetscFunctionBeginUser;
  PetscCall(to_local(x));
  PetscCall(VecGetArrayRead(local_x_, &values));
  report->assign(bodies.size(), {});
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    const contact::Body& body = bodies[b];
    // Sums: forces (6), contacting, anchored, sliding, contacting edge
    // samples; extremes: penetration, -distance, edge samples' penetration.
    double sums[10] = {0, 0, 0, 0, 0, 0, 0, 0, 0, 0};
    double extremes[3] = {0.0, -std::numeric_limits<double>::max(), 0.0};
    add_edge_contact_report(b, values, sums, &sums[9], &extremes[2]);
    for (int v : contact_vertices_) {
      const Eigen::Vector3d p = position(values, vertex_dof_[std::size_t(v)]);
      const contact::SurfaceQuery q = body.query(p, contact_clock());
      const double k = contact_stiffness(v);
      const double gap = contact.offset - q.distance;
      extremes[1] = std::max(extremes[1], -q.distance);
      if (gap > 0.0) {
        for (int d = 0; d < 3; ++d)
          sums[d] += k * gap * q.normal[d];
        sums[6] += 1.0;
        extremes[0] = std::max(extremes[0], gap);
      }
      if (solved_anchors_.size() == bodies.size() && solved_anchors_[b][std::size_t(v)].active) {
        const FrictionAnchor& anchor = solved_anchors_[b][std::size_t(v)];
        const Eigen::Vector3d spring =
            contact::anchor_spring(k, p, body.to_world(anchor.point, contact_clock()),
                                   body.direction_to_world(anchor.normal, contact_clock()),
                                   friction_bound(anchor, body.friction, solved_bounded_),
                                   element::Want::gradient)
                .gradient;
        for (int d = 0; d < 3; ++d)
          sums[3 + d] -= spring[d];
        sums[7] += 1.0;
      }
    }
    if (sliding_.size() == bodies.size()) sums[8] = double(sliding_[b]);
    double total[10], extreme[3];
    PetscCallMPI(MPIU_Allreduce(sums, total, 10, MPI_DOUBLE, MPI_SUM, comm_));
    PetscCallMPI(MPIU_Allreduce(extremes, extreme, 3, MPI_DOUBLE, MPI_MAX, comm_));
    BodyContact& r = (*report)[b];
    r.normal_force = {total[0], total[1], total[2]};
    r.friction_force = {total[3], total[4], total[5]};
    r.contacting_vertices = long(total[6]);
    r.anchored_vertices = long(total[7]);
    r.sliding_vertices = long(total[8]);
    r.max_penetration = extreme[0];
    r.min_distance = -extreme[1];
    r.contacting_edge_samples = long(total[9]);
    r.edge_max_penetration = extreme[2];
  }
  PetscCall(VecRestoreArrayRead(local_x_, &values));
  PetscFunctionReturn(0);
}

} // namespace sartor
