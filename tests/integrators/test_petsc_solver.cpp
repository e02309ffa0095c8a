// The PETSc Newton integrator's linear solver: a CHOLMOD Cholesky factorization applied once
// (KSPPREONLY, the factor kept in half precision by SupernodalCholesky), verified through
// PETSc's view of the solver; gamg's level smoothers and its finest matrix's threaded product; and
// the `auto` tangent's fallback to `projected` where the exact tangent cannot be factorized.
#include <gtest/gtest.h>
#include <omp.h>
#include <petscsys.h>

#include <sstream>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "integrators/petsc_newton.hpp"
#include "support/vibration.hpp"

namespace fissure {
namespace {

TEST(PetscSolver, KspViewShowsPreonlyCholeskyWithCholmod) {
  auto v = test::make_vibration();
  PetscNewton integrator(PetscNewtonSettings{}, "test");
  State s = v->initial;
  integrator.step(*v->dynamics, s, 10 * v->stable_dt);
  const std::string view = integrator.solver_view();
  std::istringstream lines(view);
  for (std::string line; std::getline(lines, line);)
    if (line.find("type:") != std::string::npos || line.find("CHOLMOD") != std::string::npos)
      std::printf("%s\n", line.c_str());
  EXPECT_NE(view.find("type: preonly"), std::string::npos);
  EXPECT_NE(view.find("CHOLMOD supernodal factor kept in half precision"), std::string::npos);
}

constexpr const char* kLevelsLimit = "-precond_mg_levels_ksp_max_it";

// The view's level smoothers (KSP objects prefixed precond_mg_levels_) and their iteration limits.
std::vector<int> smoother_limits(const std::string& view) {
  std::vector<int> limits;
  std::istringstream lines(view);
  const std::string limit = "maximum iterations=";
  bool level = false;
  for (std::string line; std::getline(lines, line);) {
    if (line.find("KSP Object: (precond_mg_levels_") != std::string::npos) level = true;
    const std::size_t at = line.find(limit);
    if (level && at != std::string::npos) {
      limits.push_back(std::stoi(line.substr(at + limit.size())));
      level = false;
    }
  }
  return limits;
}

// gamg smooths each level once (PETSc makes two sweeps: docs/integrators.md, "The linear
// solves", for what that saves), unless PETSC_OPTIONS sets the levels' limit; with two threads
// its finest matrix (the nearest members' 3×3 blocks) multiplies over them.
TEST(PetscSolver, GamgSmoothsEachLevelOnceUnlessPetscOptionsSayOtherwise) {
  auto v = test::make_vibration();
  PetscNewtonSettings settings;
  settings.preconditioner = PetscNewtonSettings::Preconditioner::gamg;
  auto limits_of_a_step = [&] {
    PetscNewton integrator(settings, "test");
    State s = v->initial;
    integrator.step(*v->dynamics, s, 10 * v->stable_dt);
    return smoother_limits(integrator.solver_view());
  };
  // the finest level's matrix multiplies over the threads (threaded_aij.hpp) where two run
  const int threads = omp_get_max_threads();
  omp_set_num_threads(2);
  {
    PetscNewton integrator(settings, "test");
    State s = v->initial;
    integrator.step(*v->dynamics, s, 10 * v->stable_dt);
    EXPECT_NE(integrator.solver_view().find("its matrix multiplied over the threads"),
              std::string::npos);
  }
  omp_set_num_threads(threads);
  const std::vector<int> ours = limits_of_a_step();
  std::printf("gamg: %zu levels smoothed\n", ours.size());
  ASSERT_GE(ours.size(), 1u) << "no multigrid level to smooth";
  for (int limit : ours) EXPECT_EQ(limit, 1);
  // what PETSC_OPTIONS puts in the global options database, cleared again whatever happens
  struct GlobalOption {
    GlobalOption() { EXPECT_EQ(PetscOptionsSetValue(nullptr, kLevelsLimit, "3"), 0); }
    ~GlobalOption() { EXPECT_EQ(PetscOptionsClearValue(nullptr, kLevelsLimit), 0); }
  };
  std::vector<int> theirs;
  {
    GlobalOption option;
    theirs = limits_of_a_step();
  }
  ASSERT_EQ(theirs.size(), ours.size());
  for (int limit : theirs) EXPECT_EQ(limit, 3);
}

double statistic(const Integrator& integrator, const std::string& name) {
  for (const auto& [key, value] : integrator.statistics())
    if (key == name) return value;
  ADD_FAILURE() << "no statistic " << name;
  return -1;
}

// The vibration block squeezed to 75% of its size about its centre, at rest: every bond is
// compressed, so the exact tangent's geometric term (−|t|/ℓ (I − n nᵀ) per bond) is negative,
// and along a rigid rotation it leaves the Hessian negative (E is invariant under rotations, so
// its curvature there is −∇E·W²y < 0 when the forces push outward). At 20× the explicit step the
// inertia A M = M/Δt² of backward Euler is too small to cover it: A M + K is indefinite and its
// Cholesky factorization fails. With `tangent: exact` the step stops with that message; with
// `auto` (docs/integrators.md) the stage is redone with the projected tangent (PSD, ⪰ K): the
// fallback and its refresh of the factor are counted, and the step completes without halving.
// (Before the preconditioner reset its PC after a failed factorization, CHOLMOD could not
// refactorize the failed supernodal factor and the projected stage failed too: "Newton did not
// converge ... DIVERGED_LINEAR_SOLVE after 0 iterations".)
TEST(PetscSolver, AutoTangentFallsBackToProjectedWhereTheExactFactorizationFails) {
  auto v = test::make_vibration();
  State squeezed = v->initial;
  for (std::size_t k = 0; k < squeezed.position.size(); ++k)
    squeezed.position[k] = 0.03 + 0.75 * (v->scene.particles.reference[k] - 0.03);
  const double dt = 20 * v->stable_dt;
  PetscNewtonSettings settings;
  settings.tangent = PetscNewtonSettings::Tangent::exact;
  settings.max_step_halvings = 0;
  {
    auto exact = make_integrator(integrator_settings("petsc_newton", settings), "test");
    State s = squeezed;
    try {
      exact->step(*v->dynamics, s, dt);
      ADD_FAILURE() << "the exact tangent was factorized: the case does not test the fallback";
    } catch (const RunError& e) {
      std::printf("tangent exact: %s\n", e.what());
      EXPECT_NE(std::string(e.what()).find("not positive definite"), std::string::npos);
    }
  }
  settings.tangent = PetscNewtonSettings::Tangent::automatic;
  auto integrator = std::make_unique<PetscNewton>(settings, "test");
  State s = squeezed;
  EXPECT_EQ(integrator->step(*v->dynamics, s, dt), dt);
  // The factor that recovered is CHOLMOD's still.
  EXPECT_NE(integrator->solver_view().find("CHOLMOD supernodal factor"), std::string::npos);
  EXPECT_EQ(s.time, dt);
  for (double y : s.position) ASSERT_TRUE(std::isfinite(y));
  std::printf("tangent auto: tangent_fallbacks %.0f, refreshes_fallback %.0f, step_halvings %.0f\n",
              statistic(*integrator, "tangent_fallbacks"),
              statistic(*integrator, "refreshes_fallback"),
              statistic(*integrator, "step_halvings"));
  EXPECT_GE(statistic(*integrator, "tangent_fallbacks"), 1);
  EXPECT_GE(statistic(*integrator, "refreshes_fallback"), 1);
  EXPECT_EQ(statistic(*integrator, "step_halvings"), 0);
}

}  // namespace
}  // namespace fissure
