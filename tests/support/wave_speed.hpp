#pragma once
// A longitudinal wave in a long thin bar travels at the bar speed c = √(E/ρ): the measurement
// tests/verification/test_wave_speed.cpp and test_wave_speed_fictitious.cpp share.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "integrators/integrator.hpp"
#include "model/model.hpp"
#include "support/scenes.hpp"
#include "support/state.hpp"

namespace fissure::test {

// The end x < 0.03 is pushed at constant velocity v0. Behind the front a probe's mean
// displacement grows as v0 (t − x/c), so fitting a line to u(t) once the front has passed and
// extrapolating to u = 0 gives the arrival time; c comes from two probes' arrival times, which
// cancels the time the front needs to form. E = 9κμ/(3κ + μ). `extra` is appended to the
// material map; returns the measured speed over c.
inline double wave_speed_ratio(const std::string& extra) {
  const double bulk = 5e6, shear = 5e6, density = 1000;
  const Scene scene = block_scene({.size = {1.5, 0.05, 0.05},
                                   .resolution = 0.0125,
                                   .bulk = bulk,
                                   .shear = shear,
                                   .density = density,
                                   .material = extra,
                                   .scene = "constraints:\n"
                                            "  - {region: {box: {min: [-1, -1, -1], max: "
                                            "[0.03, 1, 1]}}, velocity: [0.01, 0, 0]}\n"});
  auto model = make_model(scene);
  Dynamics dynamics(scene, *model);
  auto integrator = make_integrator("velocity_verlet", "test");
  State state = at_rest(scene.particles);
  dynamics.constrain_velocity(0, state.velocity.data());

  const double E = 9 * bulk * shear / (3 * bulk + shear);
  const double c = std::sqrt(E / density);
  const double probes[2] = {0.5, 1.0};
  std::vector<int> members[2];
  for (int p = 0; p < 2; ++p)
    for (int i = 0; i < scene.particles.count(); ++i)
      if (std::abs(scene.particles.reference[3 * i] - probes[p]) < 0.02) members[p].push_back(i);

  const double dt = 0.9 * model->stable_time_step();
  const double t_end = 1.3 / c;
  std::vector<double> times, u[2];
  while (state.time < t_end) {
    integrator->step(dynamics, state, dt);
    times.push_back(state.time);
    for (int p = 0; p < 2; ++p) {
      double sum = 0;
      for (int i : members[p]) sum += state.position[3 * i] - scene.particles.reference[3 * i];
      u[p].push_back(sum / members[p].size());
    }
  }
  // Fit u = v0 (t − t_arrival) on the window where the front has clearly passed: from 0.1 m of
  // travel (0.1/c) after the nominal arrival to the end of the record, before the reflection
  // from the far end at 1.5 m can return to x = 1.0.
  double arrival[2];
  for (int p = 0; p < 2; ++p) {
    const double t0 = probes[p] / c + 0.1 / c;
    double st = 0, su = 0, stt = 0, stu = 0;
    int n = 0;
    for (std::size_t k = 0; k < times.size(); ++k)
      if (times[k] > t0) {
        st += times[k], su += u[p][k], stt += times[k] * times[k], stu += times[k] * u[p][k];
        ++n;
      }
    EXPECT_GT(n, 10);
    const double slope = (n * stu - st * su) / (n * stt - st * st);
    const double intercept = (su - slope * st) / n;
    arrival[p] = -intercept / slope;
    std::printf("probe x = %.1f: particle velocity %.4g m/s (push 0.01), arrival %.4g s\n",
                probes[p], slope, arrival[p]);
  }
  const double measured = (probes[1] - probes[0]) / (arrival[1] - arrival[0]);
  std::printf("wave speed %.2f m/s, sqrt(E/rho) = %.2f m/s, ratio %.4f\n", measured, c,
              measured / c);
  return measured / c;
}

}  // namespace fissure::test
