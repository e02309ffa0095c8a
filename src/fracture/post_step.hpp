#pragma once
// The post-step every integrator hands over to after a completed step (never inside a force
// evaluation): the plastic return map (paper §4.2), then bond breaking (§5.1), then the embedded
// mesh's vertex splitting and motion (§5.2). Only the effects the scene asks for run.
#include <memory>

#include "fracture/bond_breaking.hpp"
#include "fracture/embedded_mesh.hpp"
#include "model/model.hpp"
#include "scene/scene.hpp"

namespace fissure {

class PostStep {
 public:
  // With measure_energy, run() also books the stored energy the return map and bond breaking
  // release at fixed positions (released()): one or two extra energy evaluations on the steps
  // where bonds yield or break, and one per step before the return map of a plastic scene.
  PostStep(const Scene& scene, Model& model, bool measure_energy = false);
  // Over several ranks (docs/mpi.md): bond breaking tests and changes this rank's rows
  // (BondBreaking::distribute), run() returns whether bonds broke on any rank and books the
  // energy released on all of them, the same on every rank. Throws std::invalid_argument naming
  // the key of an effect that cannot be distributed yet. The halo must outlive this.
  void distribute(const Halo& halo);
  // Returns true if the bond set changed, so the integrator must drop what it derived from it.
  // `velocity` and the step `dt` move the embedded mesh's vertices with `surface_motion:
  // velocity` (Eq 22).
  bool run(const double* y, const double* velocity = nullptr, double dt = 0);
  // φ per particle, or nullptr without fracture.
  const std::vector<double>* damage() const;
  std::size_t broken_bonds() const;
  // How many times run() was called: one per accepted step, whichever integrator ran.
  std::size_t calls() const { return calls_; }
  // Energy released so far at fixed positions [J]: by the plastic return map (Π(e^p_old) −
  // Π(e^p_new), plastic dissipation) and by broken bonds (Π before − Π after breaking).
  struct Released {
    double plastic = 0, fracture = 0;
  };
  const Released& released() const { return released_; }
  // For checkpoints: the broken bonds, the model's state, the calls and the released energies;
  // restore_state() rebuilds the embedded mesh from the restored bonds (split from scratch).
  NamedArrays saved_state() const;
  void restore_state(const Scene& scene, const NamedArrays& state,
                     const std::vector<std::uint8_t>& broken);
  // 1 per broken directed bond, or empty without fracture.
  std::vector<std::uint8_t> broken() const;
  // The embedded tet mesh, or nullptr unless the config writes surfaces or tets.
  EmbeddedMesh* embedded_mesh() { return embedded_mesh_.get(); }

 private:
  Model& model_;
  std::unique_ptr<BondBreaking> bond_breaking_;
  std::unique_ptr<EmbeddedMesh> embedded_mesh_;
  std::size_t calls_ = 0;
  bool measure_energy_;
  Released released_;
  const Halo* halo_ = nullptr;
};

}  // namespace fissure
