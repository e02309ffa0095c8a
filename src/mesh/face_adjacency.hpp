#pragma once
// Face adjacency of a tet mesh: which tet lies across each face.
#include <vector>

#include "mesh/tet_mesh.hpp"

namespace fissure {

// Local corners of face k (the face opposite corner k), ordered so that the face's normal points
// out of a positively oriented tet.
inline constexpr int kFaceCorners[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};

// For each face id 4 t + k, the id 4 n + k' of the same face seen from the tet n across it, or −1
// on the boundary. A face held by more than two tets (a non-manifold input) is boundary for all.
std::vector<int> face_adjacency(const TetMesh& mesh);

}  // namespace fissure
