// The patch model (element/patch_bending.hpp): a rotation-free Kirchhoff
// triangle whose curvature comes from its own and its neighbours' patches,
// and which converges to plate theory (docs/finite-elements.md#bending).

#include "common/error.hpp"
#include "fem/bending_models.hpp"
#include "fem/forms/bending_forms.hpp"

#include <algorithm>
#include <stdexcept>

namespace sartor::fem {

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

// The patch triangles this rank assembles, each with its twelve-node
// stencil: its own patch and its neighbours' (the edge slopes are the mean
// of both patches').
std::unique_ptr<Form> patch_form(const BendingSetUp& setup, element::BendingModel) {
  const TriangleMesh& mesh = setup.mesh;
  const std::vector<Across> across = neighbours(mesh);
  std::vector<Patch> patches(mesh.triangle_count());
  // A triangle of fixed vertices (a clamp) has a prescribed curvature: it
  // stores nothing the unknowns could change, and it imposes its own
  // plane's slope on the edges it shares.
  std::vector<bool> fixed(mesh.triangle_count());
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    const auto& corners = mesh.triangles[t];
    fixed[t] = std::all_of(corners.begin(), corners.end(),
                           [&](int v) { return setup.is_pinned[std::size_t(v)]; });
    if (fixed[t]) {
      patches[t].vertices = {corners[0], corners[1], corners[2],
                             corners[0], corners[1], corners[2]};
      patches[t].slopes = element::plane_slopes(mesh.material_uv[t]);
    } else {
      patches[t] = patch_of(mesh, across, t, setup.material(t).patch_rigidity());
    }
  }
  std::vector<LocalPatch> local_patches;
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    if (!setup.triangle_owned[t] || fixed[t]) continue;
    const auto& corners = mesh.triangles[t];
    const ClothMaterial& material = setup.material(t);
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
      const auto& other_corners = mesh.triangles[std::size_t(neighbour.triangle)];
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
    LocalPatch local;
    local.dofs = setup.dofs<36>(stencil);
    local.project = material.project_bending;
    const Eigen::Vector3d rest_curvature =
        material.rest_curvature.empty() ? Eigen::Vector3d::Zero() : material.rest_curvature[t];
    local.rest =
        element::patch_rest(mesh.material_uv[t], slopes, material.patch_rigidity(), rest_curvature);
    local.rest.curves = material.bending_curves;
    local_patches.push_back(local);
  }
  return std::make_unique<PatchBendingForm>(std::move(local_patches));
}

} // namespace

BendingModelEntry patch_model() {
  return {"patch", "patch triangles, converges to plate theory", false, patch_form};
}

} // namespace sartor::fem
