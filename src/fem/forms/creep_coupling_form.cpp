#include "fem/forms/creep_coupling_form.hpp"

#include "fem/forms/membrane_form.hpp"

namespace sartor::fem {

void CreepCouplingForm::add_energy(const TriangleView& t, const FormPoint&, double* sum) const {
  *sum += held_membrane_energy(t, nonelastic_[std::size_t(t.index)]);
}

element::Vector9 CreepCouplingForm::gradient(const TriangleView& t, const FormPoint&) const {
  const element::NonelasticStrain strain =
      response_->respond(t.index, t.material, t.rest, t.x, false).strain;
  return element::membrane(t.material.membrane_model, t.material.membrane, t.rest, strain, t.x,
                           element::Want::gradient)
      .gradient;
}

void CreepCouplingForm::add_hessian(const TriangleView& t, const FormPoint& at,
                                    Matrix9& block) const {
  const NonelasticResponse::Answer response =
      response_->respond(t.index, t.material, t.rest, t.x, true);
  auto result = element::membrane(t.material.membrane_model, t.material.membrane, t.rest,
                                  response.strain, t.x, element::Want::hessian);
  if (t.material.project_membrane && !at.exact_hessian) element::project_to_psd<9>(result.hessian);
  // The force also moves with the unloaded lengths: dF/dn dn/dx.
  result.hessian +=
      element::membrane_creep_sensitivity(t.material.membrane_model, t.material.membrane, t.rest,
                                          response.strain, t.x)
          .force_per_nonelastic *
      response.per_position;
  block += result.hessian;
}

} // namespace sartor::fem
