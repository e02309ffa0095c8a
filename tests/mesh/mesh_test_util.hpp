#pragma once
// Mesh measures, a unit-cube fixture and a per-test temp directory for the mesh tests, and
// expect_input_error (support/error_message.hpp).
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "mesh/tet_mesh.hpp"
#include "support/error_message.hpp"

namespace fissure::test {

inline double tet_volume(const TetMesh& m, int t) {
  const int* q = &m.tets[4 * static_cast<size_t>(t)];
  const double* a = &m.vertices[3 * q[0]];
  double e[3][3];
  for (int k = 0; k < 3; ++k) {
    for (int c = 0; c < 3; ++c) e[k][c] = m.vertices[3 * q[k + 1] + c] - a[c];
  }
  return (e[0][0] * (e[1][1] * e[2][2] - e[1][2] * e[2][1]) -
          e[0][1] * (e[1][0] * e[2][2] - e[1][2] * e[2][0]) +
          e[0][2] * (e[1][0] * e[2][1] - e[1][1] * e[2][0])) /
         6.0;
}

inline double total_volume(const TetMesh& m) {
  double sum = 0.0;
  for (int t = 0; t < m.tet_count(); ++t) sum += tet_volume(m, t);
  return sum;
}

inline double min_volume(const TetMesh& m) {
  double least = INFINITY;
  for (int t = 0; t < m.tet_count(); ++t) least = std::min(least, tet_volume(m, t));
  return least;
}

// Mean length over the distinct edges of the mesh.
inline double mean_edge_length(const TetMesh& m) {
  std::vector<std::pair<int, int>> edges;
  for (size_t t = 0; t < m.tets.size(); t += 4) {
    for (int a = 0; a < 4; ++a) {
      for (int b = a + 1; b < 4; ++b) {
        edges.emplace_back(std::min(m.tets[t + a], m.tets[t + b]),
                           std::max(m.tets[t + a], m.tets[t + b]));
      }
    }
  }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  double sum = 0.0;
  for (const auto& [i, j] : edges) {
    const double* p = &m.vertices[3 * i];
    const double* q = &m.vertices[3 * j];
    sum += std::hypot(p[0] - q[0], p[1] - q[1], p[2] - q[2]);
  }
  return sum / static_cast<double>(edges.size());
}

// Unit cube [0,1]^3: 8 corners and 12 triangles (0-based).
inline const double kCubeVertices[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                                           {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
inline const int kCubeTriangles[12][3] = {{0, 2, 1}, {0, 3, 2}, {4, 5, 6}, {4, 6, 7},
                                          {0, 1, 5}, {0, 5, 4}, {1, 2, 6}, {1, 6, 5},
                                          {2, 3, 7}, {2, 7, 6}, {3, 0, 4}, {3, 4, 7}};

inline SurfaceMesh cube_surface() {
  SurfaceMesh s;
  for (const auto& v : kCubeVertices) s.vertices.insert(s.vertices.end(), v, v + 3);
  for (const auto& t : kCubeTriangles) s.triangles.insert(s.triangles.end(), t, t + 3);
  return s;
}

// Gives each test an empty directory for its fixture files, removed afterwards.
class MeshFileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("fissure_mesh_" + std::to_string(getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  std::string path(const std::string& name) const { return (dir_ / name).string(); }

  std::string write(const std::string& name, std::string_view contents) const {
    std::ofstream out(path(name), std::ios::binary);
    out.write(contents.data(), static_cast<std::streamsize>(contents.size()));
    return path(name);
  }

  std::filesystem::path dir_;
};

}  // namespace fissure::test
