#pragma once
// Particle frames as VTK unstructured grids (one vertex cell per particle), binary appended,
// readable by ParaView.
#include <cstdint>
#include <string>
#include <vector>

namespace fissure {

struct PointField {
  std::string name;
  int components;                     // 1 or 3
  const std::vector<double>* values;  // components * point count
};

// One data array of a grid: a VTK type name ("Float64", "Int32"), its components, its bytes.
struct VtuArray {
  std::string type;
  std::string name;
  int components;
  const void* data;
  std::uint64_t bytes;
};

// An unstructured grid of `points` (xyz) and cells of `corners` points each, of VTK cell type
// `vtk_type`, with per-point and per-cell arrays; binary, appended raw, written atomically.
void write_vtu(const std::string& path, const std::vector<double>& points,
               const std::vector<std::int32_t>& connectivity, int corners, std::uint8_t vtk_type,
               const std::vector<VtuArray>& point_data, const std::vector<VtuArray>& cell_data);

// Particles as vertex cells.
void write_particles_vtu(const std::string& path, const std::vector<double>& points,
                         const std::vector<PointField>& fields,
                         const std::vector<int>* body_id = nullptr);

// The parallel file (.pvtu) that joins the pieces `pieces` (file names relative to it) of a
// frame written with write_particles_vtu by several ranks, with the same `fields` and body ids.
void write_particles_pvtu(const std::string& path, const std::vector<std::string>& pieces,
                          const std::vector<PointField>& fields, bool body_id);

// The ParaView collection file listing every frame written so far; rewritten atomically.
class PvdIndex {
 public:
  explicit PvdIndex(std::string path) : path_(std::move(path)) {}
  void add(double time, const std::string& relative_file);
  // Replaces the list (a resumed run: the frames up to its checkpoint) and rewrites the file.
  void reset(std::vector<std::pair<double, std::string>> frames);

 private:
  void write() const;

  std::string path_;
  std::vector<std::pair<double, std::string>> frames_;
};

}  // namespace fissure
