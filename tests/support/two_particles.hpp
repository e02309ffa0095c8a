#pragma once
// A body of two particles, one bond: the smallest scene whose motion and energy are known in
// closed form. Particles of volume V at x = 0 and x = L on the x axis, so |ξ| = L < δ and each
// particle's family is the other one. The LPS model (docs/model.md) then has, per particle,
// m_i = ω L² V (ω = δ/L, Eq 5), plain dilatation weights (a family of fewer than six bonds cannot
// be calibrated) c = 3ωL/m_i = 3/(L V), θ_i = c e V = 3e/L (Eq 6 without Λ) and
// ê = e − θL/3 = 0 (Eq 9, corrected): the bond stores Π = Σ_i V_i ½κθ_i² = 9κV e²/L², a linear
// spring of stiffness k_s = 18κV/L² in the extension e for motion along the bond.
#include <fmt/format.h>

#include <string>

namespace fissure::test {

struct TwoParticles {
  double spacing = 0.01;       // L [m]
  double volume = 1e-6;        // V of each particle [m³]
  double density = 1000;       // ρ [kg/m³]
  double bulk = 1.0e4;         // κ [Pa]
  double shear = 1.0e4;        // μ [Pa]: no deviatoric extension, so no role
  double speed = 0.0;          // the particles move apart along x at ±speed
  std::string material_extra;  // further material keys, e.g. ", fracture: {...}"

  double mass() const { return density * volume; }
  // Π = ½ k_s e² (header comment).
  double spring() const { return 18.0 * bulk * volume / (spacing * spacing); }
  double energy(double extension) const { return 0.5 * spring() * extension * extension; }
  // The points file (x y z volume vx vy vz per line).
  std::string points() const {
    return fmt::format("0 0 0 {0} {1} 0 0\n{2} 0 0 {0} {3} 0 0\n", volume, -speed, spacing, speed);
  }
  // The body's YAML entry (under `bodies:`), reading the points from `file`: resolution L, so
  // δ = 1.45 L holds the one bond.
  std::string body(const std::string& file) const {
    return fmt::format(
        "  - geometry: {{points: {{file: {}}}}}\n"
        "    resolution: {}\n"
        "    material: {{density: {}, bulk_modulus: {}, shear_modulus: {}{}}}\n",
        file, spacing, density, bulk, shear, material_extra);
  }
};

}  // namespace fissure::test
