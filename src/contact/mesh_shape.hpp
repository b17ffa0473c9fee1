#pragma once
// A rigid body given as a closed triangle mesh (an OBJ file, the built-in
// mannequin, or vertices and faces in memory), queried through CGAL's AABB
// tree. Replicated on every rank: it is serial data.
//
// The query finds the nearest triangle and, on it, the nearest feature
// (the triangle's interior, one of its edges, or a vertex). The sign comes
// from that feature's angle-weighted pseudo-normal (Baerentzen & Aanaes),
// which is correct at edges and vertices too; the normal is the gradient of
// the signed distance and the Hessian its curvature part:
//   face:   normal = face normal,     H = 0
//   edge:   normal = s (p - c)/|p - c|, H = (I - e e^T - n n^T) / d
//   vertex: normal = s (p - c)/|p - c|, H = (I - n n^T) / d
// with d the signed distance, e the edge's direction and s the sign. At
// distances below 1e-12 of the mesh size the gradient is undefined at edges
// and vertices; there the pseudo-normal is returned with H = 0.
//
// That distance has creases: over a concave edge two triangles are equally
// near and its gradient jumps, so a penalty on it has a kink there, which
// stalls Newton when a contact point settles on it. With `smoothing` eps > 0
// the query returns the soft minimum of the distances g_i to the triangles
// within g + 12 eps of p (g the nearest),
//   g_s = g - eps ln sum_i exp(-(g_i - g) / eps),
// signed as above: smooth across the creases, at most eps ln(n) below the
// exact distance (n the triangles counted), its gradient a mean of unit
// vectors (so |normal| <= 1: slope_bound stays 1), its Hessian
//   sum_i w_i H_i - (sum_i w_i u_i u_i^T - n n^T) / eps   (w_i the weights).
// The closest point is then p - d n, on the smoothed surface.

#include "contact/shape.hpp"

#include <array>
#include <memory>
#include <string>
#include <vector>

namespace sartor::contact {

// Checks the mesh as a body (closed, 2-manifold, outward; see
// contact/body_obj.hpp) and throws InputError, starting with `name`, when it is
// not one. `name` also starts describe().
std::unique_ptr<Shape> make_mesh_shape(const std::vector<Eigen::Vector3d>& vertices,
                                       const std::vector<std::array<int, 3>>& faces,
                                       const std::string& name, double smoothing = 0.0);

// Reads and checks a body OBJ file (errors at FILE:LINE); `smoothing` (m)
// as above.
std::unique_ptr<Shape> load_mesh_shape(const std::string& path, double smoothing = 0.0);

// The built-in mannequin (contact/mannequin.hpp), built on the first call.
std::unique_ptr<Shape> make_mannequin_shape();

} // namespace sartor::contact
