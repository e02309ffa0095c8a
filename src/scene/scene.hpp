#pragma once
// A loaded scene: the config plus the particles and families sampled from it.
#include <vector>

#include "mesh/tet_mesh.hpp"
#include "scene/config.hpp"
#include "scene/particles.hpp"

namespace fissure {

// The tet mesh a body was sampled from (paper §5.2), kept only when the config writes surfaces
// or tets.
struct BodyTetMesh {
  int body = 0;
  TetMesh mesh;
  std::vector<int> particle;  // particle of each tet after the spatial sort; −1: tet without volume
};

struct Scene {
  Config config;
  Particles particles;
  Families families;
  std::vector<double> horizon_of_body;  // δ in metres, per body
  std::vector<BodyTetMesh> tet_meshes;  // per tet body, only if config.output.embedded_mesh()
};

// Samples every body into particles (one per tet at its barycentre, paper §5.2, or read from a
// points file) and builds the families. Throws InputError for unusable geometry.
Scene build_scene(const Config& config);

}  // namespace fissure
