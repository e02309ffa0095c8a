#pragma once
// A k-d tree (nanoflann) over points stored xyz interleaved, as Particles::reference holds them.
#include <cstddef>
#include <cstdint>
#include <nanoflann.hpp>
#include <vector>

namespace fissure {

struct PointCloud {
  const std::vector<double>& xyz;
  std::size_t kdtree_get_point_count() const { return xyz.size() / 3; }
  double kdtree_get_pt(std::size_t i, std::size_t dim) const { return xyz[3 * i + dim]; }
  template <class Box>
  bool kdtree_get_bbox(Box&) const {
    return false;
  }
};

using KdTree = nanoflann::KDTreeSingleIndexAdaptor<
    nanoflann::L2_Simple_Adaptor<double, PointCloud, double, std::uint32_t>, PointCloud, 3,
    std::uint32_t>;

}  // namespace fissure
