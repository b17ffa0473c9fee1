// The bending term of ClothProblem: the form of the material's bending
// model, from the registry of bending models (fem/bending_models.hpp).

#include "common/error.hpp"
#include "fem/bending_models.hpp"
#include "fem/cloth_problem.hpp"

#include <algorithm>

namespace sartor {

void ClothProblem::set_up_bending(const std::vector<bool>& triangle_owned,
                                  const std::vector<bool>& is_pinned) {
  const bool any_bending =
      std::any_of(materials_.begin(), materials_.end(),
                  [](const ClothMaterial& material) { return material.has_bending(); });
  if (!any_bending) return;
  const element::BendingModel model = materials_.front().bending_model;
  const fem::BendingModelEntry& entry = fem::bending_model_entry(model);
  // Only the discrete shell has a rest angle per hinge (docs/pleats.md).
  if (!mesh_.creases.empty() && !entry.carries_crease_angles) {
    throw InputError("the mesh has " + std::to_string(mesh_.creases.size()) +
                     " crease edges with rest angles, which only --bending-model "
                     "discrete_shell honours");
  }
  for (const ClothMaterial& material : materials_) {
    if (!material.rest_curvature.empty() &&
        material.rest_curvature.size() != mesh_.triangle_count()) {
      throw InputError("cloth: " + std::to_string(material.rest_curvature.size()) +
                       " rest curvatures for " + std::to_string(mesh_.triangle_count()) +
                       " triangles");
    }
  }
  const fem::BendingSetUp setup{
      mesh_, triangle_owned, is_pinned, vertex_dof_,
      [this](std::size_t triangle) -> const ClothMaterial& { return triangle_material(triangle); }};
  forms_.push_back(entry.form(setup, model));
}

} // namespace sartor
