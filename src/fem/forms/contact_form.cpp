// ContactForm (fem/forms/contact_form.hpp): the vertices' penalty and
// friction anchors, and the edges' sample points (docs/contact.md#edges:
// normal contact only, so that a coarse edge cannot cut through a curved
// body between its vertices; friction stays with the vertices' anchors).

#include "fem/forms/contact_form.hpp"

#include "common/error.hpp"
#include "contact/conservative_advance.hpp"
#include "element/membrane.hpp"
#include "fem/cloth_problem.hpp"
#include "fem/forms/local_arrays.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

namespace sartor::fem {

ContactForm::ContactForm(const ClothProblem& problem, const std::vector<PetscInt>& vertex_dof,
                         const std::vector<bool>& vertex_owned, const std::vector<bool>& moves,
                         std::vector<bool> triangle_owned, double modulus)
    : problem_(problem), mesh_(problem.mesh()), vertex_dof_(vertex_dof),
      vertex_owned_(vertex_owned), moves_(moves), triangle_owned_(std::move(triangle_owned)),
      modulus_(modulus) {
  for (std::size_t v = 0; v < mesh_.vertex_count(); ++v) {
    if (vertex_owned_[v] && moves_[v]) vertices_.push_back(int(v));
  }
  vertex_area_.assign(mesh_.vertex_count(), 0.0);
  for (std::size_t t = 0; t < mesh_.triangle_count(); ++t) {
    const auto& uv = mesh_.material_uv[t];
    const double area = material_area(uv);
    for (std::size_t k = 0; k < 3; ++k) {
      vertex_area_[std::size_t(mesh_.triangles[t][k])] += area / 3.0;
      mesh_size_ = std::max(mesh_size_, (uv[(k + 1) % 3] - uv[k]).norm());
    }
  }
}

const std::vector<contact::Body>& ContactForm::bodies() const {
  return problem_.bodies;
}
const ContactSettings& ContactForm::settings() const {
  return problem_.contact;
}
double ContactForm::clock() const {
  return problem_.contact_clock();
}

bool ContactForm::projects() const {
  return settings().project_hessian;
}

double ContactForm::stiffness(int vertex) const {
  if (settings().stiffness > 0.0) return settings().stiffness_scale * settings().stiffness;
  return settings().stiffness_scale *
         contact::penalty_stiffness(settings().stiffness_factor, modulus_,
                                    vertex_area_[std::size_t(vertex)], mesh_size_);
}

std::vector<double> ContactForm::relative_stiffness_changes(const RestChange& change) const {
  std::vector<double> relative(mesh_.vertex_count(), 0.0);
  if (settings().stiffness > 0.0) return relative; // given, not from the pattern
  // The longest edge's change; edges within round-off of the longest count
  // as tied, and the largest change among them wins.
  double longest_change = -std::numeric_limits<double>::infinity();
  std::vector<double> area_change(mesh_.vertex_count(), 0.0);
  for (std::size_t t = 0; t < mesh_.triangle_count(); ++t) {
    const auto& uv = mesh_.material_uv[t];
    const auto& delta = change[t];
    const double d_area = element::triangle_area_derivative(uv, delta);
    for (std::size_t k = 0; k < 3; ++k) {
      area_change[std::size_t(mesh_.triangles[t][k])] += d_area / 3.0;
      const Eigen::Vector2d edge = uv[(k + 1) % 3] - uv[k];
      if (edge.norm() < (1.0 - 1e-12) * mesh_size_) continue;
      longest_change =
          std::max(longest_change, edge.dot(delta[(k + 1) % 3] - delta[k]) / edge.norm());
    }
  }
  for (std::size_t v = 0; v < relative.size(); ++v) {
    if (vertex_area_[v] > 0.0)
      relative[v] = area_change[v] / vertex_area_[v] - 2.0 * longest_change / mesh_size_;
  }
  return relative;
}

void ContactForm::add_rest_derivative(const FormPoint& at, const RestChange& change,
                                      PetscScalar* changes) const {
  if (bodies().empty()) return;
  const std::vector<double> relative = relative_stiffness_changes(change);
  // The spring in the plane at the vertex reads its curvature too.
  const auto needs = settings().friction_plane_at_vertex
                         ? contact::surface_anchor_needs(element::Want::gradient)
                         : contact::query_needs(element::Want::gradient);
  for (std::size_t b = 0; b < bodies().size(); ++b) {
    const contact::Body& body = bodies()[b];
    for (int v : vertices_) {
      const PetscInt offset = vertex_dof_[std::size_t(v)];
      const Eigen::Vector3d x = vertex_position(at.x, offset);
      const double k = stiffness(v), d_k = k * relative[std::size_t(v)];
      const contact::SurfaceQuery here = body.query(x, clock(), needs);
      Eigen::Vector3d d_force =
          contact::penalty(d_k, settings().offset, here, element::Want::gradient, band()).gradient;
      if (anchors_.size() == bodies().size() && anchors_[b][std::size_t(v)].active) {
        const FrictionAnchor& anchor = anchors_[b][std::size_t(v)];
        const Eigen::Vector3d held = body.anchor_to_world(anchor.point, clock());
        const double bound = friction_bound(anchor, body.friction, settings().bounded_friction);
        d_force +=
            d_k *
            (settings().friction_plane_at_vertex
                 ? contact::surface_anchor_spring_stiffness_derivative(k, x, held, here, bound)
                 : contact::anchor_spring_stiffness_derivative(
                       k, x, held,
                       body.anchor_direction_to_world(anchor.point, anchor.normal, clock()),
                       bound));
      }
      for (int d = 0; d < 3; ++d)
        changes[offset + d] += d_force[d];
    }
    for (const EdgeSample& sample : edge_samples()) {
      const PetscInt offsets[2] = {vertex_dof_[std::size_t(sample.a)],
                                   vertex_dof_[std::size_t(sample.b)]};
      const Eigen::Vector3d p = contact::edge_point(vertex_position(at.x, offsets[0]),
                                                    vertex_position(at.x, offsets[1]), sample.s);
      const double d_k = 0.5 * (stiffness(sample.a) * relative[std::size_t(sample.a)] +
                                stiffness(sample.b) * relative[std::size_t(sample.b)]);
      const contact::EdgeSampleResult r = contact::edge_sample_penalty(
          d_k, settings().offset, sample.s, body.query(p, clock(), needs), element::Want::gradient,
          false, band());
      for (int k = 0; k < 2; ++k) {
        for (int d = 0; d < 3; ++d)
          changes[offsets[k] + d] += r.gradient[3 * k + d];
      }
    }
  }
}

bool ContactForm::surely_apart(std::size_t body, int vertex, const Eigen::Vector3d& x) const {
  if (queried_.size() != bodies().size())
    queried_.assign(bodies().size(), std::vector<QueriedPlace>(mesh_.vertex_count()));
  const QueriedPlace& last = queried_[body][std::size_t(vertex)];
  const double slope = bodies()[body].shape().slope_bound();
  return last.clock == clock() &&
         last.distance - slope * (x - last.point).norm() > settings().offset;
}

contact::PointResult ContactForm::vertex_contact(std::size_t body, int vertex,
                                                 const Eigen::Vector3d& x,
                                                 element::Want want) const {
  const contact::Body& b = bodies()[body];
  const double k = stiffness(vertex);
  const FrictionAnchor* anchor =
      anchors_.size() == bodies().size() && anchors_[body][std::size_t(vertex)].active
          ? &anchors_[body][std::size_t(vertex)]
          : nullptr;
  // The spring in the plane at the vertex reads the query there, near or not.
  const bool plane_here = anchor && settings().friction_plane_at_vertex;
  contact::PointResult result;
  contact::SurfaceQuery query;
  if (plane_here || !surely_apart(body, vertex, x)) {
    query = b.query(x, clock(),
                    plane_here ? contact::surface_anchor_needs(want) : contact::query_needs(want));
    queried_[body][std::size_t(vertex)] = {x, query.distance, clock()};
    result = contact::penalty(k, settings().offset, query, want, band());
  }
  if (anchor) {
    const contact::PointResult spring =
        friction_spring(b, *anchor, k, x, query,
                        friction_bound(*anchor, b.friction, settings().bounded_friction), want);
    result.energy += spring.energy;
    result.gradient += spring.gradient;
    result.hessian += spring.hessian;
  }
  return result;
}

contact::PointResult ContactForm::friction_spring(const contact::Body& body,
                                                  const FrictionAnchor& anchor, double stiffness,
                                                  const Eigen::Vector3d& x,
                                                  const contact::SurfaceQuery& here, double bound,
                                                  element::Want want) const {
  const Eigen::Vector3d held = body.anchor_to_world(anchor.point, clock());
  if (settings().friction_plane_at_vertex)
    return contact::surface_anchor_spring(stiffness, x, held, here, bound, want);
  return contact::anchor_spring(
      stiffness, x, held, body.anchor_direction_to_world(anchor.point, anchor.normal, clock()),
      bound, want);
}

void ContactForm::add_energy(const FormPoint& at, double* sum) const {
  const PetscScalar* x = at.x;
  double energy = 0.0;
  for (std::size_t b = 0; b < bodies().size(); ++b) {
    for (int v : vertices_) {
      energy += vertex_contact(b, v, vertex_position(x, vertex_dof_[std::size_t(v)]),
                               element::Want::energy)
                    .energy;
    }
  }
  *sum += energy + edge_energy(x);
}

void ContactForm::add_gradient(const FormPoint& at, PetscScalar* f) const {
  const PetscScalar* x = at.x;
  for (std::size_t b = 0; b < bodies().size(); ++b) {
    for (int v : vertices_) {
      const PetscInt offset = vertex_dof_[std::size_t(v)];
      const Eigen::Vector3d g =
          vertex_contact(b, v, vertex_position(x, offset), element::Want::gradient).gradient;
      for (int d = 0; d < 3; ++d)
        f[offset + d] += g[d];
    }
  }
  add_edge_forces(x, f);
}

PetscErrorCode ContactForm::add_hessian(const FormPoint& at, Mat J) const {
  const PetscScalar* x = at.x;
  PetscFunctionBeginUser;
  for (std::size_t b = 0; b < bodies().size(); ++b) {
    for (int v : vertices_) {
      const PetscInt offset = vertex_dof_[std::size_t(v)];
      const contact::PointResult result =
          vertex_contact(b, v, vertex_position(x, offset), element::Want::hessian);
      if (result.hessian.isZero(0.0)) continue; // out of contact and unanchored
      const PetscInt dofs[3] = {offset, offset + 1, offset + 2};
      Eigen::Matrix<double, 3, 3, Eigen::RowMajor> block = result.hessian;
      if (settings().project_hessian && !at.exact_hessian) {
        Eigen::Matrix3d projected = result.hessian;
        element::project_to_psd<3>(projected);
        block = projected;
      }
      PetscCall(MatSetValuesLocal(J, 3, dofs, 3, dofs, block.data(), ADD_VALUES));
    }
  }
  PetscCall(add_edge_hessian(x, settings().project_hessian && !at.exact_hessian, J));
  PetscFunctionReturn(0);
}

double ContactForm::vertex_step_bound(std::size_t body, const Eigen::Vector3d& p,
                                      const Eigen::Vector3d& motion) const {
  const contact::Body& b = bodies()[body];
  const double length = motion.norm();
  const double slope = b.shape().slope_bound();
  if (length == 0.0) return 1.0;
  const double distance = b.distance(p, clock());
  if (distance <= 0.0) return 1.0; // inside: the penalty pushes it out
  // The distance falls by at most slope * |motion| per unit of t.
  return contact::conservative_advance(
      [&](double t) { return b.distance(p + t * motion, clock()); }, distance,
      contact::closest_allowed(distance, settings().offset), slope * length, 1.0);
}

double ContactForm::step_bound(const PetscScalar* values, const PetscScalar* motions) const {
  double smallest = 1.0;
  for (std::size_t b = 0; b < bodies().size(); ++b) {
    const double slope = bodies()[b].shape().slope_bound();
    for (int v : vertices_) {
      const PetscInt offset = vertex_dof_[std::size_t(v)];
      const Eigen::Vector3d p = vertex_position(values, offset),
                            motion = vertex_position(motions, offset);
      // The cached distance bounds the current one from below (surely_apart):
      // far vertices need no query.
      if (queried_.size() == bodies().size()) {
        const QueriedPlace& last = queried_[b][std::size_t(v)];
        const double lower = last.distance - slope * (p - last.point).norm();
        if (last.clock == clock() && lower - slope * motion.norm() > settings().offset) continue;
      }
      smallest = std::min(smallest, vertex_step_bound(b, p, motion));
    }
  }
  return std::min(smallest, edge_step_bound(values, motions));
}

// A smooth body's gradient is not always of unit length (shape.hpp).
Eigen::Vector3d ContactForm::unit_normal(const contact::SurfaceQuery& q) {
  const double slope = q.normal.norm();
  return slope > 0.0 ? Eigen::Vector3d(q.normal / slope) : q.normal;
}

double ContactForm::band() const {
  return settings().penalty_onset * settings().offset;
}

double ContactForm::normal_force(double stiffness, double depth) const {
  return contact::penalty_law(stiffness, band(), depth).force;
}

double ContactForm::penalty_normal_force(int vertex, const contact::SurfaceQuery& q) const {
  return normal_force(stiffness(vertex), settings().offset - q.distance) * q.normal.norm();
}

double ContactForm::anchor_normal_force(int vertex, const contact::SurfaceQuery& q,
                                        const Eigen::Vector3d& samples) const {
  return penalty_normal_force(vertex, q) + std::max(0.0, unit_normal(q).dot(samples));
}

namespace {
// The fraction of its stretch an anchor must slide by to count as sliding
// (far above round-off, far below the certificate's 5 % cone tolerance).
constexpr double sliding_margin = 1e-3;
} // namespace

PetscErrorCode ContactForm::accept_step(const FormPoint& at) {
  const PetscScalar* values = at.x;
  PetscFunctionBeginUser;
  if (anchors_.size() != bodies().size()) {
    anchors_.assign(bodies().size(), std::vector<FrictionAnchor>(mesh_.vertex_count()));
  }
  solved_anchors_ = anchors_;
  solved_bounded_ = settings().bounded_friction;
  sliding_.assign(bodies().size(), 0);
  // Anchors on the surface, or at the vertex's level for springs in the
  // plane at the vertex (whose force then has no share of the plane's turn,
  // surface_anchor_spring).
  const bool plane_here = settings().friction_plane_at_vertex;
  for (std::size_t b = 0; b < bodies().size(); ++b) {
    const contact::Body& body = bodies()[b];
    // Panels slide into place while they are sewn: friction starts after.
    if (!body.friction.active() || problem_.sewing()) continue;
    // The edge samples' normal forces are frictionless; the anchors of their
    // vertices carry friction for them: a vertex whose edges' samples press
    // on the body is in contact (on a convex body the samples hold it off,
    // outside the offset layer), and its share of their force counts in the
    // normal force that bounds its spring.
    std::vector<Eigen::Vector3d> sample_loads;
    PetscCall(edge_sample_loads(b, values, &sample_loads));
    for (int v : vertices_) {
      const Eigen::Vector3d p = vertex_position(values, vertex_dof_[std::size_t(v)]);
      const contact::SurfaceQuery q = body.query(p, clock());
      FrictionAnchor& anchor = anchors_[b][std::size_t(v)];
      const double slope = q.normal.norm();
      const double k = stiffness(v);
      const Eigen::Vector3d normal = unit_normal(q);
      const double normal_force = anchor_normal_force(v, q, sample_loads[std::size_t(v)]);
      if (slope == 0.0 || normal_force <= 0.0) {
        anchor.active = false; // left the body: released
        continue;
      }
      if (!anchor.active) { // a new contact sticks where it touched
        const Eigen::Vector3d touched = plane_here ? p : q.closest;
        anchor = {true, body.anchor_from_world(touched, clock()),
                  body.anchor_direction_from_world(touched, normal, clock()), normal_force, false};
        continue;
      }
      const Eigen::Vector3d held = body.anchor_to_world(anchor.point, clock());
      const Eigen::Vector3d plane =
          plane_here ? normal
                     : body.anchor_direction_to_world(anchor.point, anchor.normal, clock());
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
      if (along.norm() > 0.0) {
        const Eigen::Vector3d level = plane_here ? p : p - normal.dot(p - q.closest) * normal;
        place = level - reach * along.normalized();
      }
      // An anchor that slid last time sits on the cone (mu_k = mu_s): it
      // slides again by round-off. It moves (continuously), but counts as
      // sliding only when it moved by more than sliding_margin of its reach.
      if ((place - held).norm() > sliding_margin * reach) ++sliding_[b];
      anchor.point = body.anchor_from_world(place, clock());
      anchor.normal = body.anchor_direction_from_world(place, normal, clock());
    }
  }
  PetscFunctionReturn(0);
}

PetscErrorCode ContactForm::report(const PetscScalar* values,
                                   std::vector<BodyContact>* report) const {
  PetscFunctionBeginUser;
  report->assign(bodies().size(), {});
  for (std::size_t b = 0; b < bodies().size(); ++b) {
    const contact::Body& body = bodies()[b];
    // Sums: forces (6), contacting, anchored, sliding, contacting edge
    // samples; extremes: penetration, -distance, edge samples' penetration.
    double sums[10] = {0, 0, 0, 0, 0, 0, 0, 0, 0, 0};
    double extremes[3] = {0.0, -std::numeric_limits<double>::max(), 0.0};
    add_edge_report(b, values, sums, &sums[9], &extremes[2]);
    for (int v : vertices_) {
      const Eigen::Vector3d p = vertex_position(values, vertex_dof_[std::size_t(v)]);
      const contact::SurfaceQuery q = body.query(p, clock());
      const double k = stiffness(v);
      const double gap = settings().offset - q.distance;
      extremes[1] = std::max(extremes[1], -q.distance);
      if (gap > 0.0) {
        const double force = normal_force(k, gap);
        for (int d = 0; d < 3; ++d)
          sums[d] += force * q.normal[d];
        sums[6] += 1.0;
        extremes[0] = std::max(extremes[0], gap);
      }
      if (solved_anchors_.size() == bodies().size() && solved_anchors_[b][std::size_t(v)].active) {
        const FrictionAnchor& anchor = solved_anchors_[b][std::size_t(v)];
        const Eigen::Vector3d spring =
            friction_spring(body, anchor, k, p, q,
                            friction_bound(anchor, body.friction, solved_bounded_),
                            element::Want::gradient)
                .gradient;
        for (int d = 0; d < 3; ++d)
          sums[3 + d] -= spring[d];
        sums[7] += 1.0;
      }
    }
    if (sliding_.size() == bodies().size()) sums[8] = double(sliding_[b]);
    double total[10], extreme[3];
    PetscCallMPI(MPIU_Allreduce(sums, total, 10, MPI_DOUBLE, MPI_SUM, problem_.comm()));
    PetscCallMPI(MPIU_Allreduce(extremes, extreme, 3, MPI_DOUBLE, MPI_MAX, problem_.comm()));
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
  PetscFunctionReturn(0);
}

const std::vector<ContactForm::EdgeSample>& ContactForm::edge_samples() const {
  if (edge_samples_spacing_ == settings().edge_sample_spacing) return edge_samples_;
  edge_samples_spacing_ = settings().edge_sample_spacing;
  edge_samples_.clear();
  sample_queried_.clear();
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
    if (!triangle_owned_[t] || !(moves_[std::size_t(a)] || moves_[std::size_t(b)])) continue;
    // The edge's rest length, from the triangle's material coordinates.
    const auto& corners = mesh_.triangles[t];
    const auto corner = [&](int v) {
      return std::size_t(std::find(corners.begin(), corners.end(), v) - corners.begin());
    };
    const double length =
        (mesh_.material_uv[t][corner(b)] - mesh_.material_uv[t][corner(a)]).norm();
    for (double s : contact::edge_sample_parameters(length, settings().edge_sample_spacing))
      edge_samples_.push_back({a, b, s});
  }
  return edge_samples_;
}

double ContactForm::edge_sample_stiffness(const EdgeSample& sample) const {
  return 0.5 * (stiffness(sample.a) + stiffness(sample.b));
}

contact::EdgeSampleResult ContactForm::edge_sample_contact(std::size_t body, std::size_t index,
                                                           const PetscScalar* x, element::Want want,
                                                           bool project) const {
  const EdgeSample& sample = edge_samples()[index];
  const Eigen::Vector3d p =
      contact::edge_point(vertex_position(x, vertex_dof_[std::size_t(sample.a)]),
                          vertex_position(x, vertex_dof_[std::size_t(sample.b)]), sample.s);
  if (sample_queried_.size() != bodies().size())
    sample_queried_.assign(bodies().size(), std::vector<QueriedPlace>(edge_samples().size()));
  QueriedPlace& last = sample_queried_[body][index];
  const contact::Body& b = bodies()[body];
  // As for vertices (surely_apart): a sample that cannot have reached the
  // offset layer since its last query has no penalty, and is not queried.
  if (last.clock == clock() &&
      last.distance - b.shape().slope_bound() * (p - last.point).norm() > settings().offset)
    return {};
  const contact::SurfaceQuery query = b.query(p, clock(), contact::query_needs(want));
  last = {p, query.distance, clock()};
  return contact::edge_sample_penalty(edge_sample_stiffness(sample), settings().offset, sample.s,
                                      query, want, project, band());
}

double ContactForm::edge_energy(const PetscScalar* x) const {
  double energy = 0.0;
  for (std::size_t b = 0; b < bodies().size(); ++b) {
    for (std::size_t i = 0; i < edge_samples().size(); ++i)
      energy += edge_sample_contact(b, i, x, element::Want::energy, false).energy;
  }
  return energy;
}

void ContactForm::add_edge_forces(const PetscScalar* x, PetscScalar* f) const {
  for (std::size_t b = 0; b < bodies().size(); ++b) {
    for (std::size_t i = 0; i < edge_samples().size(); ++i) {
      const contact::EdgeSampleResult r =
          edge_sample_contact(b, i, x, element::Want::gradient, false);
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

PetscErrorCode ContactForm::add_edge_hessian(const PetscScalar* x, bool project, Mat J) const {
  PetscFunctionBeginUser;
  for (std::size_t b = 0; b < bodies().size(); ++b) {
    for (std::size_t i = 0; i < edge_samples().size(); ++i) {
      const contact::EdgeSampleResult r =
          edge_sample_contact(b, i, x, element::Want::hessian, project);
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

double ContactForm::edge_step_bound(const PetscScalar* x, const PetscScalar* motions) const {
  double smallest = 1.0;
  for (std::size_t b = 0; b < bodies().size(); ++b) {
    const double slope = bodies()[b].shape().slope_bound();
    for (std::size_t i = 0; i < edge_samples().size(); ++i) {
      const EdgeSample& sample = edge_samples_[i];
      const PetscInt a = vertex_dof_[std::size_t(sample.a)], c = vertex_dof_[std::size_t(sample.b)];
      const Eigen::Vector3d p =
          contact::edge_point(vertex_position(x, a), vertex_position(x, c), sample.s);
      const Eigen::Vector3d motion =
          contact::edge_point(vertex_position(motions, a), vertex_position(motions, c), sample.s);
      // The cached distance bounds the current one from below: far samples need no query.
      if (sample_queried_.size() == bodies().size()) {
        const QueriedPlace& last = sample_queried_[b][i];
        const double lower = last.distance - slope * (p - last.point).norm();
        if (last.clock == clock() && lower - slope * motion.norm() > settings().offset) continue;
      }
      smallest = std::min(smallest, vertex_step_bound(b, p, motion));
    }
  }
  return smallest;
}

PetscErrorCode ContactForm::edge_sample_loads(std::size_t body, const PetscScalar* x,
                                              std::vector<Eigen::Vector3d>* per_vertex) const {
  Vec local = nullptr, global = nullptr;
  PetscScalar* values = nullptr;
  PetscFunctionBeginUser;
  PetscCall(DMGetLocalVector(problem_.dm(), &local));
  PetscCall(DMGetGlobalVector(problem_.dm(), &global));
  PetscCall(VecSet(local, 0.0));
  PetscCall(VecGetArray(local, &values));
  const contact::Body& b = bodies()[body];
  for (const EdgeSample& sample : edge_samples()) {
    const PetscInt offsets[2] = {vertex_dof_[std::size_t(sample.a)],
                                 vertex_dof_[std::size_t(sample.b)]};
    const Eigen::Vector3d p = contact::edge_point(vertex_position(x, offsets[0]),
                                                  vertex_position(x, offsets[1]), sample.s);
    const contact::SurfaceQuery q = b.query(p, clock());
    const double gap = settings().offset - q.distance;
    if (gap <= 0.0) continue;
    const Eigen::Vector3d force = normal_force(edge_sample_stiffness(sample), gap) * q.normal;
    const double weights[2] = {1.0 - sample.s, sample.s};
    for (int k = 0; k < 2; ++k) {
      for (int d = 0; d < 3; ++d)
        values[offsets[k] + d] += weights[k] * force[d];
    }
  }
  PetscCall(VecRestoreArray(local, &values));
  // Sums over the ranks that assemble a vertex's edges, back to every copy.
  PetscCall(VecSet(global, 0.0));
  PetscCall(DMLocalToGlobal(problem_.dm(), local, ADD_VALUES, global));
  PetscCall(DMGlobalToLocal(problem_.dm(), global, INSERT_VALUES, local));
  PetscCall(VecGetArray(local, &values));
  per_vertex->assign(mesh_.vertex_count(), Eigen::Vector3d::Zero());
  for (std::size_t v = 0; v < mesh_.vertex_count(); ++v) {
    if (vertex_dof_[v] >= 0) (*per_vertex)[v] = vertex_position(values, vertex_dof_[v]);
  }
  PetscCall(VecRestoreArray(local, &values));
  PetscCall(DMRestoreGlobalVector(problem_.dm(), &global));
  PetscCall(DMRestoreLocalVector(problem_.dm(), &local));
  PetscFunctionReturn(0);
}

void ContactForm::vertex_contact_forces(std::size_t body, const PetscScalar* x,
                                        PetscScalar* per_vertex) const {
  for (int v : vertices_) {
    const PetscInt offset = vertex_dof_[std::size_t(v)];
    const Eigen::Vector3d g =
        vertex_contact(body, v, vertex_position(x, offset), element::Want::gradient).gradient;
    for (int d = 0; d < 3; ++d)
      per_vertex[offset + d] = -g[d];
  }
}

void ContactForm::add_edge_report(std::size_t body, const PetscScalar* x, double force_sum[3],
                                  double* contacting, double* deepest) const {
  const contact::Body& b = bodies()[body];
  for (const EdgeSample& sample : edge_samples()) {
    const Eigen::Vector3d p =
        contact::edge_point(vertex_position(x, vertex_dof_[std::size_t(sample.a)]),
                            vertex_position(x, vertex_dof_[std::size_t(sample.b)]), sample.s);
    const contact::SurfaceQuery q = b.query(p, clock());
    const double gap = settings().offset - q.distance;
    if (gap <= 0.0) continue;
    const double force = normal_force(edge_sample_stiffness(sample), gap);
    for (int d = 0; d < 3; ++d)
      force_sum[d] += force * q.normal[d];
    *contacting += 1.0;
    *deepest = std::max(*deepest, gap);
  }
}

void ContactForm::add_vertex_loads(const PetscScalar* x,
                                   const std::vector<std::vector<Eigen::Vector3d>>& sample_loads,
                                   PetscScalar* per_vertex) const {
  // The bodies' cones mu_s f_n summed, per vertex: f_n with the vertex's
  // share of the body's edge samples, as it bounds the anchor (accept_step).
  std::vector<double> cone(mesh_.vertex_count(), 0.0);
  for (std::size_t b = 0; b < bodies().size(); ++b) {
    const contact::Body& body = bodies()[b];
    for (int v : vertices_) {
      const PetscInt offset = vertex_dof_[std::size_t(v)];
      const Eigen::Vector3d p = vertex_position(x, offset);
      const contact::SurfaceQuery q = body.query(p, clock());
      const double k = stiffness(v);
      per_vertex[offset] += penalty_normal_force(v, q);
      cone[std::size_t(v)] += body.friction.static_coefficient *
                              anchor_normal_force(v, q, sample_loads[b][std::size_t(v)]);
      if (solved_anchors_.size() != bodies().size() || !solved_anchors_[b][std::size_t(v)].active)
        continue;
      const FrictionAnchor& anchor = solved_anchors_[b][std::size_t(v)];
      per_vertex[offset + 1] +=
          friction_spring(body, anchor, k, p, q,
                          friction_bound(anchor, body.friction, solved_bounded_),
                          element::Want::gradient)
              .gradient.norm();
    }
  }
  for (int v : vertices_) {
    const PetscInt offset = vertex_dof_[std::size_t(v)];
    if (cone[std::size_t(v)] > 0.0)
      per_vertex[offset + 2] = per_vertex[offset + 1] / cone[std::size_t(v)];
  }
}

void ContactForm::level_anchors(const PetscScalar* x) {
  for (auto* anchors : {&anchors_, &solved_anchors_}) {
    for (std::size_t b = 0; b < anchors->size(); ++b) {
      const contact::Body& body = bodies()[b];
      for (int v : vertices_) {
        FrictionAnchor& anchor = (*anchors)[b][std::size_t(v)];
        if (!anchor.active) continue;
        const Eigen::Vector3d p = vertex_position(x, vertex_dof_[std::size_t(v)]);
        const Eigen::Vector3d held = body.anchor_to_world(anchor.point, clock());
        const Eigen::Vector3d plane =
            body.anchor_direction_to_world(anchor.point, anchor.normal, clock());
        const Eigen::Vector3d level = held + plane.dot(p - held) * plane;
        anchor.point = body.anchor_from_world(level, clock());
        anchor.normal = body.anchor_direction_from_world(level, plane, clock());
      }
    }
  }
}

std::vector<double> ContactForm::anchor_rows() const {
  std::vector<double> rows;
  for (std::size_t body = 0; body < anchors_.size(); ++body) {
    for (std::size_t vertex = 0; vertex < anchors_[body].size(); ++vertex) {
      const FrictionAnchor& anchor = anchors_[body][vertex];
      if (!anchor.active || !vertex_owned_[vertex]) continue;
      rows.insert(rows.end(), {double(body), double(vertex), anchor.point.x(), anchor.point.y(),
                               anchor.point.z(), anchor.normal.x(), anchor.normal.y(),
                               anchor.normal.z(), anchor.normal_force, anchor.sliding ? 1.0 : 0.0});
    }
  }
  return rows;
}

void ContactForm::restore_anchors(const std::vector<AnchorRow>& rows) {
  anchors_.assign(bodies().size(), std::vector<FrictionAnchor>(mesh_.vertex_count()));
  for (const auto& row : rows) {
    const auto body = std::size_t(row[0]);
    const auto vertex = std::size_t(row[1]);
    if (body >= anchors_.size() || vertex >= mesh_.vertex_count()) {
      throw InputError("checkpoint: friction anchor of body " + std::to_string(row[0]) +
                       " at vertex " + std::to_string(row[1]) + " is not in this case");
    }
    anchors_[body][vertex].active = true;
    anchors_[body][vertex].point = {row[2], row[3], row[4]};
    anchors_[body][vertex].normal = {row[5], row[6], row[7]};
    anchors_[body][vertex].normal_force = row[8];
    anchors_[body][vertex].sliding = row[9] != 0.0;
  }
  solved_anchors_ = anchors_;
}

} // namespace sartor::fem
