#pragma once
// The 10 cm glass block of the contact tests (tests/stability/test_contact_blocks.cpp,
// tests/integrators/test_implicit_contact.cpp): Table 1's glass (κ 33 GPa, μ 20 GPa, ρ 2200),
// 48 particles at λ = 5 cm, above the ground plane z = 0, run in-process with one integrator.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "app/run_fissure.hpp"
#include "app/simulation.hpp"
#include "core/error.hpp"
#include "support/csv.hpp"

namespace fissure::test {

// A block at height `bottom` above the ground plane z = 0; probes every `every` seconds.
inline std::string glass_block(double bottom, double end, const std::string& integrator) {
  return fmt::format(
      "name: glass_block\n"
      "time: {{end: {}, dt: auto}}\n"
      "gravity: [0, 0, -9.81]\n"
      "integrator: {}\n"
      "bodies:\n"
      "  - name: block\n"
      "    geometry: {{box: {{min: [0, 0, {}], max: [0.1, 0.1, {}]}}}}\n"
      "    resolution: 0.05\n"
      "    material: {{density: 2200, bulk_modulus: 3.3e10, shear_modulus: 2.0e10}}\n"
      "colliders:\n  - {{plane: {{point: [0, 0, 0], normal: [0, 0, 1]}}}}\n"
      "probes:\n  - {{name: top, region: {{box: {{min: [-1, -1, {}], max: [1, 1, 1]}}}}}}\n"
      "output: {{every: {}, probe_every: {}}}\n",
      end, integrator, bottom, bottom + 0.1, bottom + 0.07, end, end / 200);
}

// Two such blocks of separate bodies stacked on the ground plane, the upper one `gap` above the
// lower one (0: touching as sampled), with self-contact; probes on the upper block's top and
// bottom layers and the lower block's top layer.
inline std::string stacked_glass_blocks(double gap, double end, const std::string& integrator) {
  const double upper = 0.1 + gap;
  return fmt::format(
      "name: stacked_glass_blocks\n"
      "time: {{end: {0}, dt: auto}}\n"
      "gravity: [0, 0, -9.81]\n"
      "integrator: {1}\n"
      "contact: {{self: true}}\n"
      "bodies:\n"
      "  - name: lower\n"
      "    geometry: {{box: {{min: [0, 0, 0], max: [0.1, 0.1, 0.1]}}}}\n"
      "    resolution: 0.05\n"
      "    material: {{density: 2200, bulk_modulus: 3.3e10, shear_modulus: 2.0e10}}\n"
      "  - name: upper\n"
      "    geometry: {{box: {{min: [0, 0, {2}], max: [0.1, 0.1, {3}]}}}}\n"
      "    resolution: 0.05\n"
      "    material: {{density: 2200, bulk_modulus: 3.3e10, shear_modulus: 2.0e10}}\n"
      "colliders:\n  - {{plane: {{point: [0, 0, 0], normal: [0, 0, 1]}}}}\n"
      "probes:\n"
      "  - {{name: top, region: {{box: {{min: [-1, -1, {4}], max: [1, 1, 1]}}}}}}\n"
      "  - {{name: upper_bottom, region: {{box: {{min: [-1, -1, {2}], max: [1, 1, {5}]}}}}}}\n"
      "  - {{name: lower_top, region: {{box: {{min: [-1, -1, 0.07], max: [1, 1, 0.1]}}}}}}\n"
      "output: {{every: {0}, probe_every: {6}}}\n",
      end, integrator, upper, upper + 0.1, upper + 0.07, upper + 0.03, end / 200);
}

// An integrator as a scene's `integrator:` value and its step.
struct Integrator {
  std::string name, yaml, dt;  // dt: auto, or a fixed step
};

// Every petsc_newton scheme at the step dt, those that carry an acceleration from step to step
// (Newmark, generalized-α, ESDIRK4's explicit first stage) included.
inline std::vector<Integrator> petsc_newton_schemes(const std::string& dt) {
  std::vector<Integrator> schemes;
  for (const char* scheme : {"backward_euler", "sdirk3", "sdirk4", "newmark", "alpha", "esdirk4"})
    schemes.push_back({scheme, fmt::format("{{type: petsc_newton, scheme: {}}}", scheme), dt});
  return schemes;
}

struct BlockRun {
  RunSummary summary;
  std::map<std::string, std::vector<double>> probes;
  std::string stopped;  // the message of a run that stopped
};

inline BlockRun run_block(const std::string& yaml, const Integrator& integrator) {
  const auto dir = scratch_dir(integrator.name);
  std::vector<std::string> overrides;
  if (integrator.dt != "auto") overrides.push_back("time.dt=" + integrator.dt);
  Config config = parse_config(yaml, (dir / "block.yaml").string(), overrides);
  config.output.dir = dir.string();
  BlockRun r;
  try {
    r.summary = run_simulation(config, {});
  } catch (const RunError& e) {
    r.stopped = e.what();
  }
  r.probes = test::read_probes(dir / "probes.csv");
  return r;
}

// Per probe row, the energy no entry of the ledger accounts for (docs/output.md, "Energy
// ledger"): K + Π + U + the losses − (E(0) + the works) [J], positive where energy was created.
inline std::vector<double> ledger_excess(const BlockRun& r) {
  const auto column = [&](const char* name) -> const std::vector<double>& {
    return r.probes.at(name);
  };
  const auto& k = column("kinetic_energy");
  std::vector<double> excess(k.size());
  double initial = 0;
  for (std::size_t row = 0; row < k.size(); ++row) {
    double held = 0, put_in = 0;
    for (const char* name : {"kinetic_energy", "elastic_energy", "stored_energy", "damping_loss",
                             "contact_loss", "plastic_dissipation", "fracture_release"})
      held += column(name)[row];
    for (const char* name : {"gravity_work", "constraint_work", "collider_work"})
      put_in += column(name)[row];
    if (row == 0) initial = held - put_in;
    excess[row] = held - put_in - initial;
  }
  return excess;
}

// The largest |value|.
inline double largest(const std::vector<double>& values) {
  double m = 0;
  for (double v : values) m = std::max(m, std::abs(v));
  return m;
}

}  // namespace fissure::test
