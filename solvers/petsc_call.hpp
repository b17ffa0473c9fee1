#pragma once
// PetscCall for C++ code that is not itself a PETSc-style function: on error
// PETSc's handler has already printed its trace; we unwind with an exception
// that the driver turns into a non-zero exit. (Debian's PETSc is built for C,
// so PETSc's own PetscCallThrow is not available.)

#include <petscsys.h>

#include <stdexcept>
#include <string>

namespace sartor {

class PetscFailure : public std::runtime_error {
public:
  PetscFailure(PetscErrorCode code, const char* file, int line)
      : std::runtime_error("PETSc error " + std::to_string(int(code)) + " at " + file + ":" +
                           std::to_string(line)) {}
};

} // namespace sartor

#define SartorPetscCall(...)                                                                       \
  do {                                                                                             \
    const PetscErrorCode sartor_petsc_error_ = __VA_ARGS__;                                        \
    if (PetscUnlikely(sartor_petsc_error_)) {                                                      \
      throw sartor::PetscFailure(sartor_petsc_error_, __FILE__, __LINE__);                         \
    }                                                                                              \
  } while (0)
