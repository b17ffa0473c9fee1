#pragma once
// PetscCall for C++ code that is not itself a PETSc-style function: on error
// PETSc's handler has already printed its trace; we unwind with an exception
// that the driver turns into a non-zero exit. (Debian's PETSc is built for C,
// so PETSc's own PetscCallThrow is not available.)

#include <petscsys.h>

#include <stdexcept>
#include <string>

namespace sartor {

// Errors PETSc raises for a bad option value or input, not for a bug.
inline bool is_petsc_user_error(PetscErrorCode code) {
  return code == PETSC_ERR_ARG_UNKNOWN_TYPE || code == PETSC_ERR_ARG_WRONG ||
         code == PETSC_ERR_ARG_OUTOFRANGE || code == PETSC_ERR_ARG_INCOMP ||
         code == PETSC_ERR_USER_INPUT || code == PETSC_ERR_USER || code == PETSC_ERR_FILE_OPEN ||
         code == PETSC_ERR_FILE_READ || code == PETSC_ERR_FILE_UNEXPECTED;
}

class PetscFailure : public std::runtime_error {
public:
  PetscFailure(PetscErrorCode code, const char* file, int line)
      : std::runtime_error("PETSc error " + std::to_string(int(code)) + " at " + file + ":" +
                           std::to_string(line)),
        code_(code) {}
  bool is_user_error() const { return is_petsc_user_error(code_); }

private:
  PetscErrorCode code_;
};

} // namespace sartor

#define SartorPetscCall(...)                                                                       \
  do {                                                                                             \
    const PetscErrorCode sartor_petsc_error_ = __VA_ARGS__;                                        \
    if (PetscUnlikely(sartor_petsc_error_)) {                                                      \
      throw sartor::PetscFailure(sartor_petsc_error_, __FILE__, __LINE__);                         \
    }                                                                                              \
  } while (0)
