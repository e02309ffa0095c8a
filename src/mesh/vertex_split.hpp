#pragma once
// Vertex splitting along crack faces (paper §5.2). The tets around a vertex fall into groups
// joined through their uncracked faces; where there are k ≥ 2 groups, the vertex becomes k
// copies, each group's corners re-pointed to its own copy, and the crack faces between two groups
// are retired from the crack-face set.
#include <vector>

#include "mesh/crack_faces.hpp"
#include "mesh/split_mesh.hpp"

namespace fissure {

class VertexSplitter {
 public:
  explicit VertexSplitter(int tet_count) : slot_(tet_count, -1) {}

  // Examines the vertices of the crack faces added since the last pass, then ends the pass.
  // Only those can split: the grouping around a vertex changes only when a face at that vertex
  // cracks. Several vertices of one face may split in the same pass. Returns the copies made.
  int split_cracked(SplitMesh& mesh, CrackFaces& cracks);
  // Examines every vertex (at set-up: a non-manifold input or initial cracks); `cracks` may be
  // null when nothing is cracked. Returns the copies made.
  int split_all(SplitMesh& mesh, CrackFaces* cracks);
  // Splits vertex v into one copy per group of its tets; returns the copies made (k − 1).
  int split_vertex(SplitMesh& mesh, int v, CrackFaces* cracks);

 private:
  int root(int s);

  std::vector<int> slot_;    // per tet: its index in star_ while its vertex is examined, else −1
  std::vector<int> star_;    // corner ids 4 t + c at the examined vertex
  std::vector<int> parent_;  // union-find over star_
  std::vector<int> copy_;    // per group root: the vertex its tets get
  std::vector<int> candidates_;
  std::vector<int> seen_;  // per vertex: the last pass that queued it
  int pass_ = 0;
};

}  // namespace fissure
