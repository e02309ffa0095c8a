// libFuzzer target: scene YAML text through parse_config. An InputError is the expected
// rejection of bad input; any other exception, crash, sanitizer report or hang is a finding.
#include <cstddef>
#include <cstdint>
#include <string>

#include "contact/collider_registry.hpp"
#include "core/error.hpp"
#include "integrators/petsc_newton_settings.hpp"
#include "scene/config.hpp"

namespace {

// The lean library has no integrators or models, whose registries name the built-in ones
// (integrators/registry.cpp, model/model_registry.cpp): their option parsers are registered
// here, petsc_newton's the real one (PETSc-free); arkode's needs SUNDIALS and is left out. The
// collider shapes' registry is in the lean library and registers the real parsers on first use.
[[maybe_unused]] const bool registered = [] {
  using fissure::register_option_parser;
  register_option_parser(fissure::IntegratorOptionParser{"symplectic_euler", {}, nullptr});
  register_option_parser(fissure::IntegratorOptionParser{"velocity_verlet", {}, nullptr});
  register_option_parser(fissure::IntegratorOptionParser{
      "petsc_newton", fissure::petsc_newton_keys(), fissure::read_petsc_newton_settings});
  register_option_parser(fissure::ModelOptionParser{"lps", {}, nullptr});
  register_option_parser(fissure::ModelOptionParser{"paper", {}, nullptr});
  return !fissure::collider_names().empty();
}();

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const fissure::Config config = fissure::parse_config(text, "fuzz/scene.yaml");
    if (config.bodies.empty()) __builtin_trap();  // the loader promises at least one body
  } catch (const fissure::InputError&) {
  }
  return 0;
}
