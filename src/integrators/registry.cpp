#include <functional>
#include <utility>

#include "core/error.hpp"
#include "integrators/arkode.hpp"
#include "integrators/integrator.hpp"
#include "integrators/petsc_newton.hpp"
#include "integrators/symplectic_euler.hpp"
#include "integrators/velocity_verlet.hpp"
#include "scene/unknown_choice.hpp"

namespace fissure {

namespace {

using Factory =
    std::function<std::unique_ptr<Integrator>(const IntegratorSettings&, const std::string&)>;

const std::vector<std::pair<std::string, Factory>>& registry() {
  static const std::vector<std::pair<std::string, Factory>> entries = {
      {"symplectic_euler", [](auto&, auto&) { return std::make_unique<SymplecticEuler>(); }},
      {"velocity_verlet", [](auto&, auto&) { return std::make_unique<VelocityVerlet>(); }},
      {"petsc_newton",
       [](const IntegratorSettings& s, const std::string& file) {
         return std::make_unique<PetscNewton>(s, file);
       }},
      {"arkode", [](const IntegratorSettings& s,
                    const std::string& file) { return std::make_unique<Arkode>(s, file); }},
  };
  return entries;
}

}  // namespace

std::vector<std::string> integrator_names() {
  std::vector<std::string> names;
  for (const auto& [name, factory] : registry()) names.push_back(name);
  return names;
}

std::unique_ptr<Integrator> make_integrator(const std::string& type, const std::string& file) {
  IntegratorSettings settings;
  settings.type = type;
  return make_integrator(settings, file);
}

std::unique_ptr<Integrator> make_integrator(const IntegratorSettings& settings,
                                            const std::string& file) {
  const std::string& type = settings.type;
  for (const auto& [name, factory] : registry())
    if (name == type) return factory(settings, file);
  throw InputError(file, "integrator.type", unknown_choice("integrator", type, integrator_names()));
}

}  // namespace fissure
