#include "scene/points_file.hpp"

#include <fmt/format.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "core/error.hpp"

namespace fissure {

PointSet read_points_file(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path, "", "cannot open the points file");
  PointSet points;
  std::string line;
  int line_number = 0;
  int columns_seen = 0;
  while (std::getline(in, line)) {
    ++line_number;
    if (const auto hash = line.find('#'); hash != std::string::npos) line.resize(hash);
    std::istringstream fields(line);
    std::vector<double> values;
    std::string token;
    while (fields >> token) {
      std::size_t used = 0;
      double v = 0;
      try {
        v = std::stod(token, &used);
      } catch (const std::exception&) {
        used = 0;
      }
      if (used != token.size())
        throw InputError(path, "",
                         fmt::format("line {}: '{}' is not a number", line_number, token));
      if (!std::isfinite(v))
        throw InputError(path, "", fmt::format("line {}: non-finite value", line_number));
      values.push_back(v);
    }
    if (values.empty()) continue;
    const int columns = static_cast<int>(values.size());
    if (columns != 4 && columns != 7)
      throw InputError(path, "",
                       fmt::format("line {}: expected 4 (x y z volume) or 7 "
                                   "(x y z volume vx vy vz) columns, got {}",
                                   line_number, columns));
    if (columns_seen != 0 && columns != columns_seen)
      throw InputError(path, "",
                       fmt::format("line {}: {} columns where earlier lines have {}", line_number,
                                   columns, columns_seen));
    columns_seen = columns;
    if (values[3] <= 0)
      throw InputError(path, "", fmt::format("line {}: volume must be positive", line_number));
    points.position.insert(points.position.end(), values.begin(), values.begin() + 3);
    points.volume.push_back(values[3]);
    if (columns == 7)
      points.velocity.insert(points.velocity.end(), values.begin() + 4, values.end());
  }
  if (points.volume.empty()) throw InputError(path, "", "the points file holds no particles");
  return points;
}

}  // namespace fissure
