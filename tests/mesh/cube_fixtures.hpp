#pragma once
// The unit cube in every supported surface format, as file contents.
#include <cstdint>
#include <cstring>
#include <string>

#include "mesh_test_util.hpp"

namespace fissure::test {

template <class T>
void append_bytes(std::string& out, T value) {
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  out.append(bytes, sizeof(T));
}

// Quads with v/vt/vn, v//vn and negative (relative) indices.
inline std::string cube_obj() {
  return "# unit cube\no cube\n"
         "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
         "vt 0 0\nvn 0 0 1\ns off\n"
         "f 1/1/1 4/1/1 3/1/1 2/1/1\n"
         "f 5//1 6//1 7//1 8//1\n"
         "f 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\n"
         "f -5 -8 -4 -1\n";
}

inline std::string cube_off() {
  return "OFF\n# unit cube\n8 6 12\n"
         "0 0 0\n1 0 0\n1 1 0\n0 1 0\n0 0 1\n1 0 1\n1 1 1\n0 1 1\n"
         "4 0 3 2 1\n4 4 5 6 7\n4 0 1 5 4\n4 1 2 6 5\n4 2 3 7 6\n4 3 0 4 7\n";
}

// Quads, an extra vertex property and an extra element, all to be skipped.
inline std::string cube_ply_ascii() {
  return "ply\nformat ascii 1.0\ncomment unit cube\n"
         "element vertex 8\nproperty double x\nproperty double y\nproperty double z\n"
         "property uchar red\n"
         "element face 6\nproperty list uchar int vertex_indices\n"
         "element edge 1\nproperty int vertex1\nproperty int vertex2\n"
         "end_header\n"
         "0 0 0 1\n1 0 0 1\n1 1 0 1\n0 1 0 1\n0 0 1 1\n1 0 1 1\n1 1 1 1\n0 1 1 1\n"
         "4 0 3 2 1\n4 4 5 6 7\n4 0 1 5 4\n4 1 2 6 5\n4 2 3 7 6\n4 3 0 4 7\n"
         "0 1\n";
}

inline std::string cube_ply_binary() {
  std::string out =
      "ply\nformat binary_little_endian 1.0\n"
      "element vertex 8\nproperty float x\nproperty float y\nproperty float z\n"
      "property uchar quality\n"
      "element face 12\nproperty list uchar int vertex_indices\n"
      "end_header\n";
  for (const auto& v : kCubeVertices) {
    for (double x : v) append_bytes(out, static_cast<float>(x));
    append_bytes(out, uint8_t{7});
  }
  for (const auto& t : kCubeTriangles) {
    append_bytes(out, uint8_t{3});
    for (int i : t) append_bytes(out, int32_t{i});
  }
  return out;
}

inline std::string cube_stl_ascii() {
  std::string out = "solid cube\n";
  for (const auto& t : kCubeTriangles) {
    out += "  facet normal 0 0 0\n    outer loop\n";
    for (int i : t) {
      const double* v = kCubeVertices[i];
      out += "      vertex " + std::to_string(v[0]) + " " + std::to_string(v[1]) + " " +
             std::to_string(v[2]) + "\n";
    }
    out += "    endloop\n  endfacet\n";
  }
  return out + "endsolid cube\n";
}

// The 80-byte header starts with "solid", as some exporters write it.
inline std::string cube_stl_binary() {
  std::string out = "solid binary cube";
  out.resize(80, ' ');
  append_bytes(out, uint32_t{12});
  for (const auto& t : kCubeTriangles) {
    for (int k = 0; k < 3; ++k) append_bytes(out, 0.0f);
    for (int i : t) {
      for (double x : kCubeVertices[i]) append_bytes(out, static_cast<float>(x));
    }
    append_bytes(out, uint16_t{0});
  }
  return out;
}

}  // namespace fissure::test
