#pragma once
// The kinetic energy of the state (the elastic one is the model's).
#include <vector>

namespace fissure {

// ½ Σ m_i |v_i|²
double kinetic_energy(const std::vector<double>& mass, const std::vector<double>& velocity);
// ½ Σ m_i |v_i|² over the particles [first, end) (a rank's rows).
double kinetic_energy(const std::vector<double>& mass, const std::vector<double>& velocity,
                      int first, int end);

}  // namespace fissure
