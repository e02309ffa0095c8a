// The PETSc Newton integrator's linear solver is a CHOLMOD Cholesky factorization applied once
// (KSPPREONLY + PCCHOLESKY), verified through PETSc's own view of the solver.
#include <gtest/gtest.h>

#include <sstream>

#include "integrators/petsc_newton.hpp"
#include "support/vibration.hpp"

namespace fissure {
namespace {

TEST(PetscSolver, KspViewShowsPreonlyCholeskyWithCholmod) {
  auto v = test::make_vibration();
  IntegratorSettings settings;
  settings.type = "petsc_newton";
  PetscNewton integrator(settings, "test");
  State s = v->initial;
  integrator.step(*v->dynamics, s, 10 * v->stable_dt);
  const std::string view = integrator.solver_view();
  std::istringstream lines(view);
  for (std::string line; std::getline(lines, line);)
    if (line.find("type:") != std::string::npos || line.find("package") != std::string::npos)
      std::printf("%s\n", line.c_str());
  EXPECT_NE(view.find("type: preonly"), std::string::npos);
  EXPECT_NE(view.find("type: cholesky"), std::string::npos);
  EXPECT_NE(view.find("package used to perform factorization: cholmod"), std::string::npos);
}

}  // namespace
}  // namespace fissure
