#pragma once
// The parsers of the options of the parts a scene names by type: an integrator
// (integrator.type), a model (material.model) and a collider's shape (the shape's key in a
// colliders entry), and of the outputs of a run, each with keys of its own in output:. Each part
// registers its own, next to its code (integrators/registry.hpp, model/model_registry.hpp,
// contact/collider_registry.hpp, app/output_registry.hpp); the config layer calls the one a scene
// names (every output's), so a part reads and checks its own keys without seeing YAML.
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

// A collider shape's own settings (e.g. a sphere's centre and radius), and what the shape allows
// of the keys every collider shares.
struct ColliderOptions {
  virtual ~ColliderOptions() = default;
  // Whether it may be given a velocity (a plane cannot), and a mass, which makes it dynamic.
  virtual bool moves() const { return true; }
  virtual bool can_be_dynamic() const { return false; }
};

// An output's own settings (keys of output: that only it reads).
struct OutputOptions {
  virtual ~OutputOptions() = default;
};

template <class Options>
struct OptionParser {
  std::string name;               // integrator.type, material.model, a shape key, an output
  std::vector<std::string> keys;  // its own keys, besides those every type shares
  // Reads them (a reader of the whole map, shared keys too; of its own map for a collider's
  // shape); null: the type has no options.
  std::function<std::shared_ptr<const Options>(const OptionReader&)> parse;
};

using IntegratorOptionParser = OptionParser<IntegratorOptions>;
using ModelOptionParser = OptionParser<ModelOptions>;
using ColliderOptionParser = OptionParser<ColliderOptions>;
using OutputOptionParser = OptionParser<OutputOptions>;

// Adds a parser; throws std::logic_error if its name is taken.
void register_option_parser(IntegratorOptionParser parser);
void register_option_parser(ModelOptionParser parser);
void register_option_parser(ColliderOptionParser parser);
void register_option_parser(OutputOptionParser parser);

// In the order of registration.
const std::vector<IntegratorOptionParser>& integrator_option_parsers();
const std::vector<ModelOptionParser>& model_option_parsers();
const std::vector<ColliderOptionParser>& collider_option_parsers();
const std::vector<OutputOptionParser>& output_option_parsers();

}  // namespace fissure
