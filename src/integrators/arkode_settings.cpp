#include "integrators/arkode_settings.hpp"

#include <fmt/format.h>

#include <cmath>

#include "integrators/petsc_newton_settings.hpp"

namespace fissure {

const std::vector<std::string>& arkode_keys() {
  // The last four are petsc_newton's too (petsc_newton_settings.cpp).
  static const std::vector<std::string> keys = {
      "method",           "rtol",          "atol", "fixed_step", "reuse_factor", "refresh_krylov",
      "factor_precision", "preconditioner"};
  return keys;
}

ArkodeSettings::Preconditioner choose_arkode_preconditioner(std::size_t particles,
                                                            bool distributed) {
  // As petsc_newton's auto below its multigrid: the two-hop factor while it fits (1.77 GB at
  // 7,948 particles, 6.65 GB at 17,096), the nearest members' one-hop factor above
  // (docs/integrators.md); over several ranks the two-hop rows reach beyond the halo.
  return particles <= 10000 && !distributed ? ArkodeSettings::Preconditioner::tangent
                                            : ArkodeSettings::Preconditioner::nearest;
}

std::shared_ptr<const IntegratorOptions> read_arkode_settings(const OptionReader& r) {
  using P = ArkodeSettings::Preconditioner;
  static const std::vector<std::pair<std::string, P>> preconditioners = {
      {"auto", P::automatic}, {"tangent", P::tangent}, {"nearest", P::nearest}};
  auto s = std::make_shared<ArkodeSettings>();
  s->preconditioner = r.choice("preconditioner", s->preconditioner, preconditioners);
  s->reuse_factor = r.boolean("reuse_factor", s->reuse_factor);
  s->factor_precision = read_factor_precision(r, s->factor_precision);
  if (r.has("refresh_krylov")) {
    const double v = r.positive("refresh_krylov", 0);
    if (v != std::floor(v) || v > 1e6)
      r.fail("refresh_krylov", fmt::format("must be a whole number from 1 to 1e6, got {}", v));
    s->refresh_krylov = static_cast<int>(v);
  }
  const std::string method = r.string("method", s->method->name);
  s->rtol = r.positive("rtol", s->rtol);
  s->atol = r.positive("atol", s->atol);
  s->fixed_step = r.boolean("fixed_step", s->fixed_step);
  s->method = &arkode_method(method, r.file());
  return s;
}

}  // namespace fissure
