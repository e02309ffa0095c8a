#pragma once
// Particles read directly from text: "x y z volume [vx vy vz]" per line, '#' starts a comment.
#include <string>
#include <vector>

namespace fissure {

struct PointSet {
  std::vector<double> position;  // 3 * count
  std::vector<double> volume;
  std::vector<double> velocity;  // 3 * count, or empty when the file gives none
};

PointSet read_points_file(const std::string& path);

}  // namespace fissure
