// Must not compile: the core layer (sartor_core) has no PETSc on its include
// path. The test layers.core_rejects_petsc builds this file against
// sartor_core and expects the build to fail.
#include <petsc.h>

int layer_probe() {
  return PETSC_VERSION_MAJOR;
}
