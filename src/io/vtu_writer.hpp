#pragma once
// Particle frames as VTK unstructured grids (one vertex cell per particle), binary appended,
// readable by ParaView.
#include <string>
#include <vector>

namespace fissure {

struct PointField {
  std::string name;
  int components;                     // 1 or 3
  const std::vector<double>* values;  // components * point count
};

void write_particles_vtu(const std::string& path, const std::vector<double>& points,
                         const std::vector<PointField>& fields,
                         const std::vector<int>* body_id = nullptr);

// The ParaView collection file listing every frame written so far; rewritten atomically.
class PvdIndex {
 public:
  explicit PvdIndex(std::string path) : path_(std::move(path)) {}
  void add(double time, const std::string& relative_file);

 private:
  std::string path_;
  std::vector<std::pair<double, std::string>> frames_;
};

}  // namespace fissure
