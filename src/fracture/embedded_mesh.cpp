#include "fracture/embedded_mesh.hpp"

#include <algorithm>

#include "mesh/vertex_motion.hpp"

namespace fissure {

namespace {

// All bodies' tets with a particle, with the particle of each tet.
SplitMesh join_bodies(const Scene& scene, std::vector<int>& particle) {
  TetMesh all;
  for (const BodyTetMesh& body : scene.tet_meshes) {
    const int offset = all.vertex_count();
    all.vertices.insert(all.vertices.end(), body.mesh.vertices.begin(), body.mesh.vertices.end());
    for (int t = 0; t < body.mesh.tet_count(); ++t) {
      if (body.particle[t] < 0) continue;
      for (int c = 0; c < 4; ++c) all.tets.push_back(offset + body.mesh.tets[4 * t + c]);
      particle.push_back(body.particle[t]);
    }
  }
  return make_split_mesh(std::move(all));
}

}  // namespace

EmbeddedMesh::EmbeddedMesh(const Scene& scene, const std::vector<std::uint8_t>* broken)
    : particles_(scene.particles),
      families_(scene.families),
      motion_(scene.config.output.surface_motion),
      mesh_(join_bodies(scene, particle_)),
      splitter_(mesh_.tet_count()) {
  if (broken) {
    cracks_ = std::make_unique<CrackFaces>(mesh_.tet_count());
    tet_of_particle_.assign(particles_.count(), -1);
    for (int t = 0; t < mesh_.tet_count(); ++t) tet_of_particle_[particle_[t]] = t;
    face_bond_.assign(4 * static_cast<std::size_t>(mesh_.tet_count()), -1);
    const auto& row = families_.neighbors;
    for (int f = 0; f < 4 * mesh_.tet_count(); ++f) {
      if (mesh_.across[f] < 0) continue;
      const int p = particle_[f / 4], q = particle_[mesh_.across[f] / 4];
      const auto end = row.begin() + families_.offsets[p + 1];
      const auto it = std::lower_bound(row.begin() + families_.offsets[p], end, q);
      if (it != end && *it == q)
        face_bond_[f] = static_cast<int>(it - row.begin());
      else
        unbonded_faces_ += mesh_.across[f] > f;
    }
    for (int f = 0; f < 4 * mesh_.tet_count(); ++f) test_face(f, *broken);  // initial cracks
  }
  splitter_.split_all(mesh_, cracks_.get());
}

bool EmbeddedMesh::detached(int particle, const std::vector<std::uint8_t>& broken) const {
  for (int b = families_.offsets[particle]; b < families_.offsets[particle + 1]; ++b)
    if (!broken[b]) return false;
  return true;
}

// A face cracks when the bond between its tets' particles broke. Two face-adjacent particles
// beyond each other's horizon have no bond: their face cracks once either particle has lost
// every bond.
void EmbeddedMesh::test_face(int f, const std::vector<std::uint8_t>& broken) {
  const int across = mesh_.across[f];
  if (across < 0 || cracks_->cracked(f)) return;
  const bool cracked = face_bond_[f] >= 0 ? broken[face_bond_[f]] != 0
                                          : detached(particle_[f / 4], broken) ||
                                                detached(particle_[across / 4], broken);
  if (cracked) cracks_->add(f, across);
}

int EmbeddedMesh::crack(const std::vector<std::uint8_t>& broken, const std::vector<int>& changed) {
  if (!cracks_) return 0;
  for (int p : changed) {
    const int t = tet_of_particle_[p];
    if (t < 0) continue;
    for (int k = 0; k < 4; ++k) test_face(4 * t + k, broken);
  }
  return splitter_.split_cracked(mesh_, *cracks_);
}

void EmbeddedMesh::advance(const double* velocity, double dt) {
  if (motion_ == OutputSettings::SurfaceMotion::velocity)
    advance_vertices(mesh_, particle_, particles_.mass.data(), velocity, dt);
}

void EmbeddedMesh::place(const double* y) {
  if (motion_ == OutputSettings::SurfaceMotion::position)
    place_vertices(mesh_, particle_, particles_.mass.data(), particles_.reference.data(), y);
}

}  // namespace fissure
