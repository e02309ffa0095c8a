#include "model/stiffness.hpp"

#include "linear/sparse_symmetric.hpp"

namespace fissure {

SparseSymmetric Stiffness::tangent_pattern(const Families& families) const {
  return two_hop_pattern(families);
}

}  // namespace fissure
