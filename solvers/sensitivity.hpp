#pragma once
// Design sensitivity of a static drape (Sensitive Couture §4, docs/sensitivity.md).
//
// At an equilibrium R(x, X) = 0, x the vertex positions and X the rest
// (pattern) coordinates, a pattern change dX moves the equilibrium by
//     dx = S dX = -K^-1 (dR/dX dX),   K = dR/dx,
// the tangent K exact (no PSD projection: the true Hessian of the potential),
// with the contact and the friction anchors active at the equilibrium held as
// they are. K is factorised once (MUMPS LU) and each dX costs one residual
// derivative and one pair of triangular solves.
//
// dR/dX dX: the residual depends on X only through the rest data the problem
// builds from the mesh's material coordinates (triangle rest shapes and areas,
// hinge weights, bending patches, seam springs' stiffnesses and edge
// parameters, lumped masses, the automatic contact stiffness). It is the sum
// of the forms' rest derivatives (ClothProblem::rest_derivative) when every
// enabled form has one. Otherwise (seams still being sewn, a user's form
// without one), or with `difference_rest_derivative`, it is the central
// difference of the residual at fixed x between problems built on X + h dX
// and X - h dX, extrapolated (Richardson) to fourth order in h: each rebuilt
// problem takes the state of the equilibrium (loads, load factor, contact
// settings and anchors, creep state) from the problem given.
//
// Stabilisation (SC §7, "Full-rank of sensitivity matrix"): when K cannot be
// factorised, or the solve does not reproduce its right-hand side, K is taken
// from a problem whose bending stiffness is raised to that of a plate of
// relative thickness `stabilised_thickness` (D = k h^2 / 12, k the membrane's
// modulus, h that thickness times the panels' size), local to the
// sensitivity; the drape itself is not changed.

#include "fem/cloth_problem.hpp"
#include "mesh/triangle_mesh.hpp"

#include <petscksp.h>

#include <functional>
#include <memory>
#include <vector>

namespace sartor {

// The same change for every corner of a vertex (panels' vertices are not
// shared between panels, so one (u, v) change per vertex is a pattern change).
RestChange rest_change_per_vertex(const TriangleMesh& mesh,
                                  const std::vector<Eigen::Vector2d>& delta_uv);

// The mesh with its material coordinates moved by `scale` dX.
TriangleMesh moved_rest(const TriangleMesh& mesh, const RestChange& change, double scale);

// Builds the cloth problem of a mesh (materials, pins, seams: what depends on
// the pattern) the same way for any rest coordinates. `min_bending_stiffness`
// (N m) is a floor the builder must apply to its materials' bending
// stiffnesses: 0 except for the stabilised tangent.
using ProblemFactory = std::function<std::unique_ptr<ClothProblem>(
    MPI_Comm comm, const TriangleMesh& mesh, double min_bending_stiffness)>;

struct SensitivityOptions {
  // dR/dX dX by differences of rebuilt problems even where the forms have
  // exact rest derivatives (the check of the forms').
  bool difference_rest_derivative = false;
  // The difference step h times max |dX| over the mean edge length.
  double relative_step = 1e-4;
  // Relative residual |K dx + b| / |b| above which a solve counts as failed.
  double solve_tolerance = 1e-8;
  double stabilised_thickness = 1e-2; // SC §7: h = 1/100 of the panels' size
  bool stabilise = true;
  // The exact tangent (the derivative). false: the tangent the static
  // minimiser uses (element Hessians PSD-projected where the problem's
  // materials ask), which leaves out the negative curvature of compressed
  // and wrinkled cloth: a damped, not exact, response (`sartor edit
  // --sensitivity-tangent projected`).
  bool exact_tangent = true;
};

// The state of the equilibrium that a rebuilt problem must share (loads,
// load factor, contact settings and anchors, creep state, sewing): copied
// from `from` to `to`, problems of meshes of the same topology. Pins moved
// by set_pin_position are not carried over (their places come from the
// mesh, pin_motion and pin_groups). Collective.
PetscErrorCode copy_problem_state(ClothProblem& from, ClothProblem& to);

// Collective. Copies a vector of three values per vertex (positions,
// forces, changes) from the layout of one problem to that of another on a
// mesh of the same vertices: problems on different rest coordinates may
// distribute their vertices differently over the ranks. Pinned vertices of
// `to` are left out.
PetscErrorCode transfer_vector(ClothProblem& from, Vec v, ClothProblem& to, Vec w);

class DesignSensitivity {
public:
  // Collective. `problem` is at equilibrium at `x` (kept, not owned; the
  // problem's mesh must outlive this object); `factory` builds it from a mesh.
  DesignSensitivity(ClothProblem& problem, Vec x, ProblemFactory factory,
                    SensitivityOptions options = {});
  ~DesignSensitivity();
  DesignSensitivity(const DesignSensitivity&) = delete;
  DesignSensitivity& operator=(const DesignSensitivity&) = delete;

  // Collective. Assembles and factorises the exact tangent at x (the
  // stabilised one if it is singular). Called by apply() when needed.
  PetscErrorCode factorise();
  // Collective. dR/dX dX at x, in the layout of the problem's vectors.
  PetscErrorCode rest_derivative(const RestChange& change, Vec derivative);
  // Whether rest_derivative sums the forms' exact derivatives (or
  // differences rebuilt problems).
  bool sums_forms_rest_derivatives() const;
  // Collective. dx = S dX: the linear change of the equilibrium.
  PetscErrorCode apply(const RestChange& change, Vec dx);

  // Whether the tangent was stabilised (SC §7).
  bool stabilised() const { return stabilised_; }
  // Relative residual |K dx + b| / |b| of the last solve.
  double last_solve_residual() const { return last_solve_residual_; }

private:
  PetscErrorCode residual_of_moved(const RestChange& change, double scale, Vec f);
  PetscErrorCode factorise_tangent(ClothProblem& problem, bool* ok);
  PetscErrorCode solve(Vec rhs, Vec dx, bool* ok);
  // Factorises the tangent of the problem with stiffened bending (SC §7).
  PetscErrorCode stabilise();
  double difference_step(const RestChange& change) const;
  double stabilised_bending_stiffness() const;

  ClothProblem& problem_;
  Vec x_ = nullptr;
  ProblemFactory factory_;
  SensitivityOptions options_;
  Mat tangent_ = nullptr;
  ClothProblem* tangent_problem_ = nullptr; // whose tangent_ is: problem_ or the stabilised one
  KSP ksp_ = nullptr;
  bool factorised_ = false;
  bool stabilised_ = false;
  double last_solve_residual_ = 0.0;
  // The stabilised problem and its mesh, kept while its tangent is in use.
  std::unique_ptr<ClothProblem> stabilised_problem_;
};

} // namespace sartor
