#include "integrators/petsc_session.hpp"

#include <fmt/format.h>

#include <cstdlib>

#include "core/error.hpp"

namespace fissure {

void ensure_petsc() {
  PetscBool initialized = PETSC_FALSE;
  PetscInitialized(&initialized);
  if (initialized) return;
  petsc_check(PetscInitializeNoArguments(), "initialisation");
  // Fissure reports errors itself; PETSc must not catch the process's signals.
  petsc_check(PetscPopSignalHandler(), "signal handler removal");
  petsc_check(PetscPushErrorHandler(PetscReturnErrorHandler, nullptr), "error handler");
  std::atexit([] { PetscFinalize(); });
}

void petsc_check(PetscErrorCode code, const char* what) {
  if (code == 0) return;
  const char* text = nullptr;
  PetscErrorMessage(code, &text, nullptr);
  throw RunError(fmt::format("PETSc: {} failed: {} (error {})", what, text ? text : "", code));
}

}  // namespace fissure
