#pragma once
// A tet mesh whose vertices can be split along crack faces (paper §5.2). Every tet keeps its four
// corner slots; a split re-points some corners to a copy of their vertex. Face adjacency and the
// corners around each original vertex are fixed at construction: the tets of a copy are those
// around its original vertex whose corner points to the copy.
#include <vector>

#include "mesh/tet_mesh.hpp"

namespace fissure {

struct SplitMesh {
  TetMesh mesh;                  // rest positions of every vertex (copies included) and corners
  std::vector<double> position;  // current position of every vertex, 3 per vertex
  std::vector<int> origin;       // the original vertex each vertex is a copy of
  std::vector<int> across;       // face id 4 t + k → face id across it, or −1 (face_adjacency)
  std::vector<int> corner_offsets;  // per original vertex, into `corners`
  std::vector<int> corners;         // corner ids 4 t + c at each original vertex

  int vertex_count() const { return static_cast<int>(origin.size()); }
  int tet_count() const { return mesh.tet_count(); }
  // Corner ids around original vertex o.
  const int* corners_begin(int o) const { return corners.data() + corner_offsets[o]; }
  const int* corners_end(int o) const { return corners.data() + corner_offsets[o + 1]; }
  // Appends a copy of vertex v (same rest and current position) and returns its index.
  int copy_vertex(int v);
};

// Orients every tet positively (swapping two corners where needed), then builds the face
// adjacency and the corners around each vertex. Current positions start at the rest positions.
SplitMesh make_split_mesh(TetMesh mesh);

}  // namespace fissure
