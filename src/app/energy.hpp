#pragma once
// Energies of the state that are not the model's: kinetic and gravitational.
#include <vector>

#include "scene/config.hpp"

namespace fissure {

// ½ Σ m_i |v_i|²
double kinetic_energy(const std::vector<double>& mass, const std::vector<double>& velocity);
// −Σ m_i g·y_i
double gravitational_energy(const std::vector<double>& mass, const std::vector<double>& position,
                            const Vec3& gravity);

}  // namespace fissure
