// The bending terms of ClothProblem: hinges (discrete shell, quadratic) or
// patch triangles (element/patch_bending.hpp), set up from the mesh.

#include "common/error.hpp"
#include "fem/cloth_problem.hpp"
#include "fem/forms/bending_forms.hpp"

#include <algorithm>
#include <map>
#include <stdexcept>

namespace sartor {

template <std::size_t N>
std::array<PetscInt, N> ClothProblem::vertex_dofs(const std::array<int, N / 3>& vertices) const {
  std::array<PetscInt, N> dofs;
  for (std::size_t k = 0; k < N / 3; ++k) {
    const PetscInt offset = vertex_dof_[std::size_t(vertices[k])];
    if (offset < 0) throw std::logic_error("a vertex of an owned bending element is not local");
    for (std::size_t d = 0; d < 3; ++d)
      dofs[3 * k + d] = offset + PetscInt(d);
  }
  return dofs;
}

namespace {

// The mesh's creases by edge (lower vertex, higher vertex). Throws
// InputError for a crease that is not an interior edge, or one given twice.
std::map<std::pair<int, int>, double> crease_angles(const TriangleMesh& mesh) {
  std::map<std::pair<int, int>, double> angles;
  for (const Hinge& hinge : interior_edges(mesh))
    angles[std::minmax(hinge.vertices[0], hinge.vertices[1])] = 0.0;
  std::map<std::pair<int, int>, double> creases;
  for (const CreaseEdge& crease : mesh.creases) {
    const auto edge = std::minmax(crease.a, crease.b);
    if (!angles.count(edge))
      throw InputError("cloth: crease " + std::to_string(crease.a) + "-" +
                       std::to_string(crease.b) + " is not an interior edge of the mesh");
    if (!creases.emplace(edge, crease.rest_angle).second)
      throw InputError("cloth: crease " + std::to_string(crease.a) + "-" +
                       std::to_string(crease.b) + " is given twice");
  }
  return creases;
}

} // namespace

void ClothProblem::set_up_bending(const std::vector<bool>& triangle_owned,
                                  const std::vector<bool>& is_pinned) {
  const bool any_bending =
      std::any_of(materials_.begin(), materials_.end(),
                  [](const ClothMaterial& material) { return material.has_bending(); });
  if (!any_bending) return;
  // Only the discrete shell has a rest angle per hinge (docs/pleats.md).
  if (!mesh_.creases.empty() &&
      materials_.front().bending_model != element::BendingModel::discrete_shell) {
    throw InputError("the mesh has " + std::to_string(mesh_.creases.size()) +
                     " crease edges with rest angles, which only --bending-model "
                     "discrete_shell honours");
  }
  const std::map<std::pair<int, int>, double> creases = crease_angles(mesh_);
  if (materials_.front().bending_model == element::BendingModel::patch) {
    set_up_patches(triangle_owned, is_pinned);
    return;
  }
  // Hinges of the owned triangle with the lower index.
  std::vector<fem::LocalHinge> hinges;
  for (const Hinge& hinge : interior_edges(mesh_)) {
    const auto first = std::size_t(std::min(hinge.triangles[0], hinge.triangles[1]));
    if (!triangle_owned[first]) continue;
    const ClothMaterial& one = triangle_material(std::size_t(hinge.triangles[0]));
    const ClothMaterial& other = triangle_material(std::size_t(hinge.triangles[1]));
    fem::LocalHinge local;
    local.stiffness = 0.5 * (one.bending_stiffness + other.bending_stiffness);
    local.project = one.project_bending || other.project_bending;
    local.dofs = vertex_dofs<12>(hinge.vertices);
    local.triangles = hinge.triangles;
    std::array<std::array<Eigen::Vector2d, 3>, 2> uv;
    for (std::size_t side = 0; side < 2; ++side) {
      const auto& corners = mesh_.material_uv[std::size_t(hinge.triangles[side])];
      for (std::size_t k = 0; k < 3; ++k)
        uv[side][k] = corners[std::size_t(hinge.corners[side][k])];
      for (std::size_t k = 0; k < 3; ++k)
        local.corners[side][k] = int(hinge.corners[side][k]);
    }
    const auto crease = creases.find(std::minmax(hinge.vertices[0], hinge.vertices[1]));
    local.rest = element::hinge_rest(uv[0], uv[1], crease == creases.end() ? 0.0 : crease->second);
    hinges.push_back(local);
  }
  forms_.push_back(std::make_unique<fem::HingeBendingForm>(materials_.front().bending_model,
                                                           std::move(hinges), mesh_.material_uv));
}

namespace {

// The triangle across one edge of a triangle, if any.
struct Across {
  int triangle = -1;
  int vertex = -1; // the neighbour's corner off the edge
};

// across[3 t + k]: the neighbour across the edge opposite corner k of t.
std::vector<Across> neighbours(const TriangleMesh& mesh) {
  std::vector<Across> across(3 * mesh.triangle_count());
  const auto corner_of = [&](int triangle, int vertex) {
    const auto& corners = mesh.triangles[std::size_t(triangle)];
    return int(std::find(corners.begin(), corners.end(), vertex) - corners.begin());
  };
  for (const Hinge& hinge : interior_edges(mesh)) {
    for (std::size_t side = 0; side < 2; ++side) {
      const int own = hinge.triangles[side];
      const int off = side == 0 ? hinge.vertices[2] : hinge.vertices[3];
      const int other_off = side == 0 ? hinge.vertices[3] : hinge.vertices[2];
      across[3 * std::size_t(own) + std::size_t(corner_of(own, off))] = {hinge.triangles[1 - side],
                                                                         other_off};
    }
  }
  return across;
}

} // namespace

namespace {

// A triangle's six-node patch: its corners, the vertices across its edges
// (a corner repeated across a boundary edge), and the patch's outward
// normal slopes at the edges' midpoints.
struct Patch {
  std::array<int, 6> vertices;
  std::array<Eigen::Matrix<double, 1, 6>, 3> slopes;
};

Patch patch_of(const TriangleMesh& mesh, const std::vector<Across>& across, std::size_t t,
               const element::BendingRigidity& rigidity) {
  const auto& corners = mesh.triangles[t];
  const auto& uv = mesh.material_uv[t];
  Patch patch;
  patch.vertices = {corners[0], corners[1], corners[2], corners[0], corners[1], corners[2]};
  std::array<Eigen::Vector2d, 3> nodes;
  std::array<bool, 3> has_node{};
  for (std::size_t k = 0; k < 3; ++k) {
    const Across& neighbour = across[3 * t + k];
    has_node[k] = neighbour.triangle >= 0;
    if (!has_node[k]) continue;
    patch.vertices[3 + k] = neighbour.vertex;
    const std::size_t i = (k + 1) % 3, j = (k + 2) % 3;
    const auto& other_corners = mesh.triangles[std::size_t(neighbour.triangle)];
    const auto& other_uv = mesh.material_uv[std::size_t(neighbour.triangle)];
    const auto other = [&](int vertex) {
      return other_uv[std::size_t(std::find(other_corners.begin(), other_corners.end(), vertex) -
                                  other_corners.begin())];
    };
    nodes[k] = element::node_across(uv[i], uv[j], uv[k], other(corners[i]), other(corners[j]),
                                    other(neighbour.vertex));
  }
  patch.slopes = element::midedge_slopes(uv, nodes, has_node, rigidity);
  return patch;
}

// The slot of `vertex` among the first `next` of a stencil, appended there
// if absent (the slots past `next` are not yet assigned).
std::size_t slot_of(std::array<int, 12>& stencil, std::size_t& next, int vertex) {
  for (std::size_t s = 0; s < next; ++s)
    if (stencil[s] == vertex) return s;
  stencil[next] = vertex;
  return next++;
}

} // namespace

void ClothProblem::set_up_patches(const std::vector<bool>& triangle_owned,
                                  const std::vector<bool>& is_pinned) {
  for (const ClothMaterial& material : materials_) {
    if (!material.rest_curvature.empty() &&
        material.rest_curvature.size() != mesh_.triangle_count()) {
      throw InputError("cloth: " + std::to_string(material.rest_curvature.size()) +
                       " rest curvatures for " + std::to_string(mesh_.triangle_count()) +
                       " triangles");
    }
  }
  const std::vector<Across> across = neighbours(mesh_);
  std::vector<Patch> patches(mesh_.triangle_count());
  // A triangle of fixed vertices (a clamp) has a prescribed curvature: it
  // stores nothing the unknowns could change, and it imposes its own
  // plane's slope on the edges it shares.
  std::vector<bool> fixed(mesh_.triangle_count());
  for (std::size_t t = 0; t < mesh_.triangle_count(); ++t) {
    const auto& corners = mesh_.triangles[t];
    fixed[t] = std::all_of(corners.begin(), corners.end(),
                           [&](int v) { return is_pinned[std::size_t(v)]; });
    if (fixed[t]) {
      patches[t].vertices = {corners[0], corners[1], corners[2],
                             corners[0], corners[1], corners[2]};
      patches[t].slopes = element::plane_slopes(mesh_.material_uv[t]);
    } else {
      patches[t] = patch_of(mesh_, across, t, triangle_material(t).patch_rigidity());
    }
  }
  std::vector<fem::LocalPatch> local_patches;
  for (std::size_t t = 0; t < mesh_.triangle_count(); ++t) {
    if (!triangle_owned[t] || fixed[t]) continue;
    const auto& corners = mesh_.triangles[t];
    const ClothMaterial& material = triangle_material(t);
    if (!material.has_bending()) continue;
    // Stencil: the patch's six nodes, then each neighbour's further nodes;
    // unused slots repeat corner 0 (weight zero).
    std::array<int, 12> stencil;
    stencil.fill(corners[0]);
    std::copy(patches[t].vertices.begin(), patches[t].vertices.end(), stencil.begin());
    std::array<Eigen::Matrix<double, 1, 12>, 3> slopes;
    for (std::size_t k = 0; k < 3; ++k) {
      slopes[k].setZero();
      slopes[k].head<6>() = patches[t].slopes[k];
      const Across& neighbour = across[3 * t + k];
      if (neighbour.triangle < 0) continue;
      // The edge's slope is the mean of both patches' (the neighbour's
      // outward normal is this triangle's inward one), or a clamp's own.
      const double share = fixed[std::size_t(neighbour.triangle)] ? 1.0 : 0.5;
      slopes[k] *= 1.0 - share;
      const Patch& other = patches[std::size_t(neighbour.triangle)];
      const auto& other_corners = mesh_.triangles[std::size_t(neighbour.triangle)];
      const auto edge =
          std::size_t(std::find(other_corners.begin(), other_corners.end(), neighbour.vertex) -
                      other_corners.begin());
      std::size_t next = 6 + 2 * k;
      for (std::size_t n = 0; n < 6; ++n) {
        const std::size_t s = slot_of(stencil, next, other.vertices[n]);
        if (next > 8 + 2 * k) throw std::logic_error("a bending patch with too many nodes");
        slopes[k](long(s)) -= share * other.slopes[edge](long(n));
      }
    }
    fem::LocalPatch local;
    local.dofs = vertex_dofs<36>(stencil);
    local.project = material.project_bending;
    const Eigen::Vector3d rest_curvature =
        material.rest_curvature.empty() ? Eigen::Vector3d::Zero() : material.rest_curvature[t];
    local.rest = element::patch_rest(mesh_.material_uv[t], slopes, material.patch_rigidity(),
                                     rest_curvature);
    local.rest.curves = material.bending_curves;
    local_patches.push_back(local);
  }
  forms_.push_back(std::make_unique<fem::PatchBendingForm>(std::move(local_patches)));
}

} // namespace sartor
