#include "integrators/velocity_verlet.hpp"

namespace fissure {

double VelocityVerlet::step(Dynamics& dynamics, State& state, double dt) {
  auto& y = state.position;
  auto& v = state.velocity;
  const std::size_t n = y.size();
  if (!have_acceleration_ || acceleration_.size() != n) {
    acceleration_.resize(n);
    dynamics.acceleration(state.time, y.data(), v.data(), acceleration_.data());
    have_acceleration_ = true;
  }
  const double half = 0.5 * dt;
  // this rank's rows: all on one rank
  const std::size_t first = 3 * std::size_t(dynamics.first_row()),
                    end = 3 * std::size_t(dynamics.end_row());
  // v_{n+½} = v_n + Δt/2 a_n; y_{n+1} = y_n + Δt v_{n+½}
#pragma omp parallel for schedule(static)
  for (std::size_t k = first; k < end; ++k) {
    v[k] += half * acceleration_[k];
    y[k] += dt * v[k];
  }
  state.time += dt;
  // v_{n+1} = v_{n+½} + Δt/2 a_{n+1}
  dynamics.share(y.data());
  dynamics.acceleration(state.time, y.data(), v.data(), acceleration_.data());
#pragma omp parallel for schedule(static)
  for (std::size_t k = first; k < end; ++k) v[k] += half * acceleration_[k];
  dynamics.constrain_velocity(state.time, v.data());
  return dt;
}

NamedArrays VelocityVerlet::saved_state() const {
  if (!have_acceleration_) return {};
  return {{"integrator.acceleration", acceleration_}};
}

void VelocityVerlet::restore_state(const NamedArrays& state) {
  const std::vector<double>* a = find_array(state, "integrator.acceleration");
  have_acceleration_ = a != nullptr;
  if (a) acceleration_ = *a;
}

IntegratorKind velocity_verlet_kind() {
  return {"velocity_verlet", {}, nullptr, [](const IntegratorSettings&, const std::string&) {
            return std::make_unique<VelocityVerlet>();
          }};
}

}  // namespace fissure
