#include "fem/forms/creep_coupling_form.hpp"

#include "fem/forms/membrane_form.hpp"

namespace sartor::fem {

void CreepCouplingForm::add_energy(const TriangleView& t, const FormPoint&, double* sum) const {
  *sum += membrane_energy(t, nonelastic_[std::size_t(t.index)]);
}

element::Vector9 CreepCouplingForm::gradient(const TriangleView& t, const FormPoint&) const {
  return membrane_gradient(t, response_->respond(t.index, t.material, t.rest, t.x, false).strain);
}

void CreepCouplingForm::add_hessian(const TriangleView& t, const FormPoint& at,
                                    Matrix9& block) const {
  const NonelasticResponse::Answer response =
      response_->respond(t.index, t.material, t.rest, t.x, true);
  // The force also moves with the unloaded lengths: dF/dn dn/dx.
  block += membrane_hessian(t, at, response.strain) +
           element::membrane_creep_sensitivity(t.material.membrane_model, t.material.membrane,
                                               t.rest, response.strain, t.x)
                   .force_per_nonelastic *
               response.per_position;
}

element::Vector9
CreepCouplingForm::rest_derivative(const TriangleView& t, const FormPoint&,
                                   const std::array<Eigen::Vector2d, 3>& delta_uv) const {
  const NonelasticResponse::Answer response =
      response_->respond(t.index, t.material, t.rest, t.x, true);
  const ClothMaterial& m = t.material;
  const Eigen::Vector2d strain_change =
      response.per_tension * element::membrane_tension_rest_derivative(m.membrane_model, m.membrane,
                                                                       t.uv, response.strain, t.x,
                                                                       delta_uv);
  return element::membrane_rest_derivative(m.membrane_model, m.membrane, t.uv, response.strain, t.x,
                                           delta_uv) +
         element::membrane_creep_sensitivity(m.membrane_model, m.membrane, t.rest, response.strain,
                                             t.x)
                 .force_per_nonelastic *
             strain_change;
}

} // namespace sartor::fem
