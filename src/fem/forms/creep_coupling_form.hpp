#pragma once
// The monolithic creep coupling (fem/creep_coupling.hpp) as a form: while a
// creep step is coupled, each triangle's membrane force is taken at the
// non-elastic strains the step's creep law gives at the triangle's positions
// (NonelasticResponse), and its Hessian adds their dependence on the
// positions, dF/dn dn/dx (and its rest derivative their dependence on the
// rest coordinates). It stands in for the membrane form then (one of the
// two is active at a time); the residual has no potential while it does, and
// the energy it reports is the held strains' (the step's start).

#include "fem/cloth_model.hpp"
#include "fem/form.hpp"

#include <vector>

namespace sartor::fem {

class CreepCouplingForm final : public TriangleForm {
public:
  // Both are the problem's, read at every evaluation.
  CreepCouplingForm(const std::vector<element::NonelasticStrain>& nonelastic,
                    const NonelasticResponse* const& response)
      : nonelastic_(nonelastic), response_(response) {}
  const char* name() const override { return "creep coupling"; }
  EnergyPart part() const override { return EnergyPart::membrane; }
  bool active() const override { return response_ != nullptr; }
  void add_energy(const TriangleView& t, const FormPoint& at, double* sum) const override;
  element::Vector9 gradient(const TriangleView& t, const FormPoint& at) const override;
  void add_hessian(const TriangleView& t, const FormPoint& at, Matrix9& block) const override;
  bool has_potential() const override { return !(response_ && response_->moves_with_positions()); }
  bool projects(const ClothMaterial& material) const override { return material.project_membrane; }
  // At the coupled strains, which follow the rest coordinates through the
  // tensions: dF/dX + dF/dn dn/dT dT/dX (the committed state held).
  bool has_rest_derivative() const override { return true; }
  element::Vector9 rest_derivative(const TriangleView& t, const FormPoint& at,
                                   const std::array<Eigen::Vector2d, 3>& delta_uv) const override;

private:
  const std::vector<element::NonelasticStrain>& nonelastic_;
  const NonelasticResponse* const& response_;
};

} // namespace sartor::fem
