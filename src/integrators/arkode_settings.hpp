#pragma once
// The options of arkode (docs/integrators.md) and their parser: the method (an ARKODE table or
// IMEX pair by name), the tolerances, fixed steps and the factor reuse of implicit stages.
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "integrators/arkode_methods.hpp"
#include "linear/factor_precision.hpp"
#include "scene/option_parsers.hpp"

namespace fissure {

struct ArkodeSettings final : IntegratorOptions {
  const ArkodeMethod* method = &arkode_method("ARK436L2SA", "");
  double rtol = 1e-6;
  double atol = 1e-9;
  bool fixed_step = false;  // take steps of exactly time.dt (no error control)
  // Off by default: CG with the stale factor cost more than refactorizing at each γ change on
  // the bar swing at 857 and 7,761 particles (docs/integrators.md).
  bool reuse_factor = false;
  int refresh_krylov = 40;  // refresh when one linear solve needs more Krylov iterations
  FactorPrecision factor_precision = FactorPrecision::half;  // of the kept CHOLMOD factor
  // The matrix CHOLMOD factorizes for the implicit stages: the two-hop tangent (the stage matrix
  // itself when fresh: one back-solve) or petsc_newton's `nearest` one-hop matrix (CG on the
  // exact stage matrix at every solve); auto: tangent up to 10,000 particles, nearest above.
  enum class Preconditioner { automatic, tangent, nearest };
  Preconditioner preconditioner = Preconditioner::automatic;
};

// What auto picks for a scene of `particles` particles (tangent or nearest), on one rank or
// over several.
ArkodeSettings::Preconditioner choose_arkode_preconditioner(std::size_t particles,
                                                            bool distributed = false);

// The keys under integrator: that are arkode's own, and their parser.
const std::vector<std::string>& arkode_keys();
std::shared_ptr<const IntegratorOptions> read_arkode_settings(const OptionReader& r);

}  // namespace fissure
