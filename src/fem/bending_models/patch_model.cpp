// The patch model (element/patch_bending.hpp): a rotation-free Kirchhoff
// triangle whose curvature comes from its own and its neighbours' patches,
// and which converges to plate theory (docs/finite-elements.md#bending).

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
struct Patch {
  std::array<int, 6> vertices;
  std::array<Eigen::Matrix<double, 1, 6>, 3> slopes;
};

using TriangleUV = std::array<Eigen::Vector2d, 3>;
// The material coordinates of a triangle's corners: the mesh's, or a moved
// pattern's.
using UVOf = std::function<TriangleUV(std::size_t triangle)>;

// What the patches are built from besides the material coordinates; kept by
// the form's rest derivative, which rebuilds them on moved patterns.
struct PatchGeometry {
  const TriangleMesh& mesh;
  std::vector<Across> across;
  // A triangle of fixed vertices (a clamp) has a prescribed curvature: it
  // stores nothing the unknowns could change, and it imposes its own
  // plane's slope on the edges it shares.
  std::vector<bool> fixed;
  std::vector<element::BendingRigidity> rigidity; // per triangle
};

Patch free_patch(const PatchGeometry& g, const UVOf& uv_of, std::size_t t) {
  const auto& corners = g.mesh.triangles[t];
  const TriangleUV uv = uv_of(t);
  Patch patch;
  patch.vertices = {corners[0], corners[1], corners[2], corners[0], corners[1], corners[2]};
  std::array<Eigen::Vector2d, 3> nodes;
  std::array<bool, 3> has_node{};
  for (std::size_t k = 0; k < 3; ++k) {
    const Across& neighbour = g.across[3 * t + k];
    has_node[k] = neighbour.triangle >= 0;
    if (!has_node[k]) continue;
    patch.vertices[3 + k] = neighbour.vertex;
    const std::size_t i = (k + 1) % 3, j = (k + 2) % 3;
    const auto& other_corners = g.mesh.triangles[std::size_t(neighbour.triangle)];
    const TriangleUV other_uv = uv_of(std::size_t(neighbour.triangle));
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

Patch patch_of(const PatchGeometry& g, const UVOf& uv_of, std::size_t t) {
  if (!g.fixed[t]) return free_patch(g, uv_of, t);
  const auto& corners = g.mesh.triangles[t];
  Patch patch;
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
struct Stencil {
  std::array<int, 12> vertices;
  std::array<Eigen::Matrix<double, 1, 12>, 3> slopes;
};

Stencil stencil_of(const PatchGeometry& g, const std::function<const Patch&(std::size_t)>& patch,
                   std::size_t t) {
  Stencil stencil;
  stencil.vertices.fill(g.mesh.triangles[t][0]);
  const Patch& own = patch(t);
  std::copy(own.vertices.begin(), own.vertices.end(), stencil.vertices.begin());
  for (std::size_t k = 0; k < 3; ++k) {
    auto& slope = stencil.slopes[k];
    slope.setZero();
    slope.head<6>() = own.slopes[k];
    const Across& neighbour = g.across[3 * t + k];
    if (neighbour.triangle < 0) continue;
    const double share = g.fixed[std::size_t(neighbour.triangle)] ? 1.0 : 0.5;
    slope *= 1.0 - share;
    const Patch& other = patch(std::size_t(neighbour.triangle));
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

// Triangle t's rest data on the pattern moved by `step` times `change`
// (curves, rest curvature and rigidity as the form's).
element::PatchRest moved_rest(const PatchGeometry& g, std::size_t t, const RestChange& change,
                              double step) {
  const UVOf uv_of = [&](std::size_t triangle) {
    TriangleUV uv = g.mesh.material_uv[triangle];
    for (std::size_t c = 0; c < 3; ++c)
      uv[c] += step * change[triangle][c];
    return uv;
  };
  std::vector<std::pair<std::size_t, Patch>> patches{{t, patch_of(g, uv_of, t)}};
  for (std::size_t k = 0; k < 3; ++k) {
    const int neighbour = g.across[3 * t + k].triangle;
    if (neighbour >= 0) patches.emplace_back(neighbour, patch_of(g, uv_of, std::size_t(neighbour)));
  }
  const auto patch = [&](std::size_t triangle) -> const Patch& {
    return std::find_if(patches.begin(), patches.end(),
                        [&](const auto& entry) { return entry.first == triangle; })
        ->second;
  };
  return element::patch_rest(uv_of(t), stencil_of(g, patch, t).slopes, g.rigidity[t]);
}

// Relative to the triangle's longest edge, the step of the differences of
// its rest data (fourth order after extrapolation: truncation ~1e-16, round-off
// ~1e-12 relative).
constexpr double relative_step = 1e-4;

// The change of triangle t's rest data (area and curvature weights) when the
// pattern moves by `change`: the patches rebuilt on the pattern moved by
// +-h and +-h/2 times it, differenced and extrapolated, (4 D(h/2) - D(h)) / 3.
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
  double largest = 0.0;
  for (const std::size_t triangle : involved)
    for (const Eigen::Vector2d& d : change[triangle])
      largest = std::max(largest, d.norm());
  element::PatchRestChange result;
  if (largest == 0.0) return result;
  const TriangleUV& uv = g.mesh.material_uv[t];
  const double edge =
      std::max({(uv[1] - uv[0]).norm(), (uv[2] - uv[1]).norm(), (uv[0] - uv[2]).norm()});
  const double h = relative_step * edge / largest;
  for (const auto& [step, weight] : {std::pair{h, -1.0 / 3.0}, std::pair{0.5 * h, 4.0 / 3.0}}) {
    const element::PatchRest plus = moved_rest(g, t, change, step);
    const element::PatchRest minus = moved_rest(g, t, change, -step);
    const double scale = weight / (2.0 * step);
    result.area += scale * (plus.area - minus.area);
    result.weights += scale * (plus.weights - minus.weights);
  }
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
  const UVOf mesh_uv = [&](std::size_t t) { return mesh.material_uv[t]; };
  std::vector<Patch> patches;
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t)
    patches.push_back(patch_of(*geometry, mesh_uv, t));
  const auto patch = [&](std::size_t t) -> const Patch& { return patches[t]; };
  std::vector<LocalPatch> local_patches;
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    if (!setup.triangle_owned[t] || geometry->fixed[t]) continue;
    const ClothMaterial& material = setup.material(t);
    if (!material.has_bending()) continue;
    const Stencil stencil = stencil_of(*geometry, patch, t);
    LocalPatch local;
    local.triangle = int(t);
    local.dofs = setup.dofs<36>(stencil.vertices);
    local.project = material.project_bending;
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
