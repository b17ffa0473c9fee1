#include "fem/petsc_options.hpp"

#include <cstring>

namespace sartor {

PetscErrorCode set_default_option(const char* name, const char* value) {
  PetscBool chosen = PETSC_FALSE;
  PetscFunctionBeginUser;
  PetscCall(PetscOptionsHasName(nullptr, nullptr, name, &chosen));
  if (!chosen) PetscCall(PetscOptionsSetValue(nullptr, name, value));
  PetscFunctionReturn(0);
}

namespace {

PetscErrorCode set_default_lu(const std::string& option, bool symmetric = false) {
  PetscFunctionBeginUser;
  PetscCall(set_default_option((option + "ksp_type").c_str(), "preonly"));
  PetscCall(set_default_option((option + "pc_type").c_str(), symmetric ? "cholesky" : "lu"));
  PetscCall(set_default_option((option + "pc_factor_mat_solver_type").c_str(), "mumps"));
  PetscFunctionReturn(0);
}

} // namespace

PetscErrorCode set_default_direct_solver(MPI_Comm comm, const std::string& prefix, bool symmetric) {
  PetscMPIInt size = 1;
  PetscBool chosen = PETSC_FALSE;
  PetscFunctionBeginUser;
  const std::string option = "-" + prefix;
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCall(PetscOptionsHasName(nullptr, nullptr, (option + "pc_type").c_str(), &chosen));
  if (size == 1 || chosen) {
    PetscCall(set_default_lu(option, size == 1 && symmetric));
    PetscFunctionReturn(0);
  }
  PetscCall(set_default_option((option + "ksp_type").c_str(), "preonly"));
  PetscCall(PetscOptionsSetValue(nullptr, (option + "pc_type").c_str(), "telescope"));
  PetscCall(set_default_lu(option + "telescope_"));
  PetscFunctionReturn(0);
}

PetscErrorCode gather_telescope_onto_one_rank(KSP ksp) {
  PC pc = nullptr;
  PetscBool telescope = PETSC_FALSE, chosen = PETSC_FALSE;
  const char* prefix = nullptr;
  PetscMPIInt size = 1;
  PetscFunctionBeginUser;
  PetscCall(KSPGetPC(ksp, &pc));
  PetscCall(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(pc), PCTELESCOPE, &telescope));
  if (!telescope) PetscFunctionReturn(0);
  PetscCall(PCGetOptionsPrefix(pc, &prefix));
  PetscCall(PetscOptionsHasName(nullptr, prefix, "-pc_telescope_reduction_factor", &chosen));
  PetscCallMPI(MPI_Comm_size(PetscObjectComm(reinterpret_cast<PetscObject>(pc)), &size));
  if (!chosen) PetscCall(PCTelescopeSetReductionFactor(pc, size));
  PetscFunctionReturn(0);
}

PetscErrorCode direct_solver_failed(KSP ksp, bool* failed) {
  PC pc = nullptr;
  PetscBool telescope = PETSC_FALSE;
  PCFailedReason reason = PC_NOERROR;
  PetscFunctionBeginUser;
  PetscCall(KSPGetPC(ksp, &pc));
  PetscCall(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(pc), PCTELESCOPE, &telescope));
  if (telescope) {
    KSP factorising = nullptr; // null on the ranks that do not factorise
    PetscCall(PCTelescopeGetKSP(pc, &factorising));
    pc = nullptr;
    if (factorising) PetscCall(KSPGetPC(factorising, &pc));
  }
  if (pc) PetscCall(PCGetFailedReasonRank(pc, &reason));
  int local = reason == PC_NOERROR ? 0 : 1, any = 0;
  PetscCallMPI(MPI_Allreduce(&local, &any, 1, MPI_INT, MPI_MAX,
                             PetscObjectComm(reinterpret_cast<PetscObject>(ksp))));
  *failed = any == 1;
  PetscFunctionReturn(0);
}

} // namespace sartor
