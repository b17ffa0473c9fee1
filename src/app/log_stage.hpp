#pragma once
// A PETSc log stage for as long as the object lives: -log_view reports the
// events of a level of a solve on several levels under its own name.

#include "fem/petsc_call.hpp"

#include <petsclog.h>

#include <string>

namespace sartor {

class LogStage {
public:
  explicit LogStage(const std::string& name) {
    PetscLogStage stage = 0;
    SartorPetscCall(PetscLogStageRegister(name.c_str(), &stage));
    SartorPetscCall(PetscLogStagePush(stage));
  }
  LogStage(const LogStage&) = delete;
  LogStage& operator=(const LogStage&) = delete;
  ~LogStage() { PetscLogStagePop(); }
};

} // namespace sartor
