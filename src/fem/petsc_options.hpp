#pragma once
// Defaults that the options database can override.

#include <petscsys.h>

namespace sartor {

// Sets option `name` (e.g. "-ksp_type") to `value` unless the user chose it.
inline PetscErrorCode set_default_option(const char* name, const char* value) {
  PetscBool chosen = PETSC_FALSE;
  PetscFunctionBeginUser;
  PetscCall(PetscOptionsHasName(nullptr, nullptr, name, &chosen));
  if (!chosen) PetscCall(PetscOptionsSetValue(nullptr, name, value));
  PetscFunctionReturn(0);
}

} // namespace sartor
