#include "integrators/symplectic_euler.hpp"

namespace fissure {

double SymplecticEuler::step(Dynamics& dynamics, State& state, double dt) {
  auto& y = state.position;
  auto& v = state.velocity;
  acceleration_.resize(y.size());
  dynamics.acceleration(state.time, y.data(), v.data(), acceleration_.data());
  const double t_end = state.time + dt;
  // this rank's rows: all on one rank
  const std::size_t first = 3 * std::size_t(dynamics.first_row()),
                    end = 3 * std::size_t(dynamics.end_row());
#pragma omp parallel for schedule(static)
  for (std::size_t k = first; k < end; ++k) v[k] += dt * acceleration_[k];
  dynamics.constrain_velocity(state.time, v.data());
#pragma omp parallel for schedule(static)
  for (std::size_t k = first; k < end; ++k) y[k] += dt * v[k];
  dynamics.share(y.data());  // the post-step and the next step read the ghosts' new positions
  state.time = t_end;
  return dt;
}

IntegratorKind symplectic_euler_kind() {
  return {"symplectic_euler", {}, nullptr, [](const IntegratorSettings&, const std::string&) {
            return std::make_unique<SymplecticEuler>();
          }};
}

}  // namespace fissure
