#include "scene/scene.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "core/error.hpp"
#include "mesh/geometry.hpp"
#include "scene/points_file.hpp"

namespace fissure {

namespace {

// Tetrahedralizes a box, sphere, cylinder or mesh body at its resolution λ.
TetMesh tetrahedralize_body(const Body& body, const std::string& config_file, std::size_t index) {
  const Geometry& g = body.geometry;
  const double lambda = body.resolution;
  try {
    if (g.kind == Geometry::Kind::box) return tetrahedralize_box(g.min, g.max, lambda);
    if (g.kind == Geometry::Kind::sphere) return tetrahedralize_sphere(g.center, g.radius, lambda);
    if (g.kind == Geometry::Kind::cylinder)
      return tetrahedralize_cylinder(g.p0, g.p1, g.radius, lambda);
    TetMesh mesh = load_mesh_file(g.file, lambda / g.scale);
    for (std::size_t k = 0; k < mesh.vertices.size(); ++k)
      mesh.vertices[k] = g.scale * mesh.vertices[k] + g.translate[k % 3];
    return mesh;
  } catch (const InputError& e) {
    // A primitive has no file of its own: its errors are about the resolution in the config.
    if (e.file().empty())
      throw InputError(config_file, fmt::format("bodies[{}].resolution", index), e.reason());
    throw InputError(e.file(), fmt::format("bodies[{}].geometry", index), e.reason());
  }
}

// One particle per tet at its barycentre, with the tet's volume and mass (paper §5.2). Returns
// the particle of each tet, −1 for a tet without volume.
std::vector<int> add_tet_particles(const TetMesh& mesh, int body_index, const Body& body,
                                   Particles& p) {
  std::vector<int> particle(mesh.tet_count(), -1);
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
    particle[t] = p.count();
    for (int k = 0; k < 3; ++k) {
      p.reference.push_back(0.25 * (v[0][k] + v[1][k] + v[2][k] + v[3][k]));
      p.velocity.push_back(body.velocity[k]);
    }
    p.volume.push_back(volume);
    p.mass.push_back(body.material.density * volume);
    p.body.push_back(body_index);
  }
  return particle;
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

// Every particle needs a family, and no two particles may coincide (a zero-length bond has no
// direction, and near-coincident ones would make the stable step vanish). `members(i)` is the
// size of i's family and `nearest(i)` the distance to its nearest member.
template <class Members, class Nearest>
void check_families(const Scene& scene, Members members, Nearest nearest) {
  const Particles& p = scene.particles;
  for (int i = 0; i < p.count(); ++i) {
    const int body = p.body[i];
    const double delta = scene.horizon_of_body[body];
    const double* x = &p.reference[3 * i];
    if (members(i) == 0)
      throw InputError(scene.config.file, fmt::format("bodies[{}].horizon", body),
                       fmt::format("the particle at ({:.6g}, {:.6g}, {:.6g}) has no other particle "
                                   "within the horizon δ = {:.6g} m; raise horizon or refine "
                                   "resolution",
                                   x[0], x[1], x[2], delta));
    if (const double closest = nearest(i); closest < 1e-6 * delta)
      throw InputError(scene.config.file, fmt::format("bodies[{}].geometry", body),
                       fmt::format("two particles at ({:.6g}, {:.6g}, {:.6g}) are {:.3g} m apart, "
                                   "closer than 1e-6 horizons",
                                   x[0], x[1], x[2], closest));
  }
}

// The whole families, or over several ranks this rank's part of them (Families). Each rank
// checks every particle from the counts, so that a bad scene stops every rank alike.
void build_scene_families(Scene& scene, const RowSplit& split) {
  if (!split.boundaries) {
    scene.families = build_families(scene.particles, scene.horizon_of_body);
    const Families& f = scene.families;
    check_families(
        scene, [&f](int i) { return f.offsets[i + 1] - f.offsets[i]; },
        [&f](int i) {
          double closest = std::numeric_limits<double>::infinity();
          for (int b = f.offsets[i]; b < f.offsets[i + 1]; ++b)
            closest = std::min(closest, f.reference_length[b]);
          return closest;
        });
    return;
  }
  const long n = scene.particles.count();
  const bool shared = static_cast<bool>(split.share_counts);
  FamilySizes sizes = count_families(
      scene.particles, scene.horizon_of_body,
      shared ? static_cast<int>(n * split.part / split.parts) : 0,
      shared ? static_cast<int>(n * (split.part + 1) / split.parts) : static_cast<int>(n));
  if (shared) split.share_counts(sizes);
  check_families(
      scene, [&sizes](int i) { return sizes.members[i]; },
      [&sizes](int i) { return sizes.nearest[i]; });
  const std::vector<int> offsets = sizes.offsets();
  sizes = {};
  scene.boundaries = split.boundaries(offsets);
  scene.part = split.part;
  for (int p = 0; p < split.parts; ++p)  // the same on every rank: every rank stops alike
    if (scene.boundaries.at(p + 1) == scene.boundaries.at(p))
      throw InputError(scene.config.file, "bodies",
                       fmt::format("{} particles are too few for {} ranks: rank {} would own "
                                   "none; run on fewer ranks",
                                   n, split.parts, p));
  // this rank's rows and ghosts, numbered on their own: the other particles are dropped
  scene.families = number_locally(
      split_families(scene.particles, scene.horizon_of_body, offsets,
                     scene.boundaries.at(split.part), scene.boundaries.at(split.part + 1)),
      scene.particles);
}

}  // namespace

Scene build_scene(const Config& config, const RowSplit& split) {
  Scene scene;
  scene.config = config;
  // the second-order model's images and cells come from the bodies' tet meshes
  const bool second_order =
      config.bodies.front().material.surface_correction == SurfaceCorrection::fictitious;
  double smallest_horizon = 0;
  for (std::size_t b = 0; b < config.bodies.size(); ++b) {
    const Body& body = config.bodies[b];
    const std::string key = fmt::format("bodies[{}].geometry", b);
    const int before = scene.particles.count();
    if (body.geometry.kind == Geometry::Kind::points) {
      add_point_particles(body, static_cast<int>(b), key, scene.particles);
    } else {
      BodyTetMesh tets{static_cast<int>(b), tetrahedralize_body(body, config.file, b), {}};
      tets.particle = add_tet_particles(tets.mesh, tets.body, body, scene.particles);
      if (config.output.embedded_mesh() || second_order)
        scene.tet_meshes.push_back(std::move(tets));
    }
    if (scene.particles.count() == before)
      throw InputError(config.file, key,
                       fmt::format("body '{}' has no particles (is the geometry smaller than "
                                   "the resolution?)",
                                   body.name));
    const double delta = body.horizon * body.resolution;
    scene.horizon_of_body.push_back(delta);
    smallest_horizon = b == 0 ? delta : std::min(smallest_horizon, delta);
  }
  const std::vector<int> order = sort_spatially(scene.particles, 0.5 * smallest_horizon);
  if (!scene.tet_meshes.empty()) {
    std::vector<int> sorted_index(order.size());
    for (std::size_t k = 0; k < order.size(); ++k) sorted_index[order[k]] = static_cast<int>(k);
    for (BodyTetMesh& tets : scene.tet_meshes)
      for (int& i : tets.particle)
        if (i >= 0) i = sorted_index[i];
  }
  // the tet meshes name particles of the whole scene, which a split drops (Families)
  if (split.boundaries && second_order)
    throw InputError(config.file, "bodies[0].material.surface_correction",
                     "fictitious cannot run over several ranks yet (docs/mpi.md)");
  if (split.boundaries && !scene.tet_meshes.empty())
    throw InputError(config.file, "output",
                     "output.surface and output.tets cannot be written over several ranks yet "
                     "(docs/mpi.md)");
  try {
    build_scene_families(scene, split);
  } catch (const std::length_error& e) {
    throw InputError(config.file, "bodies", e.what());
  }
  return scene;
}

}  // namespace fissure
