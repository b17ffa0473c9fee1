#pragma once
// A certificate of a static equilibrium (docs/certificate.md): what a solver
// claims as converged, checked at the state x against the physics, not
// against the solver's own stopping test.
//
//  * equilibrium: the free-vertex residual force (2-norm) over the applied
//    load (the sum of the free vertices' load magnitudes: their weight when
//    gravity is the load);
//  * seams: the largest seam gap;
//  * depth: the deepest free vertex, offset - d_min, over the contact offset
//    (above 1: the vertex is inside a body);
//  * edges: every cloth edge marched along against every body's signed
//    distance (steps of d / slope bound, so that no crossing is stepped
//    over, down to a floor of a tenth of the offset): edges with a point
//    inside a body, and the deepest such point;
//  * Coulomb: at every vertex a body pushes on, the force the contact model
//    applies (the residual with the bodies minus the residual without them)
//    split into normal f_n (along the body's normal) and tangential f_t:
//    the body may only push (f_n > -tolerance) and |f_t| <= mu_s f_n within
//    the tolerance (sticking inside the cone, sliding on it at mu_k);
//  * placement: the share of the weight each body carries; a drape on a
//    body whose weight ends on a plane (the floor) while other bodies are
//    there, or that no body or pin carries, or that fell below its whole
//    start, is reported;
//  * stability: the inertia of the true Hessian (no PSD projection of any
//    element) on the free dofs, against the lumped mass M: the number of
//    eigenvalues of H v = lambda M v below -sigma (negative: a saddle),
//    within [-sigma, sigma] (zero-energy modes, e.g. a free rigid body),
//    from the LDL^T factorisations of H + sigma M and H - sigma M by MUMPS
//    (Sylvester's law of inertia). sigma = zero_mode_tolerance |g| / L,
//    L the diagonal of the cloth's starting bounding box (|g| = 9.80665
//    m/s^2 without gravity): a mode with |lambda| < sigma is slower than a
//    pendulum of length L by 1 / sqrt(zero_mode_tolerance).
//
// Collective. Every rank gets the same certificate.

#include "fem/cloth_problem.hpp"

#include <nlohmann/json_fwd.hpp>

#include <petscvec.h>

#include <string>
#include <vector>

namespace sartor {

struct CertificateOptions {
  double residual_tolerance = 1e-3; // residual force / applied load
  double seam_gap_tolerance = 1e-3; // m
  double depth_tolerance = 1.0;     // of the contact offset: 1 = at the body's surface
  double cone_tolerance = 0.05;     // relative excess of |f_t| over mu_s f_n allowed
  // Contact forces below this share of the mean vertex load are not
  // contacts (the residual's round-off).
  double contact_force_floor = 1e-3;
  double zero_mode_tolerance = 1e-4; // see above
  bool stability = true;             // factorise the Hessian (two LDL^T)
};

struct CoulombCheck {
  long contacts = 0;        // vertex-body pairs: a body pushes on the vertex
  long sticking = 0;        // |f_t| below mu_k f_n (1 - tolerance)
  long sliding = 0;         // on the cone: between mu_k and mu_s, within the tolerance
  long outside_cone = 0;    // |f_t| > mu_s f_n (1 + tolerance)
  long pulling = 0;         // the body pulls: f_n below -tolerance |f|
  double worst_ratio = 0.0; // max |f_t| / (mu_s f_n) over the contacts (mu_s = 0: |f_t| / f_n)
  long worst_vertex = -1;   // mesh vertex of worst_ratio
  bool passed() const { return outside_cone == 0 && pulling == 0; }
};

struct StabilityCheck {
  bool assessed = false;
  bool from_symmetric_part = false; // the Jacobian is not symmetric (no potential)
  long free_dofs = 0;
  long negative = 0;   // eigenvalues below -sigma: directions of descent (a saddle)
  long zero_modes = 0; // within [-sigma, sigma]
  double sigma = 0.0;  // 1/s^2
  bool stable() const { return assessed && negative == 0; }
};

struct PlacementCheck {
  bool applicable = false;           // there are bodies and a load along gravity
  std::vector<double> carried_share; // per body: its reaction along -g over the weight
  double pins_share = 0.0;           // the pins' share
  bool on_floor = false;             // a plane carries > 10 % while other bodies are there
  bool off_body = false;             // bodies and pins carry < half the weight
  bool fell_below_start = false;     // the highest vertex ended below the lowest start
  double centroid_drop = 0.0;        // m, along g
  bool passed() const { return !applicable || (!on_floor && !off_body && !fell_below_start); }
};

struct Certificate {
  double residual_norm = 0.0;   // N
  double reference_force = 0.0; // N: the applied load (weight), or force_scale() without loads
  double relative_residual = 0.0;
  double seam_gap = 0.0;       // m
  double contact_offset = 0.0; // m
  double min_distance = 0.0;   // m: smallest signed distance of a free vertex to a body
  double relative_depth = 0.0; // (offset - min_distance) / offset; 0 without bodies
  long deepest_vertex = -1;
  long edges = 0;                  // cloth edges tested
  long edges_inside = 0;           // with a point inside a body
  long edges_through = 0;          // of these, both ends outside (a chord or a thin part)
  double deepest_edge_point = 0.0; // m: most negative distance along an edge (0: none inside)
  bool has_bodies = false;
  CoulombCheck coulomb;
  PlacementCheck placement;
  StabilityCheck stability;
  CertificateOptions options;

  bool equilibrium() const { return relative_residual <= options.residual_tolerance; }
  bool seams_closed() const { return seam_gap <= options.seam_gap_tolerance; }
  bool outside_bodies() const { return !has_bodies || relative_depth <= options.depth_tolerance; }
  bool edges_clear() const { return edges_inside == 0; }
  bool saddle() const { return stability.assessed && stability.negative > 0; }
  bool certified() const;
  // The first failed check, for closing lines: "saddle (2 negative
  // directions)", "residual 3.2e-02 of the weight", ...; "certified" when none.
  std::string verdict() const;
};

// Collective: the certificate of state x of `problem` (positions, at its
// current load factor and time).
PetscErrorCode certify(ClothProblem& problem, Vec x, const CertificateOptions& options,
                       Certificate* certificate);

// Collective, for a state with a negative direction: a unit-mass-norm
// direction v (a solution vector) along which the true Hessian at x curves
// down, v^T H v < 0, and that curvature in 1/s^2 (v^T H v / v^T M v). By
// inverse iteration on H - mu M with mu below the lowest eigenvalue (found
// by halving the inertia's shift); `found` is false when none was found.
PetscErrorCode descent_direction(ClothProblem& problem, Vec x, const CertificateOptions& options,
                                 Vec v, double* curvature, bool* found);

// Collective: x pushed along the true Hessian's lowest mode
// (descent_direction) to whichever side Phi is lower, its largest vertex
// displacement `push` (m); *pushed is false, x unchanged, where the
// Hessian has no direction of descent (not a saddle).
PetscErrorCode push_off_saddle(ClothProblem& problem, Vec x, const CertificateOptions& options,
                               double push, bool* pushed);

// The "certificate" block of summary.json.
nlohmann::json certificate_json(const Certificate& certificate);
// Its inverse (a checkpoint keeps certificates so): the measures and the
// tolerances it holds, the other options at their defaults. Throws
// nlohmann::json::exception when a field is missing or of the wrong type.
Certificate certificate_from_json(const nlohmann::json& json);

} // namespace sartor
