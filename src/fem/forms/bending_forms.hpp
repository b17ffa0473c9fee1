#pragma once
// The bending energy: hinges between neighbouring triangles (discrete shell
// or quadratic, element/bending.hpp) or the patch triangles of the model
// that converges to plate theory (element/patch_bending.hpp). The problem
// builds the elements this rank assembles (fem/bending_models/).

#include "element/bending.hpp"
#include "element/patch_bending.hpp"
#include "element/rest_derivative.hpp"
#include "fem/form.hpp"

#include <array>
#include <functional>
#include <vector>

namespace sartor::fem {

struct LocalHinge {
  std::array<PetscInt, 12> dofs; // local-vector offsets, vertex by vertex
  element::HingeRest rest;
  double stiffness; // N m
  bool project;     // PSD-project its Hessian
  // Its two mesh triangles, and which of their corners hinge_rest took
  // (element/bending.hpp), for the rest derivative.
  std::array<int, 2> triangles;
  std::array<std::array<int, 3>, 2> corners;
};

class HingeBendingForm final : public Form {
public:
  // `material_uv`: the mesh's (TriangleMesh::material_uv), for the rest derivative.
  HingeBendingForm(element::BendingModel model, std::vector<LocalHinge> hinges,
                   const std::vector<std::array<Eigen::Vector2d, 3>>& material_uv)
      : model_(model), hinges_(std::move(hinges)), uv_(material_uv) {}
  const char* name() const override { return "hinge bending"; }
  EnergyPart part() const override { return EnergyPart::bending; }
  void add_energy(const FormPoint& at, double* sum) const override;
  void add_gradient(const FormPoint& at, PetscScalar* f) const override;
  PetscErrorCode register_elements(ElementRegistry& registry) const override;
  PetscErrorCode add_element_hessians(const FormPoint& at, ElementHessians& out) const override;
  bool projects() const override;
  bool has_rest_derivative() const override { return true; }
  void add_rest_derivative(const FormPoint& at, const RestChange& change,
                           PetscScalar* f) const override;

private:
  element::BendingModel model_;
  std::vector<LocalHinge> hinges_;
  const std::vector<std::array<Eigen::Vector2d, 3>>& uv_;
};

// The patch model's triangle: its twelve-node stencil as PatchRest numbers it.
struct LocalPatch {
  int triangle = -1; // in the mesh
  std::array<PetscInt, 36> dofs;
  element::PatchRest rest;
  bool project;      // a PSD Hessian where the solver asks for one
  bool gauss_newton; // that Hessian: Gauss-Newton's, else the exact one projected
};

class PatchBendingForm final : public Form {
public:
  // The change of a patch triangle's rest data when the pattern moves by a
  // rest change (the patch model rebuilds them: fem/bending_models/).
  using RestDataChange =
      std::function<element::PatchRestChange(int triangle, const RestChange& change)>;
  PatchBendingForm(std::vector<LocalPatch> patches, RestDataChange rest_data_change)
      : patches_(std::move(patches)), rest_data_change_(std::move(rest_data_change)) {}
  const char* name() const override { return "patch bending"; }
  EnergyPart part() const override { return EnergyPart::bending; }
  void add_energy(const FormPoint& at, double* sum) const override;
  void add_gradient(const FormPoint& at, PetscScalar* f) const override;
  PetscErrorCode register_elements(ElementRegistry& registry) const override;
  PetscErrorCode add_element_hessians(const FormPoint& at, ElementHessians& out) const override;
  bool projects() const override;
  bool has_rest_derivative() const override { return true; }
  void add_rest_derivative(const FormPoint& at, const RestChange& change,
                           PetscScalar* f) const override;

private:
  std::vector<LocalPatch> patches_;
  RestDataChange rest_data_change_;
};

} // namespace sartor::fem
