#include "fem/forms/bending_forms.hpp"

#include "element/rest_derivative.hpp"
#include "fem/forms/local_arrays.hpp"

#include <algorithm>

namespace sartor::fem {

void HingeBendingForm::add_energy(const FormPoint& at, double* sum) const {
  for (const LocalHinge& h : hinges_) {
    *sum += element::bending(model_, h.stiffness, h.rest, gather<12>(at.x, h.dofs),
                             element::Want::energy)
                .energy;
  }
}

void HingeBendingForm::add_gradient(const FormPoint& at, PetscScalar* f) const {
  for (const LocalHinge& h : hinges_) {
    scatter_add<12>(f, h.dofs,
                    element::bending(model_, h.stiffness, h.rest, gather<12>(at.x, h.dofs),
                                     element::Want::gradient)
                        .gradient);
  }
}

PetscErrorCode HingeBendingForm::register_elements(ElementRegistry& registry) const {
  PetscFunctionBeginUser;
  for (const LocalHinge& h : hinges_)
    PetscCall(registry.add(h.dofs));
  PetscFunctionReturn(0);
}

PetscErrorCode HingeBendingForm::add_element_hessians(const FormPoint& at,
                                                      ElementHessians& out) const {
  PetscFunctionBeginUser;
  for (const LocalHinge& h : hinges_) {
    auto result = element::bending(model_, h.stiffness, h.rest, gather<12>(at.x, h.dofs),
                                   element::Want::hessian);
    if (h.project && !at.exact_hessian) element::project_to_psd<12>(result.hessian);
    PetscCall(out.add<12>(h.dofs, result.hessian));
  }
  PetscFunctionReturn(0);
}

bool HingeBendingForm::projects() const {
  return std::any_of(hinges_.begin(), hinges_.end(), [](const LocalHinge& h) { return h.project; });
}

void HingeBendingForm::add_rest_derivative(const FormPoint& at, const RestChange& change,
                                           PetscScalar* f) const {
  for (const LocalHinge& h : hinges_) {
    std::array<std::array<Eigen::Vector2d, 3>, 2> uv, delta;
    for (std::size_t side = 0; side < 2; ++side) {
      const auto t = std::size_t(h.triangles[side]);
      for (std::size_t k = 0; k < 3; ++k) {
        uv[side][k] = uv_[t][std::size_t(h.corners[side][k])];
        delta[side][k] = change[t][std::size_t(h.corners[side][k])];
      }
    }
    const element::HingeRest rest_change =
        element::hinge_rest_derivative(uv[0], uv[1], delta[0], delta[1]);
    scatter_add<12>(f, h.dofs,
                    element::bending_rest_derivative(model_, h.stiffness, h.rest, rest_change,
                                                     gather<12>(at.x, h.dofs)));
  }
}

void PatchBendingForm::add_energy(const FormPoint& at, double* sum) const {
  for (const LocalPatch& p : patches_) {
    *sum += element::patch_bending(p.rest, gather<36>(at.x, p.dofs), element::Want::energy).energy;
  }
}

void PatchBendingForm::add_gradient(const FormPoint& at, PetscScalar* f) const {
  for (const LocalPatch& p : patches_) {
    scatter_add<36>(
        f, p.dofs,
        element::patch_bending(p.rest, gather<36>(at.x, p.dofs), element::Want::gradient).gradient);
  }
}

PetscErrorCode PatchBendingForm::register_elements(ElementRegistry& registry) const {
  PetscFunctionBeginUser;
  for (const LocalPatch& p : patches_)
    PetscCall(registry.add(p.dofs));
  PetscFunctionReturn(0);
}

PetscErrorCode PatchBendingForm::add_element_hessians(const FormPoint& at,
                                                      ElementHessians& out) const {
  PetscFunctionBeginUser;
  for (const LocalPatch& p : patches_) {
    const element::Vector36 x = gather<36>(at.x, p.dofs);
    const bool psd = p.project && !at.exact_hessian;
    if (psd && p.gauss_newton) {
      PetscCall(out.add<36>(p.dofs, element::patch_gauss_newton_hessian(p.rest, x)));
      continue;
    }
    auto result = element::patch_bending(p.rest, x, element::Want::hessian);
    if (psd) element::project_patch_hessian_to_psd(p.rest, x, result.hessian);
    PetscCall(out.add<36>(p.dofs, result.hessian));
  }
  PetscFunctionReturn(0);
}

// The kernel's exact response to the change of the rest data; the rest
// data's own change, also exact, from the patch model (forward-mode
// automatic differentiation through the patches of the triangle and its
// neighbours).
void PatchBendingForm::add_rest_derivative(const FormPoint& at, const RestChange& change,
                                           PetscScalar* f) const {
  for (const LocalPatch& p : patches_) {
    const element::PatchRestChange delta = rest_data_change_(p.triangle, change);
    scatter_add<36>(
        f, p.dofs, element::patch_bending_rest_derivative(p.rest, delta, gather<36>(at.x, p.dofs)));
  }
}

bool PatchBendingForm::projects() const {
  return std::any_of(patches_.begin(), patches_.end(),
                     [](const LocalPatch& p) { return p.project; });
}

} // namespace sartor::fem
