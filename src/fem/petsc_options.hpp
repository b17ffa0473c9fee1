#pragma once
// Defaults that the options database can override.

#include <petscksp.h>

#include <string>

namespace sartor {

// Sets option `name` (e.g. "-ksp_type") to `value` unless the user chose it.
PetscErrorCode set_default_option(const char* name, const char* value);

// Collective. The default direct solver of the KSP with options prefix
// `prefix`: MUMPS's LU. On several ranks the matrix is gathered onto rank 0
// (PCTELESCOPE) and factorised there, because MUMPS's parallel factorisation
// adds contributions in the order messages arrive: reruns on the same ranks
// would differ at round-off, and any path that turns on round-off with them.
// `-PREFIXpc_type lu` chooses the parallel factorisation
// (docs/reliability.md#mpi-determinism).
// With `symmetric` (the system's matrices are), on one rank MUMPS's LDL^T
// (PCCHOLESKY, its symmetric mode) instead: about half the work.
PetscErrorCode set_default_direct_solver(MPI_Comm comm, const std::string& prefix = "",
                                         bool symmetric = false);

// Collective; after KSPSetFromOptions. A PCTELESCOPE whose reduction factor
// the options do not give gathers onto one rank, whatever the rank count (a
// petsc_options.txt written on some ranks re-runs on any other).
PetscErrorCode gather_telescope_onto_one_rank(KSP ksp);

// Collective. Whether the factorisation of `ksp`'s direct solver failed on any
// rank, looking through PCTELESCOPE to the factorising rank's solver.
PetscErrorCode direct_solver_failed(KSP ksp, bool* failed);

} // namespace sartor
