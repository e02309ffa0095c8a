#pragma once
// The options of petsc_newton (docs/integrators.md) and their parser: integrator.scheme,
// tangent, preconditioner, krylov as enums, the refresh policy and PETSc's own options.
#include <memory>
#include <string>
#include <vector>

#include "integrators/sdirk_tableau.hpp"
#include "linear/factor_precision.hpp"
#include "scene/option_parsers.hpp"

namespace fissure {

struct PetscNewtonSettings final : IntegratorOptions {
  enum class Scheme { backward_euler, newmark, alpha, sdirk3, sdirk4, esdirk4, static_equilibrium };
  Scheme scheme = Scheme::backward_euler;
  double rho_infinity = 0.5;  // alpha: spectral radius at infinite frequency
  int steps = 1;              // static: load increments over which loads ramp
  // The stiffness Newton uses: exact or projected (auto: exact, projected where exact fails),
  // matrix-free, or the assembled bond-wise majoriser (model.hpp).
  enum class Tangent { automatic, projected, majoriser, exact };
  Tangent tangent = Tangent::automatic;
  std::string petsc_options;  // passed to PETSc untouched, e.g. "-snes_rtol 1e-8"
  int max_step_halvings = 4;  // halvings of a step whose Newton solve fails
  // The factor Newton's linear solves are preconditioned with: the tangent itself (two-hop,
  // CHOLMOD), the one-hop majoriser (CHOLMOD), the majoriser's bonds to each family's nearest
  // members (CHOLMOD), a scalar one-hop matrix times I₃ (CHOLMOD) or algebraic multigrid on the
  // majoriser (PETSc GAMG); auto by size.
  enum class Preconditioner { automatic, tangent, majoriser, nearest, scalar, gamg };
  Preconditioner preconditioner = Preconditioner::automatic;
  // The precision a CHOLMOD factor is kept and back-solved in: single halves the bytes each
  // back-solve reads; the Newton or Krylov iteration around it corrects the rounding.
  FactorPrecision factor_precision = FactorPrecision::half;
  // The linear solver around it: none (modified Newton: the factor alone), cg or gmres on the
  // matrix-free tangent; auto: none with the tangent's own factor, cg otherwise.
  enum class Krylov { automatic, none, cg, gmres };
  Krylov krylov = Krylov::automatic;
  bool reuse_factor = true;           // false: refactorize at every Newton iteration
  double refresh_contraction = 0.25;  // refresh when |r_k+1| / |r_k| exceeds this
  int refresh_iterations = 6;         // ... or a step's Newton iterations since the refresh do
  int refresh_krylov = 40;            // ... or one linear solve needs more Krylov iterations
  // When a Newton solve stops: PETSc's residual tests (-snes_rtol, ...), or also once the
  // estimated Newton error is under 1% of the step's local error estimate (schemes with
  // embedded weights); auto: local_error for esdirk4 unless petsc_options set -snes_rtol,
  // -snes_atol or -snes_stol.
  enum class NewtonTest { automatic, residual, local_error };
  NewtonTest newton_test = NewtonTest::automatic;
  // Settings made in code only (tests): evaluate E and ∇E after every Newton update, also after
  // one the error test accepts before the step's last stage (nothing reads them there).
  bool evaluate_every_update = false;

  int load_increments() const override { return scheme == Scheme::static_equilibrium ? steps : 0; }
};

// integrator.factor_precision (petsc_newton's and arkode's): `half`, `single` or `double`.
FactorPrecision read_factor_precision(const OptionReader& r, FactorPrecision fallback);

// The keys under integrator: that are petsc_newton's own, and their parser.
const std::vector<std::string>& petsc_newton_keys();
std::shared_ptr<const IntegratorOptions> read_petsc_newton_settings(const OptionReader& r);

// Why `newton_test` cannot be used with `scheme` (local_error needs a tableau with embedded
// weights), or empty.
std::string newton_test_refusal(const PetscNewtonSettings& settings);

// The tableau of an SDIRK scheme; nullptr for the others.
const SdirkTableau* sdirk_tableau(PetscNewtonSettings::Scheme scheme);

// As the config spells them.
std::string scheme_name(PetscNewtonSettings::Scheme scheme);
std::string tangent_name(PetscNewtonSettings::Tangent tangent);
// The scheme spelt `name`; std::invalid_argument if none is.
PetscNewtonSettings::Scheme scheme_named(const std::string& name);

}  // namespace fissure
