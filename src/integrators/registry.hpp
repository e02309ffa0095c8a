#pragma once
// The integrators a scene can name (integrator.type), each registered in one place next to its
// code: its name, its own option keys and their parser (scene/option_parsers.hpp) and its
// constructor. The built-in ones are registered on first use of the registry and, through
// builtin_registration.cpp, at start-up of every program linked to this layer, so that config
// parsing sees them; a test registers its own with register_integrator.
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "integrators/integrator.hpp"

namespace fissure {

struct IntegratorKind {
  std::string name;
  std::vector<std::string> keys;  // its own keys under integrator:
  // Reads them (null: the type has none); the result is IntegratorSettings::options.
  std::function<std::shared_ptr<const IntegratorOptions>(const OptionReader&)> parse;
  // Makes the integrator; `file` names the config in error messages.
  std::function<std::unique_ptr<Integrator>(const IntegratorSettings&, const std::string& file)>
      make;
};

// Adds `kind` and its option parser; throws std::logic_error if the name is taken.
void register_integrator(IntegratorKind kind);

// The options an integrator of type T reads: its parser's, or T's defaults when none were
// parsed (settings made in code).
template <class Options>
Options options_of(const IntegratorSettings& settings) {
  if (!settings.options) return Options{};
  const auto* options = dynamic_cast<const Options*>(settings.options.get());
  if (!options) throw std::logic_error("integrator '" + settings.type + "' got foreign options");
  return *options;
}

// Settings of `type` with its own options given in code (as its parser would make them).
template <class Options>
IntegratorSettings integrator_settings(std::string type, Options options) {
  IntegratorSettings settings;
  settings.type = std::move(type);
  settings.options = std::make_shared<const Options>(std::move(options));
  return settings;
}

}  // namespace fissure
