#include "integrators/newton_system.hpp"

#include <cmath>

#include "linear/shifted_system.hpp"

namespace fissure {

NewtonSystem::NewtonSystem(Dynamics& dynamics, const std::string& tangent)
    : dynamics_(dynamics), tangent_(tangent) {
  const Families& families = dynamics.model().families();
  matrix_ = tangent == "majoriser" ? bond_pattern(families) : two_hop_pattern(families);
  diagonal_ = diagonal_positions(matrix_);
  const auto& m = dynamics.mass();
  mass_.resize(3 * m.size());
  for (std::size_t i = 0; i < m.size(); ++i)
    for (int d = 0; d < 3; ++d) mass_[3 * i + d] = m[i];
  force_.resize(mass_.size());
  external_.resize(mass_.size());
}

std::vector<double> NewtonSystem::begin_step(const ImplicitScheme& scheme, const State& state,
                                             double h, double load_factor) {
  inertia_ = scheme.inertia();
  target_ = scheme.target();
  dynamics_.external_forces(state.position.data(), state.velocity.data(), external_.data());
  for (double& f : external_) f *= load_factor;
  // Newton starts from the extrapolation y + (1 − α_f)h v or, where that overshoots (modes with
  // ωh ≫ 1 at large steps carry large velocities), from y: whichever has the lower potential.
  std::vector<double> z = scheme.guess(state, h);
  std::vector<double> stay = state.position;
  fixed_.assign(z.size(), 0);
  std::vector<int> held;
  std::vector<Vec3> velocity;
  dynamics_.held(state.time, held, velocity);
  for (std::size_t k = 0; k < held.size(); ++k)
    for (int d = 0; d < 3; ++d) {
      const int u = 3 * held[k] + d;
      fixed_[u] = 1;
      z[u] = stay[u] = scheme.held_value(state.position[u], velocity[k][d], h);
    }
  return objective(stay.data()) < objective(z.data()) ? stay : z;
}

double NewtonSystem::objective(const double* z) {
  double kinetic = 0, work = 0;
  const std::size_t n = mass_.size();
#pragma omp parallel for reduction(+ : kinetic, work) schedule(static)
  for (std::size_t k = 0; k < n; ++k) {
    if (fixed_[k]) continue;
    const double d = z[k] - target_[k];
    kinetic += mass_[k] * d * d;
    work += external_[k] * d;  // fᵀ(z − ỹ): fᵀz up to a constant, without its cancellation
  }
  const double elastic = dynamics_.model().elastic_energy(z);
  magnitude_ = 0.5 * inertia_ * kinetic + std::abs(elastic) + std::abs(work);
  return 0.5 * inertia_ * kinetic + elastic - work;
}

void NewtonSystem::residual(const double* z, double* r) {
  dynamics_.internal_forces(z, force_.data());
  const std::size_t n = mass_.size();
#pragma omp parallel for schedule(static)
  for (std::size_t k = 0; k < n; ++k)
    r[k] = fixed_[k] ? 0.0 : inertia_ * mass_[k] * (z[k] - target_[k]) - force_[k] - external_[k];
}

std::vector<double> NewtonSystem::reactions() const {
  std::vector<double> reaction(fixed_.size(), 0.0);
  for (std::size_t k = 0; k < fixed_.size(); ++k)
    if (fixed_[k]) reaction[k] = -(force_[k] + external_[k]);
  return reaction;
}

void NewtonSystem::hessian(const double* z) {
  Model& model = dynamics_.model();
  if (tangent_ == "majoriser")
    model.assemble_majoriser(z, matrix_);
  else
    model.assemble_tangent(z, matrix_, tangent_ == "projected");
  shift_and_fix(matrix_, diagonal_, mass_, inertia_, fixed_);
}

}  // namespace fissure
