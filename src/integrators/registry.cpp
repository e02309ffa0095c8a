#include "integrators/registry.hpp"

#include "core/error.hpp"
#include "integrators/arkode.hpp"
#include "integrators/petsc_newton.hpp"
#include "integrators/symplectic_euler.hpp"
#include "integrators/velocity_verlet.hpp"
#include "scene/unknown_choice.hpp"

namespace fissure {

namespace {

void add(std::vector<IntegratorKind>& kinds, IntegratorKind kind) {
  for (const auto& k : kinds)
    if (k.name == kind.name)
      throw std::logic_error("the integrator '" + kind.name + "' is registered twice");
  register_option_parser(IntegratorOptionParser{kind.name, kind.keys, kind.parse});
  kinds.push_back(std::move(kind));
}

std::vector<IntegratorKind>& kinds() {
  static std::vector<IntegratorKind> registered = [] {
    std::vector<IntegratorKind> builtin;
    add(builtin, symplectic_euler_kind());
    add(builtin, velocity_verlet_kind());
    add(builtin, petsc_newton_kind());
    add(builtin, arkode_kind());
    return builtin;
  }();
  return registered;
}

}  // namespace

void register_integrator(IntegratorKind kind) { add(kinds(), std::move(kind)); }

std::vector<std::string> integrator_names() {
  std::vector<std::string> names;
  for (const auto& kind : kinds()) names.push_back(kind.name);
  return names;
}

std::unique_ptr<Integrator> make_integrator(const std::string& type, const std::string& file) {
  IntegratorSettings settings;
  settings.type = type;
  return make_integrator(settings, file);
}

std::unique_ptr<Integrator> make_integrator(const IntegratorSettings& settings,
                                            const std::string& file) {
  for (const auto& kind : kinds())
    if (kind.name == settings.type) return kind.make(settings, file);
  throw InputError(file, "integrator.type",
                   unknown_choice("integrator", settings.type, integrator_names()));
}

}  // namespace fissure
