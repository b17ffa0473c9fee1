#include "solvers/certificate.hpp"

#include "contact/analytic_shapes.hpp"

#include <nlohmann/json.hpp>
#include <petscksp.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace sartor {

namespace {

constexpr double standard_gravity = 9.80665; // m/s^2

bool is_root(MPI_Comm comm) {
  PetscMPIInt rank = 0;
  MPI_Comm_rank(comm, &rank);
  return rank == 0;
}

// The clock bodies and pins follow (ClothProblem's contact clock).
double body_clock(const ClothProblem& problem) {
  return problem.pins_follow_time ? problem.time : problem.load_factor;
}

// Per mesh vertex, whether it is a free dof now (pins that hold are not).
std::vector<bool> free_vertices(const ClothProblem& problem) {
  std::vector<bool> free(problem.mesh().vertex_count(), true);
  for (std::size_t i = 0; i < problem.pinned().size(); ++i) {
    const bool released = std::isfinite(problem.release_times()[i]) && !problem.holds(i);
    free[std::size_t(problem.pinned()[i])] = released;
  }
  return free;
}

// The forces at x, per mesh vertex on rank 0: the residual F, what contact
// must supply for equilibrium (F without the bodies: F_nc), what the contact
// model applies (F_nc - F), the applied loads (F without loads - F), and per
// body the normal forces of the edge samples shared to their edges' vertices
// and the force of the body's own contact with each vertex.
struct VertexForces {
  std::vector<Eigen::Vector3d> positions, residual, needed_contact, applied_contact, load;
  std::vector<std::vector<Eigen::Vector3d>> sample_loads, vertex_contact;
  double residual_norm = 0.0;
};

PetscErrorCode gather_forces(ClothProblem& problem, Vec x, VertexForces* forces) {
  Vec f = nullptr, other = nullptr, difference = nullptr;
  PetscFunctionBeginUser;
  PetscCall(VecDuplicate(x, &f));
  PetscCall(VecDuplicate(x, &other));
  PetscCall(VecDuplicate(x, &difference));
  PetscCall(problem.gather_positions(x, &forces->positions));
  PetscCall(problem.residual(x, f));
  PetscCall(VecNorm(f, NORM_2, &forces->residual_norm));
  PetscCall(problem.gather_positions(f, &forces->residual));
  {
    // Bodies (and with them their friction anchors) out of the problem.
    std::vector<contact::Body> bodies;
    std::swap(bodies, problem.bodies);
    const PetscErrorCode failed = problem.residual(x, other);
    std::swap(bodies, problem.bodies);
    PetscCall(failed);
  }
  PetscCall(problem.gather_positions(other, &forces->needed_contact));
  PetscCall(VecWAXPY(difference, -1.0, f, other));
  PetscCall(problem.gather_positions(difference, &forces->applied_contact));
  {
    ClothLoads loads;
    std::swap(loads, problem.loads);
    const PetscErrorCode failed = problem.residual(x, other);
    std::swap(loads, problem.loads);
    PetscCall(failed);
  }
  PetscCall(VecWAXPY(difference, -1.0, f, other));
  PetscCall(problem.gather_positions(difference, &forces->load));
  PetscCall(problem.gather_body_vertex_forces(x, &forces->sample_loads, &forces->vertex_contact));
  for (Vec* v : {&f, &other, &difference})
    PetscCall(VecDestroy(v));
  PetscFunctionReturn(0);
}

// The lowest signed distance to `body` along segment a-b, marching by steps
// no longer than the distance allows (d / slope bound: no crossing is stepped
// over), at least `floor_step`.
double lowest_distance_along(const contact::Body& body, double clock, const Eigen::Vector3d& a,
                             const Eigen::Vector3d& b, double floor_step) {
  const double length = (b - a).norm();
  const double slope = body.shape().slope_bound();
  double lowest = std::numeric_limits<double>::infinity();
  for (double s = 0.0;;) {
    const Eigen::Vector3d p = length > 0.0 ? Eigen::Vector3d(a + (s / length) * (b - a)) : a;
    const double d = body.distance(p, clock);
    lowest = std::min(lowest, d);
    if (s >= length) break;
    s = std::min(length, s + std::max(std::abs(d) / slope, floor_step));
  }
  return lowest;
}

// Rank 0: depth and edge checks.
void check_geometry(const ClothProblem& problem, const VertexForces& forces,
                    const std::vector<bool>& free, Certificate* c) {
  const double clock = body_clock(problem);
  const double offset = problem.contact.offset;
  c->min_distance = std::numeric_limits<double>::infinity();
  for (std::size_t v = 0; v < free.size(); ++v) {
    if (!free[v]) continue;
    for (const contact::Body& body : problem.bodies) {
      const double d = body.distance(forces.positions[v], clock);
      if (d < c->min_distance) {
        c->min_distance = d;
        c->deepest_vertex = long(v);
      }
    }
  }
  c->relative_depth = (offset - c->min_distance) / offset;
  for (const auto& [a, b] : mesh_edges(problem.mesh())) {
    ++c->edges;
    const Eigen::Vector3d& pa = forces.positions[std::size_t(a)];
    const Eigen::Vector3d& pb = forces.positions[std::size_t(b)];
    double lowest = std::numeric_limits<double>::infinity();
    bool ends_outside = true;
    for (const contact::Body& body : problem.bodies) {
      lowest = std::min(lowest, lowest_distance_along(body, clock, pa, pb, 0.1 * offset));
      ends_outside =
          ends_outside && body.distance(pa, clock) >= 0.0 && body.distance(pb, clock) >= 0.0;
    }
    if (lowest >= 0.0) continue;
    ++c->edges_inside;
    if (ends_outside) ++c->edges_through;
    c->deepest_edge_point = std::min(c->deepest_edge_point, lowest);
  }
}

// One body's contact with one vertex against Coulomb's law: `f` is what its
// own contact (penalty and friction anchor) supplies, `samples` the
// frictionless normal force of its edge samples shared to the vertex, whose
// normal part counts in the cone, as it bounds the anchor's spring
// (ContactForm::accept_step).
void classify_contact(const Eigen::Vector3d& f, const Eigen::Vector3d& samples,
                      const Eigen::Vector3d& n, const contact::Friction& friction, double tolerance,
                      double floor, long vertex, CoulombCheck* check) {
  const double own_normal = f.dot(n);
  const double tangential = (f - own_normal * n).norm();
  const double normal = own_normal + std::max(0.0, n.dot(samples));
  ++check->contacts;
  if (normal < -tolerance * f.norm() - floor) {
    ++check->pulling;
    return;
  }
  const double cone = std::max(normal, 0.0) * friction.static_coefficient;
  const double ratio = tangential / std::max(cone > 0.0 ? cone : normal, floor);
  if (ratio > check->worst_ratio) {
    check->worst_ratio = ratio;
    check->worst_vertex = vertex;
  }
  if (tangential > cone * (1.0 + tolerance) + tolerance * std::max(normal, 0.0) + floor) {
    ++check->outside_cone;
  } else if (friction.active() &&
             tangential >= friction.kinetic_coefficient * normal * (1.0 - tolerance)) {
    ++check->sliding;
  } else {
    ++check->sticking;
  }
}

// Rank 0: Coulomb's law at every vertex a body pushes on, body by body:
// each body's anchor at a vertex is bounded by that body's normal force, so
// a vertex squeezed between two bodies (a specimen clamped between discs)
// holds the friction of both cones. What equilibrium needs beyond what the
// contact applies (the residual) is asked of the nearest body.
void check_coulomb(const ClothProblem& problem, const VertexForces& forces,
                   const std::vector<bool>& free, double floor, Certificate* c) {
  const double clock = body_clock(problem);
  std::vector<contact::SurfaceQuery> queries(problem.bodies.size());
  for (std::size_t v = 0; v < free.size(); ++v) {
    if (!free[v] || forces.applied_contact[v].norm() <= floor) continue;
    std::size_t nearest = 0;
    for (std::size_t b = 0; b < problem.bodies.size(); ++b) {
      queries[b] = problem.bodies[b].query(forces.positions[v], clock);
      if (queries[b].distance < queries[nearest].distance) nearest = b;
    }
    const Eigen::Vector3d unbalanced = forces.needed_contact[v] - forces.applied_contact[v];
    for (std::size_t b = 0; b < problem.bodies.size(); ++b) {
      Eigen::Vector3d f = forces.vertex_contact[b][v];
      if (b == nearest) f += unbalanced;
      const Eigen::Vector3d& samples = forces.sample_loads[b][v];
      if (b != nearest && (f + samples).norm() <= floor) continue; // b does not touch v
      if (queries[b].normal.norm() == 0.0) continue;               // no direction (a medial point)
      classify_contact(f, samples, queries[b].normal.normalized(), problem.bodies[b].friction,
                       c->options.cone_tolerance, floor, long(v), &c->coulomb);
    }
  }
}

// Rank 0: did the cloth end below its whole start?
void check_fall(const ClothProblem& problem, const VertexForces& forces, const Eigen::Vector3d& up,
                PlacementCheck* placement) {
  const auto& start = problem.mesh().positions;
  double lowest_start = std::numeric_limits<double>::infinity();
  double highest_end = -lowest_start, drop = 0.0;
  for (std::size_t v = 0; v < start.size(); ++v) {
    lowest_start = std::min(lowest_start, start[v].dot(up));
    highest_end = std::max(highest_end, forces.positions[v].dot(up));
    drop += (start[v] - forces.positions[v]).dot(up);
  }
  placement->fell_below_start = highest_end < lowest_start;
  placement->centroid_drop = start.empty() ? 0.0 : drop / double(start.size());
}

// Collective: the shares of the support each body and the pins carry.
PetscErrorCode check_support(ClothProblem& problem, Vec x, const Eigen::Vector3d& up,
                             PlacementCheck* placement) {
  std::vector<BodyContact> report;
  Eigen::Vector3d pins = Eigen::Vector3d::Zero();
  PetscFunctionBeginUser;
  PetscCall(problem.contact_report(x, &report));
  PetscCall(problem.pin_reaction(x, &pins));
  double total = pins.dot(up), planes = 0.0, others = pins.dot(up);
  std::vector<double> carried;
  bool has_other_bodies = false;
  for (std::size_t b = 0; b < report.size(); ++b) {
    carried.push_back((report[b].normal_force + report[b].friction_force).dot(up));
    total += carried.back();
    const bool plane = dynamic_cast<const contact::Plane*>(&problem.bodies[b].shape()) != nullptr;
    (plane ? planes : others) += carried.back();
    has_other_bodies = has_other_bodies || !plane;
  }
  placement->applicable = true;
  for (double share : carried)
    placement->carried_share.push_back(total > 0.0 ? share / total : 0.0);
  placement->pins_share = total > 0.0 ? pins.dot(up) / total : 0.0;
  placement->on_floor = has_other_bodies && total > 0.0 && planes > 0.1 * total;
  placement->off_body = total <= 0.0 || (has_other_bodies && others < 0.5 * total);
  PetscFunctionReturn(0);
}

// Packs the rank-0 results for a broadcast, and back.
std::vector<double> pack(const Certificate& c) {
  const CoulombCheck& k = c.coulomb;
  return {c.min_distance,
          c.relative_depth,
          double(c.deepest_vertex),
          double(c.edges),
          double(c.edges_inside),
          double(c.edges_through),
          c.deepest_edge_point,
          double(k.contacts),
          double(k.sticking),
          double(k.sliding),
          double(k.outside_cone),
          double(k.pulling),
          k.worst_ratio,
          double(k.worst_vertex),
          c.reference_force,
          double(c.placement.fell_below_start),
          c.placement.centroid_drop};
}

void unpack(const std::vector<double>& p, Certificate* c) {
  CoulombCheck& k = c->coulomb;
  c->min_distance = p[0];
  c->relative_depth = p[1];
  c->deepest_vertex = long(p[2]);
  c->edges = long(p[3]);
  c->edges_inside = long(p[4]);
  c->edges_through = long(p[5]);
  c->deepest_edge_point = p[6];
  k.contacts = long(p[7]);
  k.sticking = long(p[8]);
  k.sliding = long(p[9]);
  k.outside_cone = long(p[10]);
  k.pulling = long(p[11]);
  k.worst_ratio = p[12];
  k.worst_vertex = long(p[13]);
  c->reference_force = p[14];
  c->placement.fell_below_start = p[15] != 0.0;
  c->placement.centroid_drop = p[16];
}

// Rank 0: the applied load on the free vertices and the checks that need
// every vertex.
void check_on_root(const ClothProblem& problem, const VertexForces& forces,
                   const Eigen::Vector3d& up, Certificate* c) {
  const std::vector<bool> free = free_vertices(problem);
  long free_count = 0;
  for (std::size_t v = 0; v < free.size(); ++v) {
    if (!free[v]) continue;
    ++free_count;
    c->reference_force += forces.load[v].norm();
  }
  if (c->reference_force <= 0.0) c->reference_force = problem.force_scale();
  const double floor =
      c->options.contact_force_floor * c->reference_force / double(std::max(1L, free_count));
  if (c->has_bodies) {
    check_geometry(problem, forces, free, c);
    check_coulomb(problem, forces, free, floor, c);
  }
  if (c->placement.applicable) check_fall(problem, forces, up, &c->placement);
}

// --- stability ---

// The true Hessian at x; its symmetric part when the problem has no potential.
PetscErrorCode true_hessian(ClothProblem& problem, Vec x, Mat* hessian, bool* symmetrised) {
  bool changed = false;
  PetscFunctionBeginUser;
  PetscCall(problem.refresh_couplings(x, &changed)); // every self-contact pair at x
  PetscCall(problem.create_jacobian(hessian));
  const bool saved = problem.exact_hessian;
  problem.exact_hessian = true;
  const PetscErrorCode failed = problem.jacobian(x, *hessian);
  problem.exact_hessian = saved;
  PetscCall(failed);
  *symmetrised = !problem.has_potential();
  if (*symmetrised) {
    Mat transpose = nullptr;
    PetscCall(MatTranspose(*hessian, MAT_INITIAL_MATRIX, &transpose));
    PetscCall(MatAXPY(transpose, 1.0, *hessian, DIFFERENT_NONZERO_PATTERN));
    PetscCall(MatScale(transpose, 0.5));
    PetscCall(MatDestroy(hessian));
    *hessian = transpose;
  }
  PetscCall(MatSetOption(*hessian, MAT_SYMMETRIC, PETSC_TRUE));
  PetscCall(MatSetOptionsPrefix(*hessian, "certificate_"));
  PetscFunctionReturn(0);
}

// Rows of pins that hold in x's layout (released pins of time stepping hold
// until their release): excluded from the free dofs by decoupling them with
// a unit diagonal and no mass. Returns their number.
PetscErrorCode decouple_held_rows(ClothProblem& problem, Mat hessian, Vec mass, PetscInt* held) {
  std::vector<Eigen::Vector3d> marks(problem.mesh().vertex_count(), Eigen::Vector3d::Zero());
  bool any = false;
  Vec indicator = nullptr;
  PetscFunctionBeginUser;
  *held = 0;
  for (std::size_t i = 0; i < problem.pinned().size(); ++i) {
    if (!std::isfinite(problem.release_times()[i]) || !problem.holds(i)) continue;
    marks[std::size_t(problem.pinned()[i])].setOnes();
    any = true;
  }
  if (!any) PetscFunctionReturn(0);
  PetscCall(VecDuplicate(mass, &indicator));
  PetscCall(problem.set_solution(marks, indicator));
  PetscInt first = 0, last = 0;
  PetscCall(VecGetOwnershipRange(indicator, &first, &last));
  const PetscScalar* values = nullptr;
  std::vector<PetscInt> rows;
  PetscCall(VecGetArrayRead(indicator, &values));
  for (PetscInt i = first; i < last; ++i)
    if (values[i - first] != 0.0) rows.push_back(i);
  PetscCall(VecRestoreArrayRead(indicator, &values));
  PetscCall(MatZeroRowsColumns(hessian, PetscInt(rows.size()), rows.data(), 1.0, nullptr, nullptr));
  for (PetscInt row : rows)
    PetscCall(VecSetValue(mass, row, 0.0, INSERT_VALUES));
  PetscCall(VecAssemblyBegin(mass));
  PetscCall(VecAssemblyEnd(mass));
  PetscCall(VecDestroy(&indicator));
  const PetscInt local = PetscInt(rows.size());
  PetscCallMPI(MPIU_Allreduce(&local, held, 1, MPIU_INT, MPI_SUM, problem.comm()));
  PetscFunctionReturn(0);
}

// MUMPS reports the global inertia on several ranks only with ICNTL(13) = 1
// (no ScaLAPACK on the root front); the certificate's factorisations read
// their options with the prefix certificate_.
PetscErrorCode require_serial_root(MPI_Comm comm) {
  PetscMPIInt size = 1;
  PetscBool set = PETSC_FALSE;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCall(PetscOptionsHasName(nullptr, "certificate_", "-mat_mumps_icntl_13", &set));
  if (size > 1 && !set)
    PetscCall(PetscOptionsSetValue(nullptr, "-certificate_mat_mumps_icntl_13", "1"));
  PetscFunctionReturn(0);
}

// H - shift M, LDL^T-factorised by MUMPS; *factored false when MUMPS failed.
PetscErrorCode factor_shifted(Mat hessian, Vec mass, double shift, Mat* factor, bool* factored) {
  Mat shifted = nullptr;
  Vec diagonal = nullptr;
  MatFactorInfo info;
  MatFactorError error = MAT_FACTOR_NOERROR;
  PetscFunctionBeginUser;
  PetscCall(require_serial_root(PetscObjectComm(reinterpret_cast<PetscObject>(hessian))));
  PetscCall(MatDuplicate(hessian, MAT_COPY_VALUES, &shifted));
  PetscCall(MatSetOptionsPrefix(shifted, "certificate_"));
  PetscCall(MatSetOption(shifted, MAT_SYMMETRIC, PETSC_TRUE));
  PetscCall(VecDuplicate(mass, &diagonal));
  PetscCall(VecAXPY(diagonal, -shift, mass));
  PetscCall(MatDiagonalSet(shifted, diagonal, ADD_VALUES));
  PetscCall(MatGetFactor(shifted, MATSOLVERMUMPS, MAT_FACTOR_CHOLESKY, factor));
  PetscCall(MatSetOptionsPrefix(*factor, "certificate_"));
  PetscCall(MatFactorInfoInitialize(&info));
  PetscCall(MatCholeskyFactorSymbolic(*factor, shifted, nullptr, &info));
  PetscCall(MatCholeskyFactorNumeric(*factor, shifted, &info));
  PetscCall(MatFactorGetError(*factor, &error));
  *factored = error == MAT_FACTOR_NOERROR;
  PetscCall(VecDestroy(&diagonal));
  PetscCall(MatDestroy(&shifted));
  PetscFunctionReturn(0);
}

// The number of eigenvalues of H v = lambda M v below `shift`; -1 when the
// factorisation failed (an eigenvalue at the shift).
PetscErrorCode count_below(Mat hessian, Vec mass, double shift, PetscInt* count) {
  Mat factor = nullptr;
  bool factored = false;
  PetscFunctionBeginUser;
  PetscCall(factor_shifted(hessian, mass, shift, &factor, &factored));
  *count = -1;
  if (factored) PetscCall(MatGetInertia(factor, count, nullptr, nullptr));
  PetscCall(MatDestroy(&factor));
  PetscFunctionReturn(0);
}

// sigma of the header: zero_mode_tolerance |g| / L.
double zero_mode_shift(const ClothProblem& problem, const CertificateOptions& options) {
  const auto& p = problem.mesh().positions;
  Eigen::Vector3d low = p.empty() ? Eigen::Vector3d::Zero() : p.front(), high = low;
  for (const auto& q : p) {
    low = low.cwiseMin(q);
    high = high.cwiseMax(q);
  }
  const double g =
      problem.loads.gravity.norm() > 0.0 ? problem.loads.gravity.norm() : standard_gravity;
  const double size = (high - low).norm() > 0.0 ? (high - low).norm() : 1.0;
  return options.zero_mode_tolerance * g / size;
}

// The true Hessian and the mass the inertia is taken against, with held
// rows decoupled; `free` the number of free dofs.
struct HessianPencil {
  Mat hessian = nullptr;
  Vec mass = nullptr;
  PetscInt free = 0;
  bool symmetrised = false;
  ~HessianPencil() {
    MatDestroy(&hessian);
    VecDestroy(&mass);
  }
};

PetscErrorCode build_pencil(ClothProblem& problem, Vec x, HessianPencil* pencil) {
  PetscInt held = 0;
  PetscFunctionBeginUser;
  PetscCall(true_hessian(problem, x, &pencil->hessian, &pencil->symmetrised));
  PetscCall(VecDuplicate(x, &pencil->mass));
  PetscCall(problem.lumped_mass(pencil->mass));
  PetscCall(decouple_held_rows(problem, pencil->hessian, pencil->mass, &held));
  pencil->free = problem.global_dof_count() - held;
  PetscFunctionReturn(0);
}

PetscErrorCode check_stability(ClothProblem& problem, Vec x, Certificate* c) {
  HessianPencil pencil;
  PetscInt below_minus = 0, below_plus = 0;
  PetscFunctionBeginUser;
  StabilityCheck& s = c->stability;
  PetscCall(build_pencil(problem, x, &pencil));
  s.sigma = zero_mode_shift(problem, c->options);
  s.free_dofs = long(pencil.free);
  s.from_symmetric_part = pencil.symmetrised;
  PetscCall(count_below(pencil.hessian, pencil.mass, -s.sigma, &below_minus));
  PetscCall(count_below(pencil.hessian, pencil.mass, s.sigma, &below_plus));
  s.assessed = below_minus >= 0 && below_plus >= 0;
  if (s.assessed) {
    s.negative = long(below_minus);
    s.zero_modes = long(below_plus - below_minus);
  }
  PetscFunctionReturn(0);
}

// A start for inverse iteration that is the same on any number of ranks:
// a fixed pseudo-random vector in mesh numbering.
PetscErrorCode deterministic_start(ClothProblem& problem, Vec v) {
  std::vector<Eigen::Vector3d> values(problem.mesh().vertex_count());
  PetscFunctionBeginUser;
  for (std::size_t i = 0; i < values.size(); ++i) {
    for (int d = 0; d < 3; ++d) {
      const double s = std::sin(12.9898 * double(3 * i + std::size_t(d) + 1)) * 43758.5453;
      values[i][d] = s - std::floor(s) - 0.5;
    }
  }
  PetscCall(problem.set_solution(values, v));
  PetscFunctionReturn(0);
}

// A shift below the lowest eigenvalue: -sigma doubled until nothing is
// below it, then halved back towards the lowest eigenvalue.
PetscErrorCode shift_below_spectrum(const HessianPencil& pencil, double sigma, double* shift,
                                    bool* found) {
  PetscInt count = 0;
  PetscFunctionBeginUser;
  *found = false;
  double above = -sigma, below = -2.0 * sigma;
  for (int k = 0; k < 80; ++k, above = below, below *= 2.0) {
    PetscCall(count_below(pencil.hessian, pencil.mass, below, &count));
    if (count == 0) {
      *found = true;
      break;
    }
  }
  if (!*found) PetscFunctionReturn(0);
  for (int k = 0; k < 6; ++k) {
    const double middle = 0.5 * (above + below);
    PetscCall(count_below(pencil.hessian, pencil.mass, middle, &count));
    (count == 0 ? below : above) = middle;
  }
  *shift = below;
  PetscFunctionReturn(0);
}

PetscErrorCode mass_normalise(Vec v, Vec mass, Vec work) {
  PetscScalar norm2 = 0.0;
  PetscFunctionBeginUser;
  PetscCall(VecPointwiseMult(work, mass, v));
  PetscCall(VecDot(work, v, &norm2));
  if (norm2 > 0.0) PetscCall(VecScale(v, 1.0 / std::sqrt(norm2)));
  PetscFunctionReturn(0);
}

} // namespace

bool Certificate::certified() const {
  return verdict() == "certified";
}

std::string Certificate::verdict() const {
  char text[160];
  if (saddle()) {
    std::snprintf(text, sizeof text, "saddle (%ld negative direction%s)", stability.negative,
                  stability.negative == 1 ? "" : "s");
    return text;
  }
  if (!equilibrium()) {
    std::snprintf(text, sizeof text, "residual %.2e of the load", relative_residual);
    return text;
  }
  if (!outside_bodies()) {
    std::snprintf(text, sizeof text, "a vertex %.2e m inside a body", -min_distance);
    return text;
  }
  if (!edges_clear()) {
    std::snprintf(text, sizeof text, "%ld edge(s) through a body", edges_inside);
    return text;
  }
  if (!seams_closed()) {
    std::snprintf(text, sizeof text, "seam gap %.2e m", seam_gap);
    return text;
  }
  if (!coulomb.passed()) {
    std::snprintf(text, sizeof text, "Coulomb violated at %ld contact(s)",
                  coulomb.outside_cone + coulomb.pulling);
    return text;
  }
  if (placement.fell_below_start) return "fell below its start";
  if (placement.off_body) return "off the body";
  if (placement.on_floor) return "on the floor";
  if (options.stability && !stability.assessed) return "stability not assessed";
  return "certified";
}

PetscErrorCode certify(ClothProblem& problem, Vec x, const CertificateOptions& options,
                       Certificate* certificate) {
  VertexForces forces;
  PetscFunctionBeginUser;
  Certificate& c = *certificate;
  c = Certificate{};
  c.options = options;
  c.contact_offset = problem.contact.offset;
  c.has_bodies = !problem.bodies.empty();
  const Eigen::Vector3d up = problem.loads.gravity.norm() > 0.0
                                 ? Eigen::Vector3d(-problem.loads.gravity.normalized())
                                 : Eigen::Vector3d::Zero();
  c.placement.applicable = c.has_bodies && up.norm() > 0.0;
  PetscCall(gather_forces(problem, x, &forces));
  c.residual_norm = forces.residual_norm;
  std::vector<double> packed;
  if (is_root(problem.comm())) {
    check_on_root(problem, forces, up, &c);
    packed = pack(c);
  }
  packed.resize(pack(c).size());
  PetscCallMPI(MPI_Bcast(packed.data(), int(packed.size()), MPI_DOUBLE, 0, problem.comm()));
  unpack(packed, &c);
  c.relative_residual = c.residual_norm / c.reference_force;
  PetscCall(problem.seam_gap(x, &c.seam_gap));
  if (c.placement.applicable) PetscCall(check_support(problem, x, up, &c.placement));
  if (options.stability) PetscCall(check_stability(problem, x, &c));
  PetscFunctionReturn(0);
}

PetscErrorCode descent_direction(ClothProblem& problem, Vec x, const CertificateOptions& options,
                                 Vec v, double* curvature, bool* found) {
  HessianPencil pencil;
  Mat factor = nullptr;
  Vec rhs = nullptr, work = nullptr;
  double shift = 0.0;
  bool factored = false;
  PetscFunctionBeginUser;
  *found = false;
  *curvature = 0.0;
  PetscCall(build_pencil(problem, x, &pencil));
  const double sigma = zero_mode_shift(problem, options);
  PetscCall(shift_below_spectrum(pencil, sigma, &shift, found));
  if (!*found) PetscFunctionReturn(0);
  PetscCall(factor_shifted(pencil.hessian, pencil.mass, shift, &factor, &factored));
  *found = factored;
  if (!factored) {
    PetscCall(MatDestroy(&factor));
    PetscFunctionReturn(0);
  }
  PetscCall(VecDuplicate(v, &rhs));
  PetscCall(VecDuplicate(v, &work));
  PetscCall(deterministic_start(problem, v));
  PetscCall(mass_normalise(v, pencil.mass, work));
  // Inverse iteration: the lowest mode gains on the next by their distances
  // to the shift, at least twofold after the halving above.
  for (int k = 0; k < 40; ++k) {
    PetscCall(VecPointwiseMult(rhs, pencil.mass, v));
    PetscCall(MatSolve(factor, rhs, v));
    PetscCall(mass_normalise(v, pencil.mass, work));
  }
  PetscCall(MatMult(pencil.hessian, v, work));
  PetscCall(VecDot(work, v, curvature));
  *found = *curvature < -sigma;
  PetscCall(MatDestroy(&factor));
  PetscCall(VecDestroy(&rhs));
  PetscCall(VecDestroy(&work));
  PetscFunctionReturn(0);
}

PetscErrorCode push_off_saddle(ClothProblem& problem, Vec x, const CertificateOptions& options,
                               double push, bool* pushed) {
  Vec mode = nullptr, plus = nullptr;
  double curvature = 0.0, largest = 0.0;
  ClothEnergy up, down;
  PetscFunctionBeginUser;
  PetscCall(VecDuplicate(x, &mode));
  PetscCall(descent_direction(problem, x, options, mode, &curvature, pushed));
  PetscCall(VecNorm(mode, NORM_INFINITY, &largest));
  *pushed = *pushed && largest > 0.0;
  if (*pushed) {
    const double step = push / largest;
    PetscCall(VecDuplicate(x, &plus));
    PetscCall(VecWAXPY(plus, step, mode, x));
    PetscCall(problem.energy(plus, &up));
    PetscCall(VecAXPY(x, -step, mode));
    PetscCall(problem.energy(x, &down));
    if (up.total() <= down.total()) PetscCall(VecCopy(plus, x));
    PetscCall(VecDestroy(&plus));
  }
  PetscCall(VecDestroy(&mode));
  PetscFunctionReturn(0);
}

nlohmann::json certificate_json(const Certificate& c) {
  nlohmann::json json = {{"certified", c.certified()},
                         {"verdict", c.verdict()},
                         {"equilibrium",
                          {{"passed", c.equilibrium()},
                           {"residual_norm_N", c.residual_norm},
                           {"reference_force_N", c.reference_force},
                           {"relative_residual", c.relative_residual},
                           {"tolerance", c.options.residual_tolerance}}},
                         {"seams",
                          {{"passed", c.seams_closed()},
                           {"largest_gap_m", c.seam_gap},
                           {"tolerance_m", c.options.seam_gap_tolerance}}}};
  if (c.has_bodies) {
    json["depth"] = {
        {"passed", c.outside_bodies()},       {"contact_offset_m", c.contact_offset},
        {"min_distance_m", c.min_distance},   {"relative_depth", c.relative_depth},
        {"deepest_vertex", c.deepest_vertex}, {"tolerance", c.options.depth_tolerance}};
    json["edges"] = {{"passed", c.edges_clear()},
                     {"tested", c.edges},
                     {"inside_a_body", c.edges_inside},
                     {"both_ends_outside", c.edges_through},
                     {"deepest_point_m", c.deepest_edge_point}};
    const CoulombCheck& k = c.coulomb;
    json["coulomb"] = {{"passed", k.passed()},
                       {"contacts", k.contacts},
                       {"sticking", k.sticking},
                       {"sliding", k.sliding},
                       {"outside_cone", k.outside_cone},
                       {"pulling", k.pulling},
                       {"worst_ratio", k.worst_ratio},
                       {"worst_vertex", k.worst_vertex},
                       {"tolerance", c.options.cone_tolerance}};
  }
  if (c.placement.applicable) {
    const PlacementCheck& p = c.placement;
    json["placement"] = {{"passed", p.passed()},
                         {"body_shares", p.carried_share},
                         {"pins_share", p.pins_share},
                         {"on_floor", p.on_floor},
                         {"off_body", p.off_body},
                         {"fell_below_start", p.fell_below_start},
                         {"centroid_drop_m", p.centroid_drop}};
  }
  const StabilityCheck& s = c.stability;
  json["stability"] = {{"requested", c.options.stability},
                       {"assessed", s.assessed},
                       {"stable", s.stable()},
                       {"saddle", c.saddle()},
                       {"free_dofs", s.free_dofs},
                       {"negative_directions", s.negative},
                       {"zero_modes", s.zero_modes},
                       {"zero_mode_shift_per_s2", s.sigma},
                       {"from_symmetric_part", s.from_symmetric_part}};
  return json;
}

Certificate certificate_from_json(const nlohmann::json& json) {
  Certificate c;
  const nlohmann::json& equilibrium = json.at("equilibrium");
  c.residual_norm = equilibrium.at("residual_norm_N").get<double>();
  c.reference_force = equilibrium.at("reference_force_N").get<double>();
  c.relative_residual = equilibrium.at("relative_residual").get<double>();
  c.options.residual_tolerance = equilibrium.at("tolerance").get<double>();
  const nlohmann::json& seams = json.at("seams");
  c.seam_gap = seams.at("largest_gap_m").get<double>();
  c.options.seam_gap_tolerance = seams.at("tolerance_m").get<double>();
  c.has_bodies = json.contains("depth");
  if (c.has_bodies) {
    const nlohmann::json& depth = json.at("depth");
    c.contact_offset = depth.at("contact_offset_m").get<double>();
    c.min_distance = depth.at("min_distance_m").get<double>();
    c.relative_depth = depth.at("relative_depth").get<double>();
    c.deepest_vertex = depth.at("deepest_vertex").get<long>();
    c.options.depth_tolerance = depth.at("tolerance").get<double>();
    const nlohmann::json& edges = json.at("edges");
    c.edges = edges.at("tested").get<long>();
    c.edges_inside = edges.at("inside_a_body").get<long>();
    c.edges_through = edges.at("both_ends_outside").get<long>();
    c.deepest_edge_point = edges.at("deepest_point_m").get<double>();
    const nlohmann::json& coulomb = json.at("coulomb");
    CoulombCheck& k = c.coulomb;
    k.contacts = coulomb.at("contacts").get<long>();
    k.sticking = coulomb.at("sticking").get<long>();
    k.sliding = coulomb.at("sliding").get<long>();
    k.outside_cone = coulomb.at("outside_cone").get<long>();
    k.pulling = coulomb.at("pulling").get<long>();
    k.worst_ratio = coulomb.at("worst_ratio").get<double>();
    k.worst_vertex = coulomb.at("worst_vertex").get<long>();
    c.options.cone_tolerance = coulomb.at("tolerance").get<double>();
  }
  c.placement.applicable = json.contains("placement");
  if (c.placement.applicable) {
    const nlohmann::json& placement = json.at("placement");
    PlacementCheck& p = c.placement;
    p.carried_share = placement.at("body_shares").get<std::vector<double>>();
    p.pins_share = placement.at("pins_share").get<double>();
    p.on_floor = placement.at("on_floor").get<bool>();
    p.off_body = placement.at("off_body").get<bool>();
    p.fell_below_start = placement.at("fell_below_start").get<bool>();
    p.centroid_drop = placement.at("centroid_drop_m").get<double>();
  }
  const nlohmann::json& stability = json.at("stability");
  StabilityCheck& s = c.stability;
  s.assessed = stability.at("assessed").get<bool>();
  s.from_symmetric_part = stability.at("from_symmetric_part").get<bool>();
  s.free_dofs = stability.at("free_dofs").get<long>();
  s.negative = stability.at("negative_directions").get<long>();
  s.zero_modes = stability.at("zero_modes").get<long>();
  s.sigma = stability.at("zero_mode_shift_per_s2").get<double>();
  c.options.stability = stability.at("requested").get<bool>();
  return c;
}

} // namespace sartor
