#pragma once
// Contact kernels of one cloth vertex against one body: plain Eigen, no PETSc.
//
// Normal contact is a one-sided penalty on the depth g = offset - d(x) into
// the contact layer (d the signed distance to the body, kept at least
// `offset`, half the cloth's thickness, away from it). Its normal force is
//     f(g) = k g                          g >= b
//     f(g) = k (g^2 / b) (2 - g / b)      0 < g < b
// over an onset band b (ContactSettings::penalty_onset times the offset;
// 0, the default: E = k/2 max(0, g)^2), so that f and its slope
// f'(g) = k (4 - 3 g / b) g / b are continuous and E is C^2. The plain
// quadratic's Hessian jumps from 0 to k where a vertex touches the layer.
// Beyond the band the law is the plain one.
//     grad E = -f(g) n
//     hess E = f'(g) n n^T - f(g) H_d            (n = grad d, H_d = hess d)
// The curvature term is what makes the Jacobian exact on curved bodies; it is
// zero on flat faces. The force on the cloth is f(g) n.
//
// Coulomb friction uses moving anchors (Sensitive Couture §7, after Hasegawa
// et al.): a vertex in contact is tied to an anchor a on the body surface by a
// tangential spring of stiffness k_t whose force saturates at Coulomb's
// bound F = mu f_n (f_n the normal force when the anchor was last updated,
// lagged as in IPC's friction):
//     u = P (x - a),  P = I - m m^T,  s = |u|,  r = F / k_t
//     E = k_t/2 s^2                 (s <= r: sticking)
//     E = F (s - r/2)               (s >  r: sliding, force F along u)
// with the anchor, the tangent plane's normal m and F frozen while Newton
// iterates (so gradient and Hessian are exact; E is convex and C^1). A
// vertex can thus slide as far as the solve takes it, under the sliding
// force, instead of being held by an over-stretched spring. Between solves
// `slide_anchor` enforces Coulomb's law on the spring force (the return
// mapping onto the cone).

#include "contact/shape.hpp"
#include "element/element.hpp"
#include "element/penalty_law.hpp"

#include <Eigen/Core>

namespace sartor::contact {

// The part of a body's query the penalty's level `want` reads.
inline QueryNeeds query_needs(element::Want want) {
  switch (want) {
  case element::Want::energy:
    return QueryNeeds::distance;
  case element::Want::gradient:
    return QueryNeeds::normal;
  default:
    return QueryNeeds::curvature;
  }
}

// The penalty's law (element/penalty_law.hpp), shared with cloth self-contact.
using element::penalty_law;
using element::PenaltyLaw;

struct PointResult {
  double energy = 0.0;                                // J
  Eigen::Vector3d gradient = Eigen::Vector3d::Zero(); // N
  Eigen::Matrix3d hessian = Eigen::Matrix3d::Zero();  // N/m
};

// The normal penalty, from the body's query at the vertex, with onset band
// `band` (m).
PointResult penalty(double stiffness, double offset, const SurfaceQuery& query, element::Want want,
                    double band = 0.0);

// The tangential anchor spring with anchor `anchor`, tangent-plane normal
// `normal` (unit) and force bound `bound` (N; infinite: a plain spring) frozen.
PointResult anchor_spring(double stiffness, const Eigen::Vector3d& x, const Eigen::Vector3d& anchor,
                          const Eigen::Vector3d& normal, double bound, element::Want want);

// The same spring in the body's tangent plane at x rather than a frozen one:
// with m(x) = n / |n| the unit normal of the query at x (n its gradient of
// the distance) and r = x - a,
//     u = P(x) r = r - m (m . r),    J = du/dx = P - m (M^T r)^T - (m . r) M,
//     M = dm/dx = (I - m m^T) H / |n|,
// E as above in |u|; gradient J^T (k u or F u/|u|), exact. The Hessian is
// exact but for one term, (m . r) times the body's third derivative (which
// no shape provides): exact on a flat body and wherever the anchor sits at
// the vertex's level (m . r = 0), as the wear's anchors do. A vertex
// sliding over a curved body is then pulled along the surface where it is,
// so the anchor update after a solve finds the force the solve applied
// (the frozen plane's force pointed along the plane where the anchor was
// placed, and each update turned it: the fixed point converged at about one
// half per round on a bending knee). `query` must hold the curvature for the
// gradient and the Hessian, the normal for the energy.
PointResult surface_anchor_spring(double stiffness, const Eigen::Vector3d& x,
                                  const Eigen::Vector3d& anchor, const SurfaceQuery& query,
                                  double bound, element::Want want);

// The query fields surface_anchor_spring's level `want` reads.
inline QueryNeeds surface_anchor_needs(element::Want want) {
  return want == element::Want::energy ? QueryNeeds::normal : QueryNeeds::curvature;
}

// d(anchor_spring's gradient)/d(stiffness) at fixed bound: the tangential
// stretch while the spring sticks (its force is linear in the stiffness),
// zero once it slides (the force is the bound).
Eigen::Vector3d anchor_spring_stiffness_derivative(double stiffness, const Eigen::Vector3d& x,
                                                   const Eigen::Vector3d& anchor,
                                                   const Eigen::Vector3d& normal, double bound);

// The same for surface_anchor_spring: J^T u while it sticks, zero once it slides.
Eigen::Vector3d surface_anchor_spring_stiffness_derivative(double stiffness,
                                                           const Eigen::Vector3d& x,
                                                           const Eigen::Vector3d& anchor,
                                                           const SurfaceQuery& query, double bound);

// Coulomb's law on an anchor spring at an accepted state: when the spring's
// tangential force k_t |P (x - a)| exceeds mu_s * normal_force, the anchor
// slides towards x along the tangent plane until the force is mu_k *
// normal_force (kinetic friction); otherwise it stays (sticking). Returns the
// new anchor (not yet put back on a curved surface) and whether it slid.
struct AnchorUpdate {
  Eigen::Vector3d anchor;
  bool slid = false;
};
AnchorUpdate slide_anchor(double stiffness, const Eigen::Vector3d& x, const Eigen::Vector3d& anchor,
                          const Eigen::Vector3d& normal, double normal_force,
                          double static_coefficient, double kinetic_coefficient);

// The automatic penalty stiffness of a vertex, N/m:
//     k = factor * E_max * A_v / h^2,
// E_max the largest membrane modulus (N/m), A_v the vertex's share of the
// material area (m^2), h the mesh size (m). On a uniform mesh A_v / h^2 is
// O(1), so k is `factor` times the membrane's own vertex stiffness: stiff
// enough that the cloth's weight and tension press it into the offset layer
// by a tiny fraction of it (rho g h^2 / (factor E_max) under its weight),
// soft enough to keep Newton's systems well conditioned.
double penalty_stiffness(double factor, double modulus, double vertex_area, double h);

} // namespace sartor::contact
