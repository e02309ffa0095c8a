#include "render/field_colors.hpp"

#include <algorithm>
#include <cmath>

namespace fissure {

std::vector<double> field_values(const VtuGrid& grid, const std::string& field) {
  const auto n = static_cast<std::size_t>(grid.point_count());
  std::vector<double> values(n, 0.0);
  const auto found = grid.point_data.find(field);
  if (found == grid.point_data.end()) return values;
  const VtuArray& a = found->second;
  for (std::size_t i = 0; i < n; ++i) {
    double sum = 0;
    for (int k = 0; k < a.components; ++k)
      sum += a.values[a.components * i + k] * a.values[a.components * i + k];
    values[i] = a.components == 1 ? a.values[i] : std::sqrt(sum);
  }
  return values;
}

bool field_signed(const std::string& field) { return field == "dilatation"; }

std::array<double, 3> cool_warm(double t) {
  // Control points of Moreland's diverging map, at t = 0, 0.25, 0.5, 0.75, 1.
  static constexpr double points[5][3] = {{0.230, 0.299, 0.754},
                                          {0.552, 0.690, 0.996},
                                          {0.866, 0.866, 0.866},
                                          {0.957, 0.604, 0.482},
                                          {0.706, 0.016, 0.150}};
  const double x = std::clamp(std::isfinite(t) ? t : 0.0, 0.0, 1.0) * 4;
  const int k = std::min(static_cast<int>(x), 3);
  const double f = x - k;
  return {points[k][0] + f * (points[k + 1][0] - points[k][0]),
          points[k][1] + f * (points[k + 1][1] - points[k][1]),
          points[k][2] + f * (points[k + 1][2] - points[k][2])};
}

}  // namespace fissure
