#pragma once
// The boundary surface of a split tet mesh: every face not shared, with the same three vertices,
// by the tet across it. It holds the original surface and the crack faces that have opened (a
// vertex of theirs split); a crack face whose tets still share all three vertices stays closed.
#include <cstdint>
#include <vector>

#include "mesh/split_mesh.hpp"

namespace fissure {

struct BoundarySurface {
  std::vector<int> triangles;       // 3 vertex ids per triangle, normal pointing out of its tet
  std::vector<int> tet;             // the tet each triangle bounds
  std::vector<std::uint8_t> crack;  // 1 for an interior face of the original mesh (crack surface)
  int triangle_count() const { return static_cast<int>(tet.size()); }
};

BoundarySurface extract_boundary(const SplitMesh& mesh);

}  // namespace fissure
