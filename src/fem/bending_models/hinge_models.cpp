// The hinge models of the thesis and of Sensitive Couture: the discrete
// shell and the quadratic (IBM) model act across each interior edge
// (element/bending.hpp), one HingeBendingForm each. Only the discrete shell
// carries a rest angle per edge (the creases of docs/pleats.md).

#include "common/error.hpp"
#include "fem/bending_models.hpp"
#include "fem/forms/bending_forms.hpp"

#include <algorithm>
#include <cmath>
#include <map>

namespace sartor::fem {

namespace {

// The mesh's creases by edge (lower vertex, higher vertex). Throws
// InputError for a crease that is not an interior edge, or one given twice.
std::map<std::pair<int, int>, CreaseEdge> creases_by_edge(const TriangleMesh& mesh) {
  std::map<std::pair<int, int>, double> angles;
  for (const Hinge& hinge : interior_edges(mesh))
    angles[std::minmax(hinge.vertices[0], hinge.vertices[1])] = 0.0;
  std::map<std::pair<int, int>, CreaseEdge> creases;
  for (const CreaseEdge& crease : mesh.creases) {
    const auto edge = std::minmax(crease.a, crease.b);
    if (!angles.count(edge))
      throw InputError("cloth: crease " + std::to_string(crease.a) + "-" +
                       std::to_string(crease.b) + " is not an interior edge of the mesh");
    if (!(crease.stiffness_factor > 0.0) || !std::isfinite(crease.stiffness_factor))
      throw InputError("cloth: crease " + std::to_string(crease.a) + "-" +
                       std::to_string(crease.b) + " has a stiffness factor that is not positive");
    if (!creases.emplace(edge, crease).second)
      throw InputError("cloth: crease " + std::to_string(crease.a) + "-" +
                       std::to_string(crease.b) + " is given twice");
  }
  return creases;
}

// The hinges of the owned triangle with the lower index.
std::unique_ptr<Form> hinge_form(const BendingSetUp& setup, element::BendingModel model) {
  const TriangleMesh& mesh = setup.mesh;
  const std::map<std::pair<int, int>, CreaseEdge> creases = creases_by_edge(mesh);
  std::vector<LocalHinge> hinges;
  for (const Hinge& hinge : interior_edges(mesh)) {
    const auto first = std::size_t(std::min(hinge.triangles[0], hinge.triangles[1]));
    if (!setup.triangle_owned[first]) continue;
    const ClothMaterial& one = setup.material(std::size_t(hinge.triangles[0]));
    const ClothMaterial& other = setup.material(std::size_t(hinge.triangles[1]));
    LocalHinge local;
    local.stiffness = 0.5 * (one.bending_stiffness + other.bending_stiffness);
    local.project = one.project_bending || other.project_bending;
    local.dofs = setup.dofs<12>(hinge.vertices);
    local.triangles = hinge.triangles;
    std::array<std::array<Eigen::Vector2d, 3>, 2> uv;
    for (std::size_t side = 0; side < 2; ++side) {
      const auto& corners = mesh.material_uv[std::size_t(hinge.triangles[side])];
      for (std::size_t k = 0; k < 3; ++k)
        uv[side][k] = corners[std::size_t(hinge.corners[side][k])];
      for (std::size_t k = 0; k < 3; ++k)
        local.corners[side][k] = int(hinge.corners[side][k]);
    }
    const auto crease = creases.find(std::minmax(hinge.vertices[0], hinge.vertices[1]));
    const bool creased = crease != creases.end();
    local.rest = element::hinge_rest(uv[0], uv[1], creased ? crease->second.rest_angle : 0.0);
    if (creased) local.stiffness *= crease->second.stiffness_factor;
    hinges.push_back(local);
  }
  return std::make_unique<HingeBendingForm>(model, std::move(hinges), mesh.material_uv);
}

} // namespace

BendingModelEntry discrete_shell_model() {
  return {"discrete_shell", "hinges, energy in the dihedral angle", true, hinge_form};
}

BendingModelEntry quadratic_model() {
  return {"quadratic", "hinges, the isometric (IBM) quadratic energy", false, hinge_form};
}

} // namespace sartor::fem
