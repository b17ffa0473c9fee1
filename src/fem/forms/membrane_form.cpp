#include "fem/forms/membrane_form.hpp"

namespace sartor::fem {

void MembraneForm::add_energy(const TriangleView& t, const FormPoint&, double* sum) const {
  *sum += element::membrane(t.material.membrane_model, t.material.membrane, t.rest,
                            nonelastic_[std::size_t(t.index)], t.x, element::Want::energy)
              .energy;
}

element::Vector9 MembraneForm::gradient(const TriangleView& t, const FormPoint&) const {
  const element::NonelasticStrain strain =
      response_ ? response_->respond(t.index, t.material, t.rest, t.x, false).strain
                : nonelastic_[std::size_t(t.index)];
  return element::membrane(t.material.membrane_model, t.material.membrane, t.rest, strain, t.x,
                           element::Want::gradient)
      .gradient;
}

void MembraneForm::add_hessian(const TriangleView& t, const FormPoint& at, Matrix9& block) const {
  NonelasticResponse::Answer response;
  response.strain = nonelastic_[std::size_t(t.index)];
  if (response_) response = response_->respond(t.index, t.material, t.rest, t.x, true);
  auto result = element::membrane(t.material.membrane_model, t.material.membrane, t.rest,
                                  response.strain, t.x, element::Want::hessian);
  if (t.material.project_membrane && !at.exact_hessian) element::project_to_psd<9>(result.hessian);
  if (response_) {
    // The force also moves with the unloaded lengths: dF/dn dn/dx.
    result.hessian +=
        element::membrane_creep_sensitivity(t.material.membrane_model, t.material.membrane, t.rest,
                                            response.strain, t.x)
            .force_per_nonelastic *
        response.per_position;
  }
  block += result.hessian;
}

element::Vector9
MembraneForm::rest_derivative(const TriangleView& t, const FormPoint&,
                              const std::array<Eigen::Vector2d, 3>& delta_uv) const {
  return element::membrane_rest_derivative(t.material.membrane_model, t.material.membrane, t.uv,
                                           nonelastic_[std::size_t(t.index)], t.x, delta_uv);
}

} // namespace sartor::fem
