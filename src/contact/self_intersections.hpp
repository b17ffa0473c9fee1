#pragma once
// Faces of a body mesh that cross each other (CGAL's exact predicates): a
// surface that intersects itself bounds no solid, so its inside, and the
// signed distance contact needs, are not defined. Kept apart from
// body_obj.cpp because CGAL compiles with its own flags (src/CMakeLists.txt).

#include "contact/body_obj.hpp"

#include <cstddef>
#include <utility>
#include <vector>

namespace sartor {

// The pairs of faces (lower index first, sorted) of a closed, consistently
// oriented 2-manifold triangle mesh that intersect other than along the edge
// or at the vertex they share. Throws std::logic_error for a mesh that is not
// such a manifold (check_body_mesh's other checks come first).
std::vector<std::pair<std::size_t, std::size_t>> self_intersecting_faces(const BodyMesh& mesh);

} // namespace sartor
