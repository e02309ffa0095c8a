#pragma once
// A small elastic vibration for integrator tests: a 0.06 m block (κ = 2 MPa, μ = 1 MPa, ρ = 1000)
// released from rest in a smooth, mostly low-mode deformation, with no loads.
#include <cmath>
#include <memory>

#include "integrators/integrator.hpp"
#include "model/model.hpp"
#include "support/scenes.hpp"
#include "support/state.hpp"

namespace fissure::test {

struct Vibration {
  Scene scene;
  std::unique_ptr<Model> model;
  std::unique_ptr<Dynamics> dynamics;
  State initial;
  double stable_dt = 0;
};

inline std::unique_ptr<Vibration> make_vibration(double lambda = 0.02) {
  auto v = std::make_unique<Vibration>();
  v->scene = block_scene(0.06, lambda, 2.0e6, 1.0e6);
  v->model = make_model(v->scene);
  v->dynamics = std::make_unique<Dynamics>(v->scene, *v->model);
  const Particles& p = v->scene.particles;
  v->initial = at_rest(p);
  for (int i = 0; i < p.count(); ++i) {
    const double* x = &p.reference[3 * i];
    v->initial.position[3 * i] +=
        6e-4 * std::sin(M_PI * x[0] / 0.06) * std::cos(M_PI * x[1] / 0.06);
    v->initial.position[3 * i + 2] += 3e-4 * std::sin(M_PI * x[2] / 0.06);
  }
  v->stable_dt = v->model->stable_time_step();
  return v;
}

// Positions after integrating from the initial state to time `end` in steps of `dt` (the last one
// shortened), or, for an adaptive integrator, in whatever steps it takes.
inline std::vector<double> integrate(Vibration& v, Integrator& integrator, double end, double dt) {
  State s = v.initial;
  while (end - s.time > 1e-12 * end) integrator.step(*v.dynamics, s, std::min(dt, end - s.time));
  return s.position;
}

inline double max_difference(const std::vector<double>& a, const std::vector<double>& b) {
  double m = 0;
  for (std::size_t k = 0; k < a.size(); ++k) m = std::max(m, std::abs(a[k] - b[k]));
  return m;
}

}  // namespace fissure::test
