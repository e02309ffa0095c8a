#include "mesh/vertex_split.hpp"

#include <cstddef>
#include <numeric>

namespace fissure {

int VertexSplitter::root(int s) {
  while (parent_[s] != s) s = parent_[s] = parent_[parent_[s]];
  return s;
}

int VertexSplitter::split_vertex(SplitMesh& mesh, int v, CrackFaces* cracks) {
  std::vector<int>& tets = mesh.mesh.tets;
  star_.clear();
  for (const int* c = mesh.corners_begin(mesh.origin[v]); c != mesh.corners_end(mesh.origin[v]);
       ++c)
    if (tets[*c] == v) {
      slot_[*c / 4] = static_cast<int>(star_.size());
      star_.push_back(*c);
    }
  const int size = static_cast<int>(star_.size());
  // Join the tets of the star across their uncracked faces at v (the three faces other than the
  // one opposite v) whose other tet is also around v.
  parent_.resize(size);
  std::iota(parent_.begin(), parent_.end(), 0);
  for (int s = 0; s < size; ++s) {
    const int t = star_[s] / 4, corner = star_[s] % 4;
    for (int k = 0; k < 4; ++k) {
      const int face = 4 * t + k;
      if (k == corner || mesh.across[face] < 0 || (cracks && cracks->cracked(face))) continue;
      const int other = slot_[mesh.across[face] / 4];
      if (other >= 0) parent_[root(s)] = root(other);
    }
  }
  // The group of the first tet keeps v; every other group gets a copy.
  copy_.assign(size, -1);
  int copies = 0;
  for (int s = 0; s < size; ++s) {
    int& copy = copy_[root(s)];
    if (copy < 0) {
      copy = s == 0 ? v : mesh.copy_vertex(v);
      copies += s != 0;
    }
    tets[star_[s]] = copy;
  }
  if (copies > 0 && cracks)
    for (int s = 0; s < size; ++s) {
      const int t = star_[s] / 4, corner = star_[s] % 4;
      for (int k = 0; k < 4; ++k) {
        const int face = 4 * t + k;
        if (k == corner || !cracks->active(face)) continue;
        const int other = slot_[mesh.across[face] / 4];
        if (other >= 0 && root(other) != root(s)) cracks->retire(face, mesh.across[face]);
      }
    }
  for (int c : star_) slot_[c / 4] = -1;
  return copies;
}

int VertexSplitter::split_cracked(SplitMesh& mesh, CrackFaces& cracks) {
  const std::vector<int>& set = cracks.set();
  if (cracks.fresh_begin() == set.size()) return 0;
  ++pass_;
  seen_.resize(mesh.vertex_count(), 0);
  candidates_.clear();
  for (std::size_t i = cracks.fresh_begin(); i < set.size(); ++i) {
    const int t = set[i] / 4, opposite = set[i] % 4;
    for (int c = 0; c < 4; ++c) {
      const int v = mesh.mesh.tets[4 * static_cast<std::size_t>(t) + c];
      if (c == opposite || seen_[v] == pass_) continue;
      seen_[v] = pass_;
      candidates_.push_back(v);
    }
  }
  int copies = 0;
  for (int v : candidates_) copies += split_vertex(mesh, v, &cracks);
  cracks.end_pass();
  return copies;
}

int VertexSplitter::split_all(SplitMesh& mesh, CrackFaces* cracks) {
  int copies = 0;
  const int n = mesh.vertex_count();
  for (int v = 0; v < n; ++v) copies += split_vertex(mesh, v, cracks);
  if (cracks) cracks->end_pass();
  return copies;
}

}  // namespace fissure
