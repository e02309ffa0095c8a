#pragma once
// The deformed geometry of a bond, shared by the assembled tangent (lps_stiffness.cpp) and the
// matrix-free one's linearization (lps_tangent_product.cpp) so that both see the same ℓ and decide
// alike which bonds are collapsed; the product's row kernels recompute n as d (1/ℓ) with the same
// test (lps_rows.hpp), equal to this n to round-off.
#include <array>
#include <cmath>

#include "model/lps_rows.hpp"
#include "model/model.hpp"

namespace fissure {

// Unit bond direction n and deformed length ℓ; a collapsed bond keeps its reference direction.
struct BondGeometry {
  std::array<double, 3> n;
  double length;
};

inline BondGeometry bond_geometry(const double* y, const Particles& p, int i, int j, double xi) {
  std::array<double, 3> d{y[3 * j] - y[3 * i], y[3 * j + 1] - y[3 * i + 1],
                          y[3 * j + 2] - y[3 * i + 2]};
  double length = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  if (length <= lps::kCollapsedBond * xi) {
    d = reference_vector(p, i, j);
    length = 0;
  }
  const double norm = length > 0 ? length : xi;
  return {{d[0] / norm, d[1] / norm, d[2] / norm}, length};
}

}  // namespace fissure
