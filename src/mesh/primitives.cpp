// Box, sphere and cylinder: a surface triangulated at edge ≈ λ, then tetrahedralized.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <utility>

#include "core/error.hpp"
#include "mesh/geometry.hpp"
#include "mesh/mesh_util.hpp"

namespace fissure {

namespace {

void require_positive(double value, const char* what) {
  if (!(value > 0.0) || !std::isfinite(value)) {
    throw InputError("", "", fmt::format("{} must be positive and finite, got {}", what, value));
  }
}

// Number of segments of about `edge_length` along `length`, at least `minimum`.
int segments(double length, double edge_length, int minimum) {
  return std::max(minimum, static_cast<int>(std::lround(length / edge_length)));
}

Vec3 normalized(const Vec3& v) {
  const double n = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  return {v[0] / n, v[1] / n, v[2] / n};
}

Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

int add_vertex(SurfaceMesh& s, const Vec3& p) {
  s.vertices.insert(s.vertices.end(), p.begin(), p.end());
  return static_cast<int>(s.vertices.size() / 3) - 1;
}

// Each face is an n_u x n_v grid of squares; grid coordinates are computed per axis so that
// points shared by two faces are bit-identical and get welded.
SurfaceMesh box_surface(const Vec3& lo, const Vec3& hi, double edge_length) {
  std::array<int, 3> n{};
  for (int a = 0; a < 3; ++a) n[a] = segments(hi[a] - lo[a], edge_length, 1);
  const auto coord = [&](int axis, int i) {
    return i == n[axis] ? hi[axis] : lo[axis] + (hi[axis] - lo[axis]) * i / n[axis];
  };
  SurfaceMesh s;
  for (int axis = 0; axis < 3; ++axis) {
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;
    for (int side = 0; side < 2; ++side) {
      const int base = static_cast<int>(s.vertices.size() / 3);
      for (int i = 0; i <= n[u]; ++i) {
        for (int j = 0; j <= n[v]; ++j) {
          Vec3 p{};
          p[axis] = side ? hi[axis] : lo[axis];
          p[u] = coord(u, i);
          p[v] = coord(v, j);
          add_vertex(s, p);
        }
      }
      const auto at = [&](int i, int j) { return base + i * (n[v] + 1) + j; };
      for (int i = 0; i < n[u]; ++i) {
        for (int j = 0; j < n[v]; ++j) {
          // Counter-clockwise in (u, v) faces +axis; flipped on the low side to face outward.
          int q[4] = {at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)};
          if (!side) std::swap(q[1], q[3]);
          s.triangles.insert(s.triangles.end(), {q[0], q[1], q[2], q[0], q[2], q[3]});
        }
      }
    }
  }
  mesh_detail::weld_vertices(s);
  return s;
}

// Geodesic sphere: each icosahedron face split into n^2 triangles, projected on the sphere.
SurfaceMesh sphere_surface(const Vec3& center, double radius, double edge_length) {
  const double phi = (1.0 + std::sqrt(5.0)) / 2.0;
  const std::array<Vec3, 12> corners = {{{-1, phi, 0},
                                         {1, phi, 0},
                                         {-1, -phi, 0},
                                         {1, -phi, 0},
                                         {0, -1, phi},
                                         {0, 1, phi},
                                         {0, -1, -phi},
                                         {0, 1, -phi},
                                         {phi, 0, -1},
                                         {phi, 0, 1},
                                         {-phi, 0, -1},
                                         {-phi, 0, 1}}};
  const int faces[20][3] = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                            {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                            {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                            {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  // Icosahedron edge over circumradius.
  const double edge_ratio = 1.0 / std::sin(2.0 * std::numbers::pi / 5.0);
  const int n = segments(edge_ratio * radius, edge_length, 1);

  SurfaceMesh s;
  const auto project = [&](const Vec3& p) {
    const Vec3 d = normalized(p);
    return Vec3{center[0] + radius * d[0], center[1] + radius * d[1], center[2] + radius * d[2]};
  };
  const auto mix = [&](int a, double wa, int b, double wb, int c, double wc) {
    Vec3 p{};
    for (int k = 0; k < 3; ++k) p[k] = wa * corners[a][k] + wb * corners[b][k] + wc * corners[c][k];
    return project(p);
  };
  std::array<int, 12> corner_index{};
  for (int c = 0; c < 12; ++c) corner_index[c] = add_vertex(s, project(corners[c]));
  // Points on an icosahedron edge are made once, from its lower corner, and shared.
  std::map<std::pair<int, int>, int> edge_start;
  const auto edge_point = [&](int a, int b, int k) {
    if (k == 0) return corner_index[a];
    if (k == n) return corner_index[b];
    if (a > b) {
      std::swap(a, b);
      k = n - k;
    }
    auto [it, inserted] = edge_start.emplace(std::make_pair(a, b), 0);
    if (inserted) {
      it->second = static_cast<int>(s.vertices.size() / 3);
      for (int i = 1; i < n; ++i) add_vertex(s, mix(a, double(n - i), b, double(i), a, 0.0));
    }
    return it->second + k - 1;
  };

  std::vector<int> grid;
  for (const auto& f : faces) {
    const auto at = [&](int i, int j) { return grid[i * (n + 1) + j]; };
    grid.assign((n + 1) * (n + 1), -1);
    for (int i = 0; i <= n; ++i) {
      for (int j = 0; i + j <= n; ++j) {
        int& g = grid[i * (n + 1) + j];
        if (j == 0) {
          g = edge_point(f[0], f[1], i);
        } else if (i == 0) {
          g = edge_point(f[0], f[2], j);
        } else if (i + j == n) {
          g = edge_point(f[1], f[2], j);
        } else {
          g = add_vertex(s, mix(f[0], double(n - i - j), f[1], double(i), f[2], double(j)));
        }
      }
    }
    for (int i = 0; i < n; ++i) {
      for (int j = 0; i + j < n; ++j) {
        s.triangles.insert(s.triangles.end(), {at(i, j), at(i + 1, j), at(i, j + 1)});
        if (i + j + 2 <= n) {
          s.triangles.insert(s.triangles.end(), {at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)});
        }
      }
    }
  }
  return s;
}

// Joins an inner ring (a single centre point if it has one entry) to an outer ring, both
// starting at angle 0, advancing whichever ring's next point comes first in angle.
void stitch_rings(const std::vector<int>& inner, const std::vector<int>& outer, bool flip,
                  std::vector<int>& triangles) {
  const size_t ni = inner.size(), no = outer.size();
  size_t i = 0, j = 0;
  const auto add = [&](int a, int b, int c) {
    if (flip) std::swap(b, c);
    triangles.insert(triangles.end(), {a, b, c});
  };
  while (j < no || (ni > 1 && i < ni)) {
    const bool inner_left = ni > 1 && i < ni;
    if (j < no && (!inner_left || (j + 1) * ni <= (i + 1) * no)) {
      add(inner[i % ni], outer[j], outer[(j + 1) % no]);
      ++j;
    } else {
      add(inner[i], outer[j % no], inner[(i + 1) % ni]);
      ++i;
    }
  }
}

SurfaceMesh cylinder_surface(const Vec3& p0, const Vec3& p1, double radius, double edge_length) {
  const Vec3 d{p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]};
  const double length = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  const Vec3 axis = normalized(d);
  // (u, v, axis) is a right-handed orthonormal frame.
  int least = 0;
  for (int k = 1; k < 3; ++k) least = std::abs(axis[k]) < std::abs(axis[least]) ? k : least;
  Vec3 e{};
  e[least] = 1.0;
  const Vec3 u = normalized(cross(e, axis));
  const Vec3 v = cross(axis, u);

  const int around = segments(2.0 * std::numbers::pi * radius, edge_length, 6);
  const int layers = segments(length, edge_length, 1);
  const int rings = segments(radius, edge_length, 1);

  SurfaceMesh s;
  const auto ring = [&](double z, double rho, int count) {
    std::vector<int> indices(count);
    for (int k = 0; k < count; ++k) {
      const double theta = 2.0 * std::numbers::pi * k / count;
      const double cu = rho * std::cos(theta), cv = rho * std::sin(theta);
      Vec3 p{};
      for (int c = 0; c < 3; ++c) p[c] = p0[c] + axis[c] * z + u[c] * cu + v[c] * cv;
      indices[k] = add_vertex(s, p);
    }
    return indices;
  };

  std::vector<std::vector<int>> side;
  for (int l = 0; l <= layers; ++l) side.push_back(ring(length * l / layers, radius, around));
  for (int l = 0; l < layers; ++l) {
    for (int k = 0; k < around; ++k) {
      const int k1 = (k + 1) % around;
      const int q00 = side[l][k], q10 = side[l][k1], q01 = side[l + 1][k], q11 = side[l + 1][k1];
      s.triangles.insert(s.triangles.end(), {q00, q10, q11, q00, q11, q01});
    }
  }
  // Caps: concentric rings of about λ spacing, the innermost being the centre point.
  for (int end = 0; end < 2; ++end) {
    const double z = end ? length : 0.0;
    std::vector<int> inner = ring(z, 0.0, 1);
    for (int r = 1; r <= rings; ++r) {
      const int count =
          std::min(around, segments(2.0 * std::numbers::pi * radius * r / rings, edge_length, 6));
      std::vector<int> outer =
          r == rings ? side[end ? layers : 0] : ring(z, radius * r / rings, count);
      stitch_rings(inner, outer, end == 0, s.triangles);
      inner = std::move(outer);
    }
  }
  return s;
}

}  // namespace

TetMesh tetrahedralize_box(const Vec3& min, const Vec3& max, double edge_length) {
  require_positive(edge_length, "box edge length");
  Vec3 size{};
  for (int a = 0; a < 3; ++a) {
    if (!(max[a] > min[a]) || !std::isfinite(min[a]) || !std::isfinite(max[a])) {
      throw InputError("", "", "box max must exceed box min in every coordinate");
    }
    size[a] = max[a] - min[a];
  }
  mesh_detail::check_tet_budget(size[0] * size[1] * size[2],
                                2.0 * (size[0] * size[1] + size[1] * size[2] + size[2] * size[0]),
                                edge_length, "");
  return mesh_detail::tetrahedralize_primitive(box_surface({0, 0, 0}, size, edge_length),
                                               edge_length, min);
}

TetMesh tetrahedralize_sphere(const Vec3& center, double radius, double edge_length) {
  require_positive(edge_length, "sphere edge length");
  require_positive(radius, "sphere radius");
  for (double c : center) {
    if (!std::isfinite(c)) throw InputError("", "", "sphere center must be finite");
  }
  mesh_detail::check_tet_budget(4.0 / 3.0 * std::numbers::pi * radius * radius * radius,
                                4.0 * std::numbers::pi * radius * radius, edge_length, "");
  return mesh_detail::tetrahedralize_primitive(sphere_surface({0, 0, 0}, radius, edge_length),
                                               edge_length, center);
}

TetMesh tetrahedralize_cylinder(const Vec3& p0, const Vec3& p1, double radius, double edge_length) {
  require_positive(edge_length, "cylinder edge length");
  require_positive(radius, "cylinder radius");
  for (int a = 0; a < 3; ++a) {
    if (!std::isfinite(p0[a]) || !std::isfinite(p1[a])) {
      throw InputError("", "", "cylinder end points must be finite");
    }
  }
  const double length = std::hypot(p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]);
  require_positive(length, "cylinder length (distance between end points)");
  mesh_detail::check_tet_budget(std::numbers::pi * radius * radius * length,
                                2.0 * std::numbers::pi * radius * (radius + length), edge_length,
                                "");
  const Vec3 axis{p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]};
  return mesh_detail::tetrahedralize_primitive(
      cylinder_surface({0, 0, 0}, axis, radius, edge_length), edge_length, p0);
}

}  // namespace fissure
