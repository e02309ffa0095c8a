#pragma once
// What the second-order model with fictitious particles (docs/model.md, deviation 8)
// reads from a body's tet mesh: its boundary, across which particles are mirrored, and each
// tet's second moment about its barycentre, the cell term's M_i.
#include <array>
#include <vector>

#include "mesh/tet_mesh.hpp"

namespace fissure {

// The faces no other tet shares (face_adjacency.hpp), each as its three corners (xyz each),
// ordered so that the normal points out of the mesh.
std::vector<std::array<double, 9>> boundary_triangles(const TetMesh& mesh);

// ∫ (x − c)(x − c)ᵀ dV over tet t, c its barycentre: V/20 Σ_a d_a d_aᵀ with d_a its corners
// from c (xx, yy, zz, xy, xz, yz).
std::array<double, 6> tet_second_moment(const TetMesh& mesh, int t);

}  // namespace fissure
