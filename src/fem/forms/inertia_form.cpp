#include "fem/forms/inertia_form.hpp"

#include "fem/petsc_call.hpp"

namespace sartor::fem {

InertiaForm::InertiaForm(Vec mass) {
  for (Vec* v : {&mass_, &predicted_, &previous_, &work_})
    SartorPetscCall(VecDuplicate(mass, v));
  SartorPetscCall(VecCopy(mass, mass_));
}

InertiaForm::~InertiaForm() {
  for (Vec* v : {&mass_, &predicted_, &previous_, &work_})
    VecDestroy(v);
}

PetscErrorCode InertiaForm::energy(Vec x, double* value) {
  PetscReal inertia = 0.0, damping = 0.0;
  PetscFunctionBeginUser;
  if (inertia_weight > 0.0) {
    PetscCall(VecWAXPY(work_, -1.0, predicted_, x));
    PetscCall(VecPointwiseMult(work_, work_, work_));
    PetscCall(VecDot(work_, mass_, &inertia));
  }
  if (damping_weight > 0.0) {
    PetscCall(VecWAXPY(work_, -1.0, previous_, x));
    PetscCall(VecPointwiseMult(work_, work_, work_));
    PetscCall(VecDot(work_, mass_, &damping));
  }
  *value = 0.5 * (inertia_weight * inertia + damping_weight * damping);
  PetscFunctionReturn(0);
}

PetscErrorCode InertiaForm::add_gradient(Vec x, Vec f) {
  PetscFunctionBeginUser;
  if (inertia_weight > 0.0) {
    PetscCall(VecWAXPY(work_, -1.0, predicted_, x));
    PetscCall(VecPointwiseMult(work_, work_, mass_));
    PetscCall(VecAXPY(f, inertia_weight, work_));
  }
  if (damping_weight > 0.0) {
    PetscCall(VecWAXPY(work_, -1.0, previous_, x));
    PetscCall(VecPointwiseMult(work_, work_, mass_));
    PetscCall(VecAXPY(f, damping_weight, work_));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode InertiaForm::add_hessian(Vec, bool, Mat J) {
  PetscFunctionBeginUser;
  const double weight = inertia_weight + damping_weight;
  if (weight > 0.0) {
    PetscCall(VecCopy(mass_, work_));
    PetscCall(VecScale(work_, weight));
    PetscCall(MatDiagonalSet(J, work_, ADD_VALUES));
  }
  PetscFunctionReturn(0);
}

} // namespace sartor::fem
