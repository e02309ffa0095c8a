#include "integrators/petsc_newton_settings.hpp"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

namespace fissure {

namespace {

using S = PetscNewtonSettings;

const std::vector<std::pair<std::string, S::Scheme>> kSchemes = {
    {"backward_euler", S::Scheme::backward_euler},
    {"newmark", S::Scheme::newmark},
    {"alpha", S::Scheme::alpha},
    {"sdirk3", S::Scheme::sdirk3},
    {"sdirk4", S::Scheme::sdirk4},
    {"esdirk4", S::Scheme::esdirk4},
    {"static", S::Scheme::static_equilibrium}};
const std::vector<std::pair<std::string, S::Tangent>> kTangents = {
    {"auto", S::Tangent::automatic},
    {"projected", S::Tangent::projected},
    {"majoriser", S::Tangent::majoriser},
    {"exact", S::Tangent::exact}};
const std::vector<std::pair<std::string, S::Preconditioner>> kPreconditioners = {
    {"auto", S::Preconditioner::automatic},      {"tangent", S::Preconditioner::tangent},
    {"majoriser", S::Preconditioner::majoriser}, {"nearest", S::Preconditioner::nearest},
    {"scalar", S::Preconditioner::scalar},       {"gamg", S::Preconditioner::gamg}};
const std::vector<std::pair<std::string, S::Krylov>> kKrylov = {{"auto", S::Krylov::automatic},
                                                                {"none", S::Krylov::none},
                                                                {"cg", S::Krylov::cg},
                                                                {"gmres", S::Krylov::gmres}};
const std::vector<std::pair<std::string, S::NewtonTest>> kNewtonTests = {
    {"auto", S::NewtonTest::automatic},
    {"residual", S::NewtonTest::residual},
    {"local_error", S::NewtonTest::local_error}};

// A whole number from 1 to 1e6 (the refresh limits).
int refresh_limit(const OptionReader& r, const std::string& key, int fallback) {
  if (!r.has(key)) return fallback;
  const double v = r.positive(key, 0);
  if (v != std::floor(v) || v > 1e6)
    r.fail(key, fmt::format("must be a whole number from 1 to 1e6, got {}", v));
  return static_cast<int>(v);
}

}  // namespace

FactorPrecision read_factor_precision(const OptionReader& r, FactorPrecision fallback) {
  static const std::vector<std::pair<std::string, FactorPrecision>> names = {
      {"single", FactorPrecision::single},
      {"double", FactorPrecision::full},
      {"half", FactorPrecision::half}};
  return r.choice("factor_precision", fallback, names);
}

const std::vector<std::string>& petsc_newton_keys() {
  // The last three are arkode's too (arkode_settings.cpp): the factor reuse of both.
  static const std::vector<std::string> keys = {"scheme",
                                                "rho_infinity",
                                                "steps",
                                                "tangent",
                                                "petsc_options",
                                                "max_step_halvings",
                                                "preconditioner",
                                                "krylov",
                                                "newton_test",
                                                "refresh_contraction",
                                                "refresh_iterations",
                                                "reuse_factor",
                                                "refresh_krylov",
                                                "factor_precision"};
  return keys;
}

std::shared_ptr<const IntegratorOptions> read_petsc_newton_settings(const OptionReader& r) {
  auto s = std::make_shared<PetscNewtonSettings>();
  s->max_step_halvings = r.whole("max_step_halvings", s->max_step_halvings, 0, 20);
  s->scheme = r.choice("scheme", s->scheme, kSchemes);
  s->tangent = r.choice("tangent", s->tangent, kTangents);
  s->preconditioner = r.choice("preconditioner", s->preconditioner, kPreconditioners);
  s->krylov = r.choice("krylov", s->krylov, kKrylov);
  s->factor_precision = read_factor_precision(r, s->factor_precision);
  s->newton_test = r.choice("newton_test", s->newton_test, kNewtonTests);
  if (const std::string refusal = newton_test_refusal(*s); !refusal.empty())
    r.fail("newton_test", refusal);
  if (s->tangent == S::Tangent::majoriser && s->preconditioner == S::Preconditioner::tangent)
    r.fail("preconditioner",
           "'tangent' factors the exact tangent; with tangent: majoriser use preconditioner: "
           "majoriser");
  s->reuse_factor = r.boolean("reuse_factor", s->reuse_factor);
  s->refresh_contraction = r.positive("refresh_contraction", s->refresh_contraction);
  if (s->refresh_contraction >= 1)
    r.fail("refresh_contraction", fmt::format("must be in (0, 1), got {}", s->refresh_contraction));
  s->refresh_iterations = refresh_limit(r, "refresh_iterations", s->refresh_iterations);
  s->refresh_krylov = refresh_limit(r, "refresh_krylov", s->refresh_krylov);
  s->rho_infinity = r.non_negative("rho_infinity", s->rho_infinity);
  if (s->rho_infinity > 1)
    r.fail("rho_infinity", fmt::format("must be in [0, 1], got {}", s->rho_infinity));
  if (r.has("steps")) {
    const double steps = r.positive("steps", 0);
    if (steps != std::floor(steps) || steps > 1e9)
      r.fail("steps", fmt::format("must be a whole number of increments, got {}", steps));
    s->steps = static_cast<int>(steps);
  }
  s->petsc_options = r.string("petsc_options", s->petsc_options);
  return s;
}

const SdirkTableau* sdirk_tableau(S::Scheme scheme) {
  switch (scheme) {
    case S::Scheme::sdirk3:
      return &sdirk3_tableau();
    case S::Scheme::sdirk4:
      return &sdirk4_tableau();
    case S::Scheme::esdirk4:
      return &esdirk4_tableau();
    default:
      return nullptr;
  }
}

std::string newton_test_refusal(const PetscNewtonSettings& settings) {
  if (settings.newton_test != S::NewtonTest::local_error) return {};
  const SdirkTableau* tableau = sdirk_tableau(settings.scheme);
  if (tableau && !tableau->b_embedded.empty()) return {};
  return fmt::format(
      "'local_error' needs a scheme with an embedded error estimate (esdirk4 or sdirk4), not {}",
      scheme_name(settings.scheme));
}

std::string scheme_name(S::Scheme scheme) { return choice_name(scheme, kSchemes); }
std::string tangent_name(S::Tangent tangent) { return choice_name(tangent, kTangents); }

S::Scheme scheme_named(const std::string& name) {
  for (const auto& [spelt, scheme] : kSchemes)
    if (spelt == name) return scheme;
  throw std::invalid_argument("no petsc_newton scheme '" + name + "'");
}

}  // namespace fissure
