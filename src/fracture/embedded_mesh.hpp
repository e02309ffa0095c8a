#pragma once
// The embedded tet mesh of paper §5.2: the tets the particles were sampled from (one particle per
// tet), split along the faces across which the material broke, with vertices that follow the
// particles. Built only when the config writes surfaces or tets; the crack bookkeeping exists
// only with fracture.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "mesh/crack_faces.hpp"
#include "mesh/split_mesh.hpp"
#include "mesh/vertex_split.hpp"
#include "scene/scene.hpp"

namespace fissure {

class EmbeddedMesh {
 public:
  // The bodies' tet meshes (scene.tet_meshes) as one mesh. `broken` is the bond breaking's flag
  // per directed bond (initial cracks already applied), or null without fracture.
  EmbeddedMesh(const Scene& scene, const std::vector<std::uint8_t>* broken);

  // After bond breaking: the faces of the tets of the `changed` particles (those that lost
  // bonds) whose bond broke join the crack-face set, then the vertices of the new crack faces
  // split. The cost grows with the changes, not with the mesh. Returns the copies made.
  int crack(const std::vector<std::uint8_t>& broken, const std::vector<int>& changed);
  // Eqs 20–22, every step, with `surface_motion: velocity`; nothing otherwise.
  void advance(const double* velocity, double dt);
  // Before a frame is written, with `surface_motion: position`: x_v from the particles'
  // displacements; nothing otherwise.
  void place(const double* y);

  const SplitMesh& mesh() const { return mesh_; }
  const std::vector<int>& particle() const { return particle_; }  // per tet
  // The crack-face set, or nullptr without fracture.
  const CrackFaces* cracks() const { return cracks_.get(); }
  // Faces ever cracked, and those still in the crack-face set (not yet retired).
  std::size_t crack_faces() const { return cracks_ ? cracks_->total() : 0; }
  std::size_t active_crack_faces() const { return cracks_ ? cracks_->set().size() : 0; }
  // Interior faces whose two particles are not bonded (beyond each other's horizon).
  std::size_t unbonded_faces() const { return unbonded_faces_; }

 private:
  bool detached(int particle, const std::vector<std::uint8_t>& broken) const;
  // Adds face f to the crack-face set if the material across it broke.
  void test_face(int f, const std::vector<std::uint8_t>& broken);

  const Particles& particles_;
  const Families& families_;
  OutputSettings::SurfaceMotion motion_;
  std::vector<int> particle_;  // per tet; filled while mesh_ is built, so declared before it
  SplitMesh mesh_;
  VertexSplitter splitter_;
  std::unique_ptr<CrackFaces> cracks_;
  // Per face id: the directed bond from the tet's particle to the particle across the face, or
  // −1 (boundary, or the two particles are not bonded). Per particle: its tet, or −1.
  std::vector<int> face_bond_;
  std::vector<int> tet_of_particle_;
  std::size_t unbonded_faces_ = 0;
};

}  // namespace fissure
