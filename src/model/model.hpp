#pragma once
// The constitutive model: internal forces, energies and the stable explicit step, for positions
// y. It knows nothing of time stepping.
#include <array>
#include <atomic>
#include <cmath>
#include <cstddef>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "core/named_arrays.hpp"
#include "model/plastic_flow.hpp"
#include "model/stiffness.hpp"
#include "scene/particles.hpp"

namespace fissure {

struct Scene;
class Halo;

// Per-particle material constants, expanded from the bodies.
struct MaterialPoints {
  std::vector<double> bulk_modulus;   // κ
  std::vector<double> shear_modulus;  // μ
  std::vector<double> density;        // ρ
  std::vector<double> horizon;        // δ [m]
  // G per particle, row major (Eq 17); empty when every body is isotropic.
  std::vector<std::array<double, 9>> anisotropy;
};

// ξ = x_j − x_i.
inline std::array<double, 3> reference_vector(const Particles& p, int i, int j) {
  return {p.reference[3 * j] - p.reference[3 * i], p.reference[3 * j + 1] - p.reference[3 * i + 1],
          p.reference[3 * j + 2] - p.reference[3 * i + 2]};
}

// The influence function ω_ij = δ / |G ξ| (Eq 17), or δ / |ξ| without G (Eq 5).
double influence(const MaterialPoints& m, int i, const double* xi_vector, double xi_length);

// Per-particle plasticity constants (paper §4.2), expanded from the bodies.
struct PlasticPoints {
  std::vector<double> yield_potential;      // Ψ0 of Eq 13, or NaN where yield_stress is given
  std::vector<double> yield_stress;         // σ_y [Pa], or NaN where Ψ0 is given
  std::vector<double> max_plastic_stretch;  // γ / |ξ| (infinite: no cap)
};

class Model {
 public:
  Model(const Particles& particles, const Families& families, MaterialPoints materials)
      : particles_(particles), families_(families), materials_(std::move(materials)) {}
  virtual ~Model() = default;
  virtual std::string name() const = 0;
  const Families& families() const { return families_; }
  // Internal forces F_i = V_i Σ_j (T<j,i> − T<i,j>) V_j (Eq 2 times V_i), 3N, overwritten.
  // Evaluations (forces, energy_density, dilatation, forces_and_energy) keep nothing another
  // call reads: what they share is scratch filled anew by each, or kept for the same positions
  // and revision() only, so that a result never depends on the calls before it.
  virtual void forces(const double* y, double* f) = 0;
  // Strain energy density W_i of each particle at positions y (N values); over several ranks
  // (distribute()) of this rank's rows only, the others untouched. Collective there.
  virtual void energy_density(const double* y, double* w) = 0;
  // Total elastic energy Π = Σ V_i W_i.
  double elastic_energy(const double* y);
  // Σ V_i W_i over the given particles only: what the energy ledger books when bonds break, which
  // changes only the broken bonds' rows. This one evaluates every W_i; a model whose W_i reads
  // only row i's bonds evaluates the listed rows alone.
  virtual double rows_energy(const double* y, const std::vector<int>& rows);
  // Dilatation θ_i of each particle at positions y (N values), the one the forces at y use;
  // over several ranks (distribute()) of this rank's rows only, the other values untouched.
  virtual void dilatation(const double* y, double* theta) const = 0;
  // Gershgorin bound on the stable explicit step at the reference state (notes §4); over several
  // ranks the same value on every rank (collective).
  virtual double stable_time_step() const = 0;
  // Removes bond b of row i for good (fracture): it carries no force and stores no energy.
  // The same bond in the other row (Families::reverse) is removed by its own call; calls for
  // different rows may run in parallel.
  virtual void break_bond(int i, std::size_t b) = 0;
  // False once bond b has been broken.
  virtual bool bond_intact(std::size_t b) const = 0;
  // For checkpoints: what breaking and plasticity changed beyond the broken bonds themselves, and
  // its restoration after the broken bonds have been replayed through break_bond().
  virtual NamedArrays saved_state() const { return {}; }
  virtual void restore_state(const NamedArrays&) {}
  // Whether saved_state()'s array `name` holds one value per directed bond (CSR order), not
  // per particle: over several ranks a checkpoint gathers it by the rows' bonds.
  virtual bool per_bond_state(const std::string&) const { return false; }
  // Optional capabilities, nullptr where the model has none: its stiffness for implicit
  // integrators (model/stiffness.hpp) and its plastic flow (model/plastic_flow.hpp, only when
  // the scene asks for plasticity).
  virtual Stiffness* stiffness() { return nullptr; }
  virtual const Stiffness* stiffness() const { return nullptr; }
  virtual PlasticFlow* plastic_flow() { return nullptr; }
  virtual const PlasticFlow* plastic_flow() const { return nullptr; }
  // F_int(y) into f (as forces()) and the elastic energy Π(y) (as elastic_energy()) from one pass
  // over the bonds: an implicit step's residual and its line search's objective at one point.
  virtual double forces_and_energy(const double* y, double* f);
  // Counts changes of the model's own state (a bond broken, plastic flow, a restore): what was
  // computed from the model at another revision (an integrator's kept forces) is stale.
  std::size_t revision() const { return revision_.load(std::memory_order_relaxed); }
  // Bytes stored per directed bond: the families (neighbour, |ξ|, reverse index) and the
  // model's own bond data.
  virtual std::size_t bytes_per_bond() const = 0;
  // Bytes of bond data one force evaluation reads per directed bond (all passes).
  virtual std::size_t bytes_read_per_bond() const = 0;
  // What the model's set-up reached, by name (summary.json model_statistics, `fissure info`):
  // e.g. the LPS deviatoric calibration's exact rows. Empty for most models.
  virtual std::vector<std::pair<std::string, double>> statistics() const { return {}; }
  // From now on forces() and forces_and_energy() evaluate only the rows this rank owns
  // (halo.begin() to halo.end()): they read the positions of those rows and of the halo's
  // ghosts, write those rows of f, and forces_and_energy() returns this rank's share of Π;
  // whatever a row needs from a ghost's row comes through the halo (docs/mpi.md).
  // The halo must outlive the model. dilatation() and energy_density() evaluate the own rows
  // too (elastic_energy() is then this rank's share), and so does the stiffness
  // (stiffness.hpp); rows_energy() evaluates the rows it is given. break_bond() changes only the
  // row it names. A model that cannot be distributed throws std::invalid_argument saying why.
  virtual void distribute(const Halo& halo);

 protected:
  const Particles& particles_;
  const Families& families_;
  MaterialPoints materials_;
  // Every change of the state counts once; break_bond may run for many rows at a time.
  void mark_changed() { revision_.fetch_add(1, std::memory_order_relaxed); }

 private:
  std::atomic<std::size_t> revision_{0};
};

// Each particle's material constants, from its body.
MaterialPoints material_points(const Scene& scene);
// The model the scene's bodies ask for (material.model), set up for its particles. The model
// refers to the scene's particles and families, so the scene must outlive it; a temporary scene
// is refused at compile time.
std::unique_ptr<Model> make_model(const Scene& scene);
std::unique_ptr<Model> make_model(const Scene&& scene) = delete;

}  // namespace fissure
