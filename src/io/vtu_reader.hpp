#pragma once
// Reads VTK unstructured-grid files in the binary appended raw form that src/io/vtu_writer.cpp
// writes (uncompressed, little endian, UInt32 or UInt64 block headers).
#include <map>
#include <string>
#include <vector>

namespace fissure {

struct VtuArray {
  int components = 1;
  std::vector<double> values;  // components × count
};

struct VtuGrid {
  std::vector<double> points;  // xyz interleaved
  std::vector<long> connectivity, offsets;
  std::map<std::string, VtuArray> point_data;
  long point_count() const { return static_cast<long>(points.size() / 3); }
};

// Throws InputError naming the file when it cannot be read or is not in that form. A .pvtu (a
// frame of a run over several ranks) is read as its pieces joined in the order it lists them.
VtuGrid read_vtu(const std::string& path);

}  // namespace fissure
