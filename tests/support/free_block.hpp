#pragma once
// The free block of the ledger and recipe tests: a 0.1 m cube of 8 particles of a soft solid
// (ρ = 1000 kg/m³, so M = 1 kg), 100 steps of 1 ms, no constraint, with the top-level YAML
// `extra` (gravity, output) after it.
#include <string>

namespace fissure::test {

inline std::string free_block_yaml(const std::string& extra) {
  return "time: {end: 0.1, dt: 0.001}\n"
         "bodies:\n"
         "  - geometry: {box: {min: [0, 0, 0], max: [0.1, 0.1, 0.1]}}\n"
         "    resolution: 0.05\n"
         "    material: {density: 1000, bulk_modulus: 1.0e5, shear_modulus: 5.0e4}\n" +
         extra;
}

}  // namespace fissure::test
