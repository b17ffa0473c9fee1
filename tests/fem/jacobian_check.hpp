#pragma once
// The Jacobian of an assembled cloth problem against central differences of
// its residual along one direction, for the tests of every term (elements,
// contact, seams). The Jacobian is created through create_jacobian, so a
// coupling missing from the preallocation fails here too.

#include "fem/cloth_problem.hpp"

#include <petscmat.h>

namespace sartor::testing {

// |J v - (F(x + h v) - F(x - h v)) / (2 h)| / |J v| in `norm`; -1 when an
// assembly call fails.
inline double directional_jacobian_error(ClothProblem& problem, Vec x, Vec direction, double h,
                                         NormType norm) {
  Vec shifted = nullptr, up = nullptr, down = nullptr, jv = nullptr;
  Mat J = nullptr;
  for (Vec* w : {&shifted, &up, &down, &jv})
    VecDuplicate(x, w);
  double error = -1.0;
  if (problem.create_jacobian(&J) == 0 && problem.jacobian(x, J) == 0) {
    MatMult(J, direction, jv);
    VecWAXPY(shifted, h, direction, x);
    const PetscErrorCode plus = problem.residual(shifted, up);
    VecWAXPY(shifted, -h, direction, x);
    const PetscErrorCode minus = problem.residual(shifted, down);
    if (plus == 0 && minus == 0) {
      VecAXPY(up, -1.0, down);
      VecScale(up, 1.0 / (2.0 * h));
      PetscReal reference = 0.0, difference = 0.0;
      VecNorm(jv, norm, &reference);
      VecAXPY(up, -1.0, jv);
      VecNorm(up, norm, &difference);
      error = difference / reference;
    }
  }
  for (Vec* w : {&shifted, &up, &down, &jv})
    VecDestroy(w);
  MatDestroy(&J);
  return error;
}

} // namespace sartor::testing
