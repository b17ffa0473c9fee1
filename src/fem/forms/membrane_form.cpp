#include "fem/forms/membrane_form.hpp"

namespace sartor::fem {

double membrane_energy(const TriangleView& t, const element::NonelasticStrain& strain) {
  return element::membrane(t.material.membrane_model, t.material.membrane, t.rest, strain, t.x,
                           element::Want::energy)
      .energy;
}

element::Vector9 membrane_gradient(const TriangleView& t, const element::NonelasticStrain& strain) {
  return element::membrane(t.material.membrane_model, t.material.membrane, t.rest, strain, t.x,
                           element::Want::gradient)
      .gradient;
}

Matrix9 membrane_hessian(const TriangleView& t, const FormPoint& at,
                         const element::NonelasticStrain& strain) {
  auto result = element::membrane(t.material.membrane_model, t.material.membrane, t.rest, strain,
                                  t.x, element::Want::hessian);
  if (t.material.project_membrane && !at.exact_hessian) element::project_to_psd<9>(result.hessian);
  return result.hessian;
}

void MembraneForm::add_energy(const TriangleView& t, const FormPoint&, double* sum) const {
  *sum += membrane_energy(t, nonelastic_[std::size_t(t.index)]);
}

element::Vector9 MembraneForm::gradient(const TriangleView& t, const FormPoint&) const {
  return membrane_gradient(t, nonelastic_[std::size_t(t.index)]);
}

void MembraneForm::add_hessian(const TriangleView& t, const FormPoint& at, Matrix9& block) const {
  block += membrane_hessian(t, at, nonelastic_[std::size_t(t.index)]);
}

element::Vector9
MembraneForm::rest_derivative(const TriangleView& t, const FormPoint&,
                              const std::array<Eigen::Vector2d, 3>& delta_uv) const {
  return element::membrane_rest_derivative(t.material.membrane_model, t.material.membrane, t.uv,
                                           nonelastic_[std::size_t(t.index)], t.x, delta_uv);
}

} // namespace sartor::fem
