#pragma once
// The terms a time step adds to the cloth's potential, both quadratic in the
// lumped masses M (solvers/incremental_system.hpp):
//   (a/2) |x - x_pred|^2_M   inertia: backward Euler's a = 1/h^2 about
//                            x_pred = x_n + h v_n; pseudo-transient
//                            continuation's 1/dt^2 about the last state;
//   (b/2) |x - x_prev|^2_M   mass-proportional damping alpha M v: b = alpha/h
//                            about x_prev = x_n.
// One form for both: their Hessian (a + b) M is one diagonal. A weight of 0
// leaves its term out. The form belongs to the step's incremental potential,
// not to the cloth: ClothProblem refuses it (its energy report has no line
// for it). Its rows of held pins are the problem's to replace.

#include "fem/form.hpp"

namespace sartor::fem {

class InertiaForm final : public CouplingForm {
public:
  // Collective. `mass`: the lumped masses, three per vertex (copied).
  explicit InertiaForm(Vec mass);
  ~InertiaForm() override;
  InertiaForm(const InertiaForm&) = delete;
  InertiaForm& operator=(const InertiaForm&) = delete;

  double inertia_weight = 0.0; // a, 1/s^2
  double damping_weight = 0.0; // b, 1/s^2
  Vec mass() const { return mass_; }
  Vec predicted() const { return predicted_; } // x_pred
  Vec previous() const { return previous_; }   // x_prev
  bool active() const { return inertia_weight > 0.0 || damping_weight > 0.0; }

  const char* name() const override { return "inertia"; }
  EnergyPart part() const override { return EnergyPart::inertia; }
  PetscErrorCode energy(Vec x, double* energy) override;
  PetscErrorCode add_gradient(Vec x, Vec f) override;
  PetscErrorCode add_hessian(Vec x, bool exact, Mat J) override;
  // Diagonal: within the vertices' own blocks, always preallocated.
  PetscErrorCode record_couplings(Mat) override { return 0; }

private:
  Vec mass_ = nullptr;
  Vec predicted_ = nullptr;
  Vec previous_ = nullptr;
  Vec work_ = nullptr;
};

} // namespace sartor::fem
