#pragma once
// The parsers of the options of the parts a scene names by type: an integrator
// (integrator.type) and a model (material.model). Each part registers its own, next to its code
// (integrators/registry.hpp, model/model_registry.hpp); the config layer calls the one a scene
// names, so a part reads and checks its own keys without seeing YAML.
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "scene/option_reader.hpp"

namespace fissure {

// An integrator's own settings, as its parser made them (e.g. integrators/
// petsc_newton_settings.hpp); the integrator's constructor reads them back.
struct IntegratorOptions {
  virtual ~IntegratorOptions() = default;
  // Increments over which the loads ramp to full (a static solve), 0 when they do not: time.dt
  // auto is then time.end over them, and a time.dt that reaches time.end in fewer is refused.
  virtual int load_increments() const { return 0; }
};

// A model's own settings for one body (e.g. a test-only model's spring constant).
struct ModelOptions {
  virtual ~ModelOptions() = default;
};

template <class Options>
struct OptionParser {
  std::string name;               // integrator.type or material.model
  std::vector<std::string> keys;  // its own keys, besides those every type shares
  // Reads them (a reader of the whole map: shared keys too); null: the type has no options.
  std::function<std::shared_ptr<const Options>(const OptionReader&)> parse;
};

using IntegratorOptionParser = OptionParser<IntegratorOptions>;
using ModelOptionParser = OptionParser<ModelOptions>;

// Adds a parser; throws std::logic_error if its name is taken.
void register_option_parser(IntegratorOptionParser parser);
void register_option_parser(ModelOptionParser parser);

// In the order of registration.
const std::vector<IntegratorOptionParser>& integrator_option_parsers();
const std::vector<ModelOptionParser>& model_option_parsers();

}  // namespace fissure
