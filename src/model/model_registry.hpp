#pragma once
// The models a scene can name (material.model), each registered in one place next to its code:
// its name, its own option keys under material: and their parser (scene/option_parsers.hpp) and
// its constructor. The built-in ones are registered on first use of the registry and, through
// builtin_registration.cpp, at start-up of every program linked to this layer, so that config
// parsing sees them; a test registers its own with register_model. make_model (model.hpp)
// builds the one the bodies name.
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "model/model.hpp"
#include "scene/option_parsers.hpp"

namespace fissure {

struct ModelKind {
  std::string name;
  std::vector<std::string> keys;  // its own keys in a body's material: map
  // Reads them for one body (null: the model has none); the result is Material::options.
  std::function<std::shared_ptr<const ModelOptions>(const OptionReader&)> parse;
  // Makes the model for the scene's particles with their material constants.
  std::function<std::unique_ptr<Model>(const Scene&, MaterialPoints)> make;
};

// Adds `kind` and its option parser; throws std::logic_error if the name is taken.
void register_model(ModelKind kind);
std::vector<std::string> model_names();

}  // namespace fissure
