#pragma once
// The built-in mannequin for contact: its smooth implicit surface
// (mesh/mannequin.hpp) instead of the triangles polygonised from it.
//
// The distance to a triangle mesh has a kink wherever the surface is
// concave: on the outside of a concave edge the nearest face switches from
// one side to the other across the bisecting plane, and the penalty's
// force jumps with it. A cloth vertex pressed into a crease (groin, armpit,
// between the shoulder blades) comes to rest on that plane, and Newton stalls
// there. The implicit function is C1 everywhere the cloth goes, so the
// penalty's force is continuous and its Jacobian exact (it jumps only where a
// fillet begins).
//
// The query returns the function's value as the distance (near the surface,
// the distance to the piece of the body there: exactly for the capsules, to
// first order for the ellipsoids; less in the fillets between pieces), its
// gradient as the normal (unit on the surface of a piece, shorter in the
// fillets) and its Hessian; the closest point is one Newton step from p onto
// the zero level set. Where the cloth rests (within millimetres of the
// surface) these agree with the exact distance to first order; the penalty
// is exact for the function it is given. Away from the surface the
// function is a rough distance only: its gradient reaches 2.8 within 3 cm
// of the hands and is bounded by slope_bound() everywhere outside the body.

#include "contact/shape.hpp"

#include <memory>

namespace sartor::contact {

std::unique_ptr<Shape> make_smooth_mannequin_shape();

} // namespace sartor::contact
