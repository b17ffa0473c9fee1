#pragma once
// The Jacobian of an assembled cloth problem against central differences of
// its residual along one direction, for the tests of every term (elements,
// contact, seams). The Jacobian is created through create_jacobian, so a
// coupling missing from the preallocation fails here too.

#include "fem/cloth_problem.hpp"

#include <petscmat.h>

namespace sartor::testing {

// |J v - (F(x + h v) - F(x - h v)) / (2 h)| / |J v| in `norm`, for a residual
// `residual(y, F)` and a Jacobian `jacobian(y, J)` assembled into J (made
// by the caller); -1 when a call fails.
template <class Residual, class Jacobian>
double directional_derivative_error(Mat J, Vec x, Vec direction, double h, NormType norm,
                                    const Residual& residual, const Jacobian& jacobian) {
  Vec shifted = nullptr, up = nullptr, down = nullptr, jv = nullptr;
  for (Vec* w : {&shifted, &up, &down, &jv})
    VecDuplicate(x, w);
  double error = -1.0;
  if (jacobian(x, J) == 0) {
    MatMult(J, direction, jv);
    VecWAXPY(shifted, h, direction, x);
    const PetscErrorCode plus = residual(shifted, up);
    VecWAXPY(shifted, -h, direction, x);
    const PetscErrorCode minus = residual(shifted, down);
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
  return error;
}

// The same for an assembled cloth problem, its Jacobian made by create_jacobian.
inline double directional_jacobian_error(ClothProblem& problem, Vec x, Vec direction, double h,
                                         NormType norm) {
  Mat J = nullptr;
  double error = -1.0;
  if (problem.create_jacobian(&J) == 0) {
    error = directional_derivative_error(
        J, x, direction, h, norm, [&](Vec y, Vec f) { return problem.residual(y, f); },
        [&](Vec y, Mat A) { return problem.jacobian(y, A); });
  }
  MatDestroy(&J);
  return error;
}

} // namespace sartor::testing
