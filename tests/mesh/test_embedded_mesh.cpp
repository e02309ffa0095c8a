// The embedded mesh of a scene (paper §5.2): tets keep their particles through the
// spatial sort, faces crack when their bond breaks, vertices follow the particles.
#include <gtest/gtest.h>

#include <string>

#include "fracture/embedded_mesh.hpp"
#include "fracture/post_step.hpp"
#include "model/model.hpp"
#include "split_fixtures.hpp"

namespace fissure::test {
namespace {

// A fracturing box [0, 0.4] × [0, 0.2] × [0, 0.2] with surfaces on; `extra` is appended to the
// YAML (initial cracks, output keys).
Scene box_scene(const std::string& output, const std::string& extra = "") {
  const std::string yaml =
      "time: {end: 1.0}\n"
      "bodies:\n"
      "  - geometry: {box: {min: [0, 0, 0], max: [0.4, 0.2, 0.2]}}\n"
      "    resolution: 0.05\n"
      "    material: {density: 1000, bulk_modulus: 1e6, shear_modulus: 1e6,\n"
      "               fracture: {critical_stretch: 0.01}}\n"
      "output: {" +
      output + "}\n" + extra;
  return build_scene(parse_config(yaml, "test_embedded.yaml"));
}

std::vector<double> translated(const Particles& p, const double c[3], double t) {
  std::vector<double> y(p.reference);
  for (int i = 0; i < p.count(); ++i)
    for (int k = 0; k < 3; ++k) y[3 * i + k] += c[k] * t;
  return y;
}

// Every vertex at its rest position plus `shift`, to round-off.
void expect_shifted(const SplitMesh& m, const double shift[3]) {
  for (int v = 0; v < m.vertex_count(); ++v)
    for (int k = 0; k < 3; ++k)
      ASSERT_NEAR(m.position[3 * v + k], m.mesh.vertices[3 * v + k] + shift[k], 1e-12)
          << "vertex " << v;
}

// Rest x of the particle of each tet, read through the tet → particle map.
double particle_x(const Scene& scene, const EmbeddedMesh& e, int t) {
  return scene.particles.reference[3 * e.particle()[t]];
}

TEST(EmbeddedMesh, EachTetKeepsItsParticleThroughTheSpatialSort) {
  const Scene scene = box_scene("surface: true");
  const EmbeddedMesh e(scene, nullptr);
  ASSERT_EQ(e.mesh().tet_count(), scene.particles.count());
  for (int t = 0; t < e.mesh().tet_count(); ++t) {
    const auto c = barycentre(e.mesh(), t);
    for (int k = 0; k < 3; ++k)
      ASSERT_NEAR(scene.particles.reference[3 * e.particle()[t] + k], c[k], 1e-12) << "tet " << t;
  }
}

TEST(EmbeddedMesh, NotKeptUnlessSurfacesOrTetsAreWritten) {
  EXPECT_TRUE(box_scene("every: 0.1").tet_meshes.empty());
  EXPECT_EQ(box_scene("tets: true").tet_meshes.size(), 1u);
}

TEST(EmbeddedMesh, RigidTranslationKeepsTheSurfaceAndMovesVerticesExactly) {
  const double c[3] = {0.3, -1.2, 2.5};
  const double dt = 1e-3;
  for (const std::string motion : {"position", "velocity"}) {
    SCOPED_TRACE(motion);
    const Scene scene = box_scene("surface: true, surface_motion: " + motion);
    const auto model = make_model(scene);
    PostStep post_step(scene, *model);
    EmbeddedMesh& e = *post_step.embedded_mesh();
    const BoundarySurface first = extract_boundary(e.mesh());
    const int vertices = e.mesh().vertex_count();
    std::vector<double> v(scene.particles.velocity.size());
    for (std::size_t k = 0; k < v.size(); ++k) v[k] = c[k % 3];
    for (int step = 1; step <= 50; ++step) {
      const std::vector<double> y = translated(scene.particles, c, step * dt);
      EXPECT_FALSE(post_step.run(y.data(), v.data(), dt));  // no bond stretches
      if (step % 10) continue;
      e.place(y.data());  // a frame
      const double shift[3] = {c[0] * step * dt, c[1] * step * dt, c[2] * step * dt};
      expect_shifted(e.mesh(), shift);
      const BoundarySurface now = extract_boundary(e.mesh());
      EXPECT_EQ(now.triangles, first.triangles);
      EXPECT_EQ(e.mesh().vertex_count(), vertices);
    }
    EXPECT_EQ(e.crack_faces(), 0u);
  }
}

TEST(EmbeddedMesh, InitialCrackThroughTheBoxSplitsTheMeshInTwo) {
  const Scene scene = box_scene(
      "surface: true", "initial_cracks: [{plane: {point: [0.2, 0, 0], normal: [1, 0, 0]}}]\n");
  const auto model = make_model(scene);
  PostStep post_step(scene, *model);
  const EmbeddedMesh& e = *post_step.embedded_mesh();
  EXPECT_EQ(e.unbonded_faces(), 0u);
  EXPECT_GT(e.crack_faces(), 0u);
  EXPECT_EQ(count_labels(pieces_by_vertices(e.mesh())), 2);
  // No vertex is shared by tets whose particles lie on both sides of the crack.
  std::vector<int> side(e.mesh().vertex_count(), -1);
  for (int t = 0; t < e.mesh().tet_count(); ++t)
    for (int q = 0; q < 4; ++q) {
      int& s = side[e.mesh().mesh.tets[4 * t + q]];
      const int here = particle_x(scene, e, t) > 0.2;
      EXPECT_TRUE(s < 0 || s == here);
      s = here;
    }
  expect_valid(e.mesh(), *e.cracks(), false);
}

TEST(EmbeddedMesh, BondsBrokenDuringTheRunCrackTheirFacesAndSplitVertices) {
  const Scene scene = box_scene("surface: true");
  const auto model = make_model(scene);
  PostStep post_step(scene, *model);
  const EmbeddedMesh& e = *post_step.embedded_mesh();
  const int before = e.mesh().vertex_count();
  // The half x > 0.2 pulled away by 5 cm: every bond across x = 0.2 stretches past s_c.
  std::vector<double> y = scene.particles.reference;
  for (int i = 0; i < scene.particles.count(); ++i)
    if (y[3 * i] > 0.2) y[3 * i] += 0.05;
  EXPECT_TRUE(post_step.run(y.data()));
  EXPECT_GT(e.mesh().vertex_count(), before);
  EXPECT_EQ(count_labels(pieces_by_vertices(e.mesh())), 2);
  const BoundarySurface surface = extract_boundary(e.mesh());
  EXPECT_GT(std::count(surface.crack.begin(), surface.crack.end(), 1), 0);
  expect_valid(e.mesh(), *e.cracks(), false);
}

TEST(EmbeddedMesh, ShippedFractureScenesBondEveryPairOfFaceAdjacentTets) {
  for (const char* name : {"glass_wall", "thin_sheet"}) {
    SCOPED_TRACE(name);
    const Config config = load_config(
        std::string(FISSURE_SOURCE_DIR) + "/configs/" + name + ".yaml", {"output.surface=true"});
    const Scene scene = build_scene(config);
    const auto model = make_model(scene);
    PostStep post_step(scene, *model);
    EXPECT_EQ(post_step.embedded_mesh()->unbonded_faces(), 0u);
  }
}

}  // namespace
}  // namespace fissure::test
