#pragma once
// The registry of bending models (element::BendingModel).
//
// A bending model is an energy form (fem/form.hpp) that the problem builds
// from the mesh, the materials and the rank's dof layout (BendingSetUp):
// the hinges of the discrete shell and the quadratic (IBM) model, or the
// patch triangles that converge to plate theory
// (docs/finite-elements.md#bending).
//
// A new model is one file in bending_models/ that defines a function
// returning its BendingModelEntry (its kernel and form beside it, or in
// element/ and forms/), and one line in register_bending_models
// (bending_models.cpp); `--bending-model NAME` then selects it.

#include "element/bending.hpp"
#include "fem/cloth_model.hpp"
#include "fem/form.hpp"
#include "mesh/triangle_mesh.hpp"

#include <petscsys.h>

#include <array>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace sartor::fem {

// What a bending model's form is built from.
struct BendingSetUp {
  const TriangleMesh& mesh;
  const std::vector<bool>& triangle_owned; // the triangles this rank assembles
  const std::vector<bool>& is_pinned;      // per vertex
  const std::vector<PetscInt>& vertex_dof; // local-vector offset of each vertex, -1 if absent
  std::function<const ClothMaterial&(std::size_t triangle)> material; // of a triangle

  // The local-vector offsets of an element's vertices, vertex by vertex.
  template <std::size_t N>
  std::array<PetscInt, N> dofs(const std::array<int, N / 3>& vertices) const {
    std::array<PetscInt, N> result;
    for (std::size_t k = 0; k < N / 3; ++k) {
      const PetscInt offset = vertex_dof[std::size_t(vertices[k])];
      if (offset < 0) throw std::logic_error("a vertex of an owned bending element is not local");
      for (std::size_t d = 0; d < 3; ++d)
        result[3 * k + d] = offset + PetscInt(d);
    }
    return result;
  }
};

struct BendingModelEntry {
  std::string name;    // as --bending-model and case files name it
  std::string summary; // a few words for --help
  // Whether the model honours the mesh's creases (rest angles per edge,
  // docs/pleats.md); a creased mesh takes such a model unless one is given.
  bool carries_crease_angles = false;
  // The form of `model` (this entry's index) on the set-up's mesh.
  std::unique_ptr<Form> (*form)(const BendingSetUp& setup, element::BendingModel model) = nullptr;
};

// The entry of a registered model.
const BendingModelEntry& bending_model_entry(element::BendingModel model);
// The model of that name; throws InputError naming `context` and the
// registered names.
element::BendingModel bending_model_named(const std::string& name, const std::string& context);
const std::string& bending_model_name(element::BendingModel model);
// Every registered name, in registration order.
std::vector<std::string> bending_model_names();

// The built-in models (bending_models/).
BendingModelEntry discrete_shell_model();
BendingModelEntry quadratic_model();
BendingModelEntry patch_model();

} // namespace sartor::fem
