#pragma once
// The membrane energy of every triangle (element/membrane.hpp) at the
// triangle's non-elastic strains held from the last step (the creep state).
// While a creep step is coupled monolithically, the creep coupling form
// (fem/forms/creep_coupling_form.hpp) stands in for this one.

#include "fem/cloth_model.hpp"
#include "fem/form.hpp"

#include <vector>

namespace sartor::fem {

class MembraneForm final : public TriangleForm {
public:
  // Both are the problem's, read at every evaluation.
  MembraneForm(const std::vector<element::NonelasticStrain>& nonelastic,
               const NonelasticResponse* const& response)
      : nonelastic_(nonelastic), response_(response) {}
  const char* name() const override { return "membrane"; }
  EnergyPart part() const override { return EnergyPart::membrane; }
  bool active() const override { return response_ == nullptr; }
  void add_energy(const TriangleView& t, const FormPoint& at, double* sum) const override;
  element::Vector9 gradient(const TriangleView& t, const FormPoint& at) const override;
  void add_hessian(const TriangleView& t, const FormPoint& at, Matrix9& block) const override;
  bool projects(const ClothMaterial& material) const override { return material.project_membrane; }
  // At the held non-elastic strains (the creep state of the step).
  bool has_rest_derivative() const override { return true; }
  element::Vector9 rest_derivative(const TriangleView& t, const FormPoint& at,
                                   const std::array<Eigen::Vector2d, 3>& delta_uv) const override;

private:
  const std::vector<element::NonelasticStrain>& nonelastic_;
  const NonelasticResponse* const& response_;
};

// The membrane kernel of triangle t at non-elastic strains `strain`, as the
// membrane form (at the held strains) and the creep coupling form (at the
// responding ones) evaluate it; the Hessian projected as the material and
// `at` ask.
double membrane_energy(const TriangleView& t, const element::NonelasticStrain& strain);
element::Vector9 membrane_gradient(const TriangleView& t, const element::NonelasticStrain& strain);
Matrix9 membrane_hessian(const TriangleView& t, const FormPoint& at,
                         const element::NonelasticStrain& strain);

} // namespace sartor::fem
