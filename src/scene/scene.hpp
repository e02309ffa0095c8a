#pragma once
// A loaded scene: the config plus the particles and families sampled from it.
#include <functional>
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
  // Over several ranks (RowSplit): the first row of each rank's range and the row count, and
  // this rank; families and particles then hold only this rank's rows and its ghosts, numbered
  // on their own (Families::global_id). Empty on one rank.
  std::vector<int> boundaries;
  int part = 0;
};

// How build_scene splits the rows over ranks: `boundaries` maps the whole families' CSR offsets
// to the ranks' row ranges (parallel/ownership.hpp), and this rank is `part`. Unset: one rank.
// With share_counts, each of the `parts` ranks counts the family members of its share of the
// particles, [part·n/parts, (part + 1)·n/parts), and share_counts fills in the others' from
// their ranks; without, each rank counts them all.
struct RowSplit {
  std::function<std::vector<int>(const std::vector<int>& offsets)> boundaries;
  int part = 0;
  int parts = 1;
  std::function<void(FamilySizes& sizes)> share_counts;
};

// Samples every body into particles (one per tet at its barycentre, paper §5.2, or read from a
// points file) and builds the families, split as `split` asks. Throws InputError for unusable
// geometry, the same on every rank.
Scene build_scene(const Config& config, const RowSplit& split = {});

}  // namespace fissure
