// The embedded mesh's splitting cost per step (paper §5.2) against the number of crack
// faces and the mesh size. A zig-zag crack (every face between tets whose barycentres lie on
// both sides of x = 0.5) grows through TetGen boxes of three sizes, `per_step` faces per step;
// each step runs the vertex-splitting pass. Prints one line per mesh and crack rate: tets,
// new crack faces per step, crack faces at the end, microseconds per step (mean, and over the
// first and last tenth of the steps) and nanoseconds per new crack face.
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <vector>

#include "mesh/crack_faces.hpp"
#include "mesh/geometry.hpp"
#include "mesh/split_mesh.hpp"
#include "mesh/vertex_split.hpp"

namespace {

using Clock = std::chrono::steady_clock;

double x_centre(const fissure::SplitMesh& s, int t) {
  double x = 0;
  for (int q = 0; q < 4; ++q) x += 0.25 * s.mesh.vertices[3 * s.mesh.tets[4 * t + q]];
  return x;
}

// The faces of the crack, ordered along y then z so that it grows as a front.
std::vector<int> crack_front(const fissure::SplitMesh& s) {
  std::vector<int> faces;
  for (int f = 0; f < 4 * s.tet_count(); ++f)
    if (s.across[f] > f && (x_centre(s, f / 4) < 0.5) != (x_centre(s, s.across[f] / 4) < 0.5))
      faces.push_back(f);
  auto key = [&](int f) {
    const int* tet = &s.mesh.tets[4 * (f / 4)];
    return s.mesh.vertices[3 * tet[0] + 1] + 1e-3 * s.mesh.vertices[3 * tet[0] + 2];
  };
  std::sort(faces.begin(), faces.end(), [&](int a, int b) { return key(a) < key(b); });
  return faces;
}

void run(const fissure::TetMesh& box, int per_step) {
  fissure::SplitMesh s = fissure::make_split_mesh(box);
  fissure::CrackFaces cracks(s.tet_count());
  fissure::VertexSplitter splitter(s.tet_count());
  const std::vector<int> faces = crack_front(s);
  std::vector<double> step_seconds;
  for (std::size_t begin = 0; begin < faces.size(); begin += per_step) {
    const std::size_t end = std::min(faces.size(), begin + per_step);
    for (std::size_t i = begin; i < end; ++i) cracks.add(faces[i], s.across[faces[i]]);
    const auto start = Clock::now();
    splitter.split_cracked(s, cracks);
    step_seconds.push_back(std::chrono::duration<double>(Clock::now() - start).count());
  }
  const std::size_t steps = step_seconds.size(), tenth = std::max<std::size_t>(1, steps / 10);
  auto mean_us = [&](std::size_t from, std::size_t to) {
    double sum = 0;
    for (std::size_t i = from; i < to; ++i) sum += step_seconds[i];
    return 1e6 * sum / static_cast<double>(to - from);
  };
  const double total = mean_us(0, steps) * static_cast<double>(steps);
  fmt::print("{:>8} {:>10} {:>12} {:>12} {:>8.1f} {:>10.1f} {:>10.1f} {:>10.0f}\n", s.tet_count(),
             per_step, cracks.total(), s.vertex_count() - box.vertex_count(), mean_us(0, steps),
             mean_us(0, tenth), mean_us(steps - tenth, steps),
             1e3 * total / static_cast<double>(faces.size()));
}

}  // namespace

int main() {
  fmt::print("{:>8} {:>10} {:>12} {:>12} {:>8} {:>10} {:>10} {:>10}\n", "tets", "new/step",
             "crack_faces", "copies", "us/step", "us_first", "us_last", "ns/face");
  for (double lambda : {0.1, 0.05, 0.025}) {
    const fissure::TetMesh box = fissure::tetrahedralize_box({0, 0, 0}, {1, 1, 1}, lambda);
    for (int per_step : {1, 10, 100}) run(box, per_step);
  }
}
