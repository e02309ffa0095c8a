#pragma once
// How the vertices of the embedded mesh follow the particles (paper §5.2). A vertex's particles
// are those of the tets around it (its copy's tets, after splits).
#include <vector>

#include "mesh/split_mesh.hpp"

namespace fissure {

// Eqs 20–22: ω_v = Σ_p ¼ m_p, v_v = Σ_p ¼ m_p v_p / ω_v, x_v ← x_v + Δt v_v.
// `particle` is the particle of each tet; `mass` and `velocity` are per particle.
void advance_vertices(SplitMesh& mesh, const std::vector<int>& particle, const double* mass,
                      const double* velocity, double dt);

// The position-based variant: x_v = X_v + Σ_p m_p (y_p − x_p) / Σ_p m_p, with X_v the vertex's
// rest position and x_p, y_p the particles' reference and deformed positions.
void place_vertices(SplitMesh& mesh, const std::vector<int>& particle, const double* mass,
                    const double* reference, const double* y);

}  // namespace fissure
