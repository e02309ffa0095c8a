#include "integrators/registry.hpp"

#include "core/error.hpp"
#include "integrators/arkode.hpp"
#include "integrators/petsc_newton.hpp"
#include "integrators/symplectic_euler.hpp"
#include "integrators/velocity_verlet.hpp"
#include "scene/kind_list.hpp"
#include "scene/unknown_choice.hpp"

namespace fissure {

namespace {

std::vector<IntegratorKind>& kinds() {
  static std::vector<IntegratorKind> registered = [] {
    std::vector<IntegratorKind> builtin;
    add_kind(builtin, symplectic_euler_kind(), "integrator");
    add_kind(builtin, velocity_verlet_kind(), "integrator");
    add_kind(builtin, petsc_newton_kind(), "integrator");
    add_kind(builtin, arkode_kind(), "integrator");
    return builtin;
  }();
  return registered;
}

}  // namespace

void register_integrator(IntegratorKind kind) { add_kind(kinds(), std::move(kind), "integrator"); }

std::vector<std::string> integrator_names() { return kind_names(kinds()); }

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
