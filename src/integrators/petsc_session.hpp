#pragma once
// PETSc is initialised once per process, on first use, and finalised at exit. Its errors come
// back as return codes (no traceback on stderr) and become RunError through petsc_check.
#include <petscsys.h>

namespace fissure {

void ensure_petsc();
// Throws RunError naming `what` when a PETSc call failed.
void petsc_check(PetscErrorCode code, const char* what);
// For destructors, which must not throw: a failed call is reported on stderr.
void petsc_release(PetscErrorCode code, const char* what) noexcept;

}  // namespace fissure
