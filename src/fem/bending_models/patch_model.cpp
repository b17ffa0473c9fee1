// The patch model (element/patch_bending.hpp): a rotation-free Kirchhoff
// triangle whose curvature comes from its own and its neighbours' patches,
// and which converges to plate theory (docs/finite-elements.md#bending).

#include "common/autodiff.hpp"
#include "common/error.hpp"
#include "fem/bending_models.hpp"
#include "fem/forms/bending_forms.hpp"

#include <algorithm>
#include <functional>
#include <memory>
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
// Of either scalar: double, or AutoDiff for the rest data's derivative along
// a change of the pattern.
template <typename Scalar>
struct Patch {
  std::array<int, 6> vertices;
  element::EdgeSlopes<Scalar> slopes;
};

template <typename Scalar>
using TriangleUV = element::PatchTriangle<Scalar>;
// The material coordinates of a triangle's corners: the mesh's, or the
// mesh's carrying a change of the pattern.
template <typename Scalar>
using UVOf = std::function<TriangleUV<Scalar>(std::size_t triangle)>;

// What the patches are built from besides the material coordinates; kept by
// the form's rest derivative, which builds them again carrying a change of
// the pattern.
struct PatchGeometry {
  const TriangleMesh& mesh;
  std::vector<Across> across;
  // A triangle of fixed vertices (a clamp) has a prescribed curvature: it
  // stores nothing the unknowns could change, and it imposes its own
  // plane's slope on the edges it shares.
  std::vector<bool> fixed;
  std::vector<element::BendingRigidity> rigidity; // per triangle
};

template <typename Scalar>
Patch<Scalar> free_patch(const PatchGeometry& g, const UVOf<Scalar>& uv_of, std::size_t t) {
  const auto& corners = g.mesh.triangles[t];
  const TriangleUV<Scalar> uv = uv_of(t);
  Patch<Scalar> patch;
  patch.vertices = {corners[0], corners[1], corners[2], corners[0], corners[1], corners[2]};
  TriangleUV<Scalar> nodes;
  std::array<bool, 3> has_node{};
  for (std::size_t k = 0; k < 3; ++k) {
    const Across& neighbour = g.across[3 * t + k];
    has_node[k] = neighbour.triangle >= 0;
    if (!has_node[k]) continue;
    patch.vertices[3 + k] = neighbour.vertex;
    const std::size_t i = (k + 1) % 3, j = (k + 2) % 3;
    const auto& other_corners = g.mesh.triangles[std::size_t(neighbour.triangle)];
    const TriangleUV<Scalar> other_uv = uv_of(std::size_t(neighbour.triangle));
    const auto other = [&](int vertex) {
      return other_uv[std::size_t(std::find(other_corners.begin(), other_corners.end(), vertex) -
                                  other_corners.begin())];
    };
    nodes[k] = element::node_across(uv[i], uv[j], uv[k], other(corners[i]), other(corners[j]),
                                    other(neighbour.vertex));
  }
  patch.slopes = element::midedge_slopes(uv, nodes, has_node, g.rigidity[t]);
  return patch;
}

template <typename Scalar>
Patch<Scalar> patch_of(const PatchGeometry& g, const UVOf<Scalar>& uv_of, std::size_t t) {
  if (!g.fixed[t]) return free_patch(g, uv_of, t);
  const auto& corners = g.mesh.triangles[t];
  Patch<Scalar> patch;
  patch.vertices = {corners[0], corners[1], corners[2], corners[0], corners[1], corners[2]};
  patch.slopes = element::plane_slopes(uv_of(t));
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

// A patch triangle's twelve-node stencil (its own patch's nodes, then each
// neighbour's further nodes; unused slots repeat corner 0 with weight zero)
// and its edges' outward normal slopes over it: the mean of both patches'
// (the neighbour's outward normal is this triangle's inward one), or a
// clamp's own.
template <typename Scalar>
struct Stencil {
  std::array<int, 12> vertices;
  std::array<Eigen::Matrix<Scalar, 1, 12>, 3> slopes;
};

template <typename Scalar>
using PatchOf = std::function<const Patch<Scalar>&(std::size_t)>;

template <typename Scalar>
Stencil<Scalar> stencil_of(const PatchGeometry& g, const PatchOf<Scalar>& patch, std::size_t t) {
  Stencil<Scalar> stencil;
  stencil.vertices.fill(g.mesh.triangles[t][0]);
  const Patch<Scalar>& own = patch(t);
  std::copy(own.vertices.begin(), own.vertices.end(), stencil.vertices.begin());
  for (std::size_t k = 0; k < 3; ++k) {
    auto& slope = stencil.slopes[k];
    slope.setZero();
    slope.template head<6>() = own.slopes[k];
    const Across& neighbour = g.across[3 * t + k];
    if (neighbour.triangle < 0) continue;
    const double share = g.fixed[std::size_t(neighbour.triangle)] ? 1.0 : 0.5;
    slope *= 1.0 - share;
    const Patch<Scalar>& other = patch(std::size_t(neighbour.triangle));
    const auto& other_corners = g.mesh.triangles[std::size_t(neighbour.triangle)];
    const auto edge =
        std::size_t(std::find(other_corners.begin(), other_corners.end(), neighbour.vertex) -
                    other_corners.begin());
    std::size_t next = 6 + 2 * k;
    for (std::size_t n = 0; n < 6; ++n) {
      const std::size_t s = slot_of(stencil.vertices, next, other.vertices[n]);
      if (next > 8 + 2 * k) throw std::logic_error("a bending patch with too many nodes");
      slope(long(s)) -= share * other.slopes[edge](long(n));
    }
  }
  return stencil;
}

// The change of triangle t's rest data (area and curvature weights) when the
// pattern moves by `change`: the patches of t and its neighbours built on
// material coordinates carrying the change (AutoDiff), their exact
// derivative.
element::PatchRestChange rest_change(const PatchGeometry& g, std::size_t t,
                                     const RestChange& change) {
  // The patches of t and its neighbours reach the triangles across the
  // neighbours' edges: two rings.
  std::vector<std::size_t> involved{t};
  for (std::size_t ring = 0, first = 0; ring < 2; ++ring) {
    const std::size_t last = involved.size();
    for (std::size_t i = first; i < last; ++i)
      for (std::size_t k = 0; k < 3; ++k)
        if (const int other = g.across[3 * involved[i] + k].triangle; other >= 0)
          involved.push_back(std::size_t(other));
    first = last;
  }
  element::PatchRestChange result;
  const bool unchanged = std::all_of(involved.begin(), involved.end(), [&](std::size_t triangle) {
    return std::all_of(change[triangle].begin(), change[triangle].end(),
                       [](const Eigen::Vector2d& d) { return d.isZero(0.0); });
  });
  if (unchanged) return result;
  const UVOf<AutoDiff> uv_of = [&](std::size_t triangle) {
    TriangleUV<AutoDiff> uv;
    for (std::size_t c = 0; c < 3; ++c) {
      const Eigen::Vector2d& at = g.mesh.material_uv[triangle][c];
      const Eigen::Vector2d& d = change[triangle][c];
      uv[c] = {seeded(at.x(), d.x()), seeded(at.y(), d.y())};
    }
    return uv;
  };
  std::vector<std::pair<std::size_t, Patch<AutoDiff>>> patches{{t, patch_of(g, uv_of, t)}};
  for (std::size_t k = 0; k < 3; ++k) {
    const int neighbour = g.across[3 * t + k].triangle;
    if (neighbour >= 0) patches.emplace_back(neighbour, patch_of(g, uv_of, std::size_t(neighbour)));
  }
  const PatchOf<AutoDiff> patch = [&](std::size_t triangle) -> const Patch<AutoDiff>& {
    return std::find_if(patches.begin(), patches.end(),
                        [&](const auto& entry) { return entry.first == triangle; })
        ->second;
  };
  const element::PatchWeights<AutoDiff> moving =
      element::patch_weights(uv_of(t), stencil_of(g, patch, t).slopes);
  result.area = derivative_of(moving.area);
  result.weights = derivatives(moving.weights);
  return result;
}

// The patch triangles this rank assembles, each with its twelve-node
// stencil: its own patch and its neighbours'.
std::unique_ptr<Form> patch_form(const BendingSetUp& setup, element::BendingModel) {
  const TriangleMesh& mesh = setup.mesh;
  auto geometry = std::make_shared<PatchGeometry>(PatchGeometry{mesh, neighbours(mesh), {}, {}});
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    const auto& corners = mesh.triangles[t];
    geometry->fixed.push_back(std::all_of(corners.begin(), corners.end(),
                                          [&](int v) { return setup.is_pinned[std::size_t(v)]; }));
    geometry->rigidity.push_back(geometry->fixed.back() ? element::BendingRigidity{}
                                                        : setup.material(t).patch_rigidity());
  }
  const UVOf<double> mesh_uv = [&](std::size_t t) { return mesh.material_uv[t]; };
  std::vector<Patch<double>> patches;
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t)
    patches.push_back(patch_of(*geometry, mesh_uv, t));
  const PatchOf<double> patch = [&](std::size_t t) -> const Patch<double>& { return patches[t]; };
  std::vector<LocalPatch> local_patches;
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    if (!setup.triangle_owned[t] || geometry->fixed[t]) continue;
    const ClothMaterial& material = setup.material(t);
    if (!material.has_bending()) continue;
    const Stencil<double> stencil = stencil_of(*geometry, patch, t);
    LocalPatch local;
    local.triangle = int(t);
    local.dofs = setup.dofs<36>(stencil.vertices);
    local.project = material.project_bending;
    local.gauss_newton = material.patch_gauss_newton;
    const Eigen::Vector3d rest_curvature =
        material.rest_curvature.empty() ? Eigen::Vector3d::Zero() : material.rest_curvature[t];
    local.rest = element::patch_rest(mesh.material_uv[t], stencil.slopes, geometry->rigidity[t],
                                     rest_curvature);
    local.rest.curves = material.bending_curves;
    local_patches.push_back(local);
  }
  return std::make_unique<PatchBendingForm>(std::move(local_patches),
                                            [geometry](int t, const RestChange& change) {
                                              return rest_change(*geometry, std::size_t(t), change);
                                            });
}

} // namespace

BendingModelEntry patch_model() {
  return {"patch", "patch triangles, converges to plate theory", false, patch_form};
}

} // namespace sartor::fem
