#include "integrators/petsc_session.hpp"

#include <fmt/format.h>

#include <cstdio>
#include <cstdlib>

#include "core/error.hpp"

namespace fissure {

void ensure_petsc() {
  PetscBool initialized = PETSC_FALSE;
  petsc_check(PetscInitialized(&initialized), "PetscInitialized");
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
  if (PetscErrorMessage(code, &text, nullptr) != 0) text = nullptr;
  throw RunError(fmt::format("PETSc: {} failed: {} (error {})", what, text ? text : "", code));
}

void petsc_release(PetscErrorCode code, const char* what) noexcept {
  if (code != 0) std::fprintf(stderr, "warning: PETSc: %s failed (error %d)\n", what, int(code));
}

}  // namespace fissure
