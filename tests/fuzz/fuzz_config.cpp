// libFuzzer target: scene YAML text through parse_config. An InputError is the expected
// rejection of bad input; any other exception, crash, sanitizer report or hang is a finding.
#include <cstddef>
#include <cstdint>
#include <string>

#include "core/error.hpp"
#include "scene/config.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const fissure::Config config = fissure::parse_config(text, "fuzz/scene.yaml");
    if (config.bodies.empty()) __builtin_trap();  // the loader promises at least one body
  } catch (const fissure::InputError&) {
  }
  return 0;
}
