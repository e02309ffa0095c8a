#include "scene/scene.hpp"

#include <fmt/format.h>

#include <cmath>

#include "core/error.hpp"
#include "mesh/geometry.hpp"
#include "scene/points_file.hpp"

namespace fissure {

namespace {

TetMesh tetrahedralize_body(const Body& body, const std::string& key) {
  const Geometry& g = body.geometry;
  const double lambda = body.resolution;
  try {
    switch (g.kind) {
      case Geometry::Kind::box:
        return tetrahedralize_box(g.min, g.max, lambda);
      case Geometry::Kind::sphere:
        return tetrahedralize_sphere(g.center, g.radius, lambda);
      case Geometry::Kind::cylinder:
        return tetrahedralize_cylinder(g.p0, g.p1, g.radius, lambda);
      case Geometry::Kind::mesh: {
        TetMesh mesh = load_mesh_file(g.file, lambda / g.scale);
        for (std::size_t k = 0; k < mesh.vertices.size(); ++k)
          mesh.vertices[k] = g.scale * mesh.vertices[k] + g.translate[k % 3];
        return mesh;
      }
      case Geometry::Kind::points:
        break;
    }
  } catch (const InputError& e) {
    throw InputError(e.file(), key, e.reason());
  }
  return {};
}

// One particle per tet at its barycentre, with the tet's volume and mass (paper §5.2).
void add_tet_particles(const TetMesh& mesh, int body_index, const Body& body, Particles& p) {
  for (int t = 0; t < mesh.tet_count(); ++t) {
    const double* v[4];
    for (int c = 0; c < 4; ++c) v[c] = &mesh.vertices[3 * mesh.tets[4 * t + c]];
    double a[3], b[3], d[3];
    for (int k = 0; k < 3; ++k) {
      a[k] = v[1][k] - v[0][k];
      b[k] = v[2][k] - v[0][k];
      d[k] = v[3][k] - v[0][k];
    }
    const double volume =
        std::abs(a[0] * (b[1] * d[2] - b[2] * d[1]) - a[1] * (b[0] * d[2] - b[2] * d[0]) +
                 a[2] * (b[0] * d[1] - b[1] * d[0])) /
        6.0;
    if (!(volume > 0)) continue;
    for (int k = 0; k < 3; ++k) {
      p.reference.push_back(0.25 * (v[0][k] + v[1][k] + v[2][k] + v[3][k]));
      p.velocity.push_back(body.velocity[k]);
    }
    p.volume.push_back(volume);
    p.mass.push_back(body.material.density * volume);
    p.body.push_back(body_index);
  }
}

void add_point_particles(const Body& body, int body_index, const std::string& key, Particles& p) {
  PointSet points;
  try {
    points = read_points_file(body.geometry.file);
  } catch (const InputError& e) {
    throw InputError(e.file(), key, e.reason());
  }
  const double s = body.geometry.scale;
  for (std::size_t i = 0; i < points.volume.size(); ++i) {
    for (int k = 0; k < 3; ++k) {
      p.reference.push_back(s * points.position[3 * i + k] + body.geometry.translate[k]);
      p.velocity.push_back(points.velocity.empty() ? body.velocity[k] : points.velocity[3 * i + k]);
    }
    const double volume = s * s * s * points.volume[i];
    p.volume.push_back(volume);
    p.mass.push_back(body.material.density * volume);
    p.body.push_back(body_index);
  }
}

}  // namespace

Scene build_scene(const Config& config) {
  Scene scene;
  scene.config = config;
  double smallest_horizon = 0;
  for (std::size_t b = 0; b < config.bodies.size(); ++b) {
    const Body& body = config.bodies[b];
    const std::string key = fmt::format("bodies[{}].geometry", b);
    const int before = scene.particles.count();
    if (body.geometry.kind == Geometry::Kind::points)
      add_point_particles(body, static_cast<int>(b), key, scene.particles);
    else
      add_tet_particles(tetrahedralize_body(body, key), static_cast<int>(b), body, scene.particles);
    if (scene.particles.count() == before)
      throw InputError(config.file, key,
                       fmt::format("body '{}' has no particles (is the geometry smaller than "
                                   "the resolution?)",
                                   body.name));
    const double delta = body.horizon * body.resolution;
    scene.horizon_of_body.push_back(delta);
    smallest_horizon = b == 0 ? delta : std::min(smallest_horizon, delta);
  }
  sort_spatially(scene.particles, 0.5 * smallest_horizon);
  scene.families = build_families(scene.particles, scene.horizon_of_body);
  return scene;
}

}  // namespace fissure
