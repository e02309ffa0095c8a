// The energy ledger's contact entries against independent figures: self-contact's contact_loss
// against the penalty energy of the measured overlap, a moving box's collider_work against its
// velocity times the momentum it gave, and ground friction's work against μ M g times the
// sliding distance. Velocity Verlet throughout.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>

#include "stability/stability_case.hpp"
#include "support/csv.hpp"

namespace fissure {
namespace {

// A block of n × n × n points on a lattice of spacing λ with its corner at the origin, every
// point of volume λ³ (so a probe's mean position is the centre of mass), at velocity (vx, 0, 0).
std::string lattice(int n, double spacing, double vx) {
  std::string points;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k)
        points += fmt::format("{} {} {} {} {} 0 0\n", i * spacing, j * spacing, k * spacing,
                              spacing * spacing * spacing, vx);
  return points;
}

// Two bodies of two particles each (volume V, κ; one bond along y, of length V^(1/3)), flying at
// each other along x at ±v0 from a gap g between the contact spheres (radius r = ½V^(1/3)) of
// facing particles. Only facing particles touch (the diagonal pairs stay √2 r + r apart), and by
// symmetry each body translates rigidly: two equal contacts. Once a pair overlaps by p the
// self-contact penalty k p (k = stiffness × κ × V^(1/3), docs/config.md) acts, and with the
// reduced mass m/2 the overlap grows as p = (u/Ω) sin Ω(t − t0), u = 2v0, Ω = √(2k/m). The run
// ends at Ω(T − t0) = 1 rad, before the deepest overlap, so p rises monotonically. contact_loss
// books −½ Σ (F(y_n) + F(y_{n+1}))·Δy per pair, the trapezoidal rule on ∫ k p dp: exactly
// ½ k (p_{n+1}² − p_n²) on each step in contact, and on the step the pair enters, from a gap
// g to p, ½ k p (p + g) where ½ k p² was stored: ½ k p g ≤ k (u h)²/8 more (p + g ≤ u h). So it
// exceeds ½ k p(T)² by at most that, 3.5e-7 of it at Ω h = 1e-3 for the two contacts together;
// a right-end sum (F(y_{n+1}) alone) would exceed it by ½ k Σ Δp_n², about 6e-4 of it here, and a
// left-end sum fall short as much.
// Two particles of volume V at (x, 0, 0) and (x, V^(1/3), 0), moving at (vx, 0, 0).
std::string pair(double x, double volume, double vx) {
  return fmt::format("{0} 0 0 {1} {2} 0 0\n{0} {3} 0 {1} {2} 0 0\n", x, volume, vx,
                     std::cbrt(volume));
}

TEST(ContactLedger, ContactLossIsThePenaltyEnergyOfTheOverlap) {
  const double volume = 1e-6, bulk = 1e4, density = 1000, v0 = 0.05, gap = 2e-4;
  const double size = std::cbrt(volume), k = bulk * size, m = density * volume;
  const double omega = std::sqrt(2 * k / m), u = 2 * v0, h = 1e-3 / omega;
  const double touch = gap / u, end = touch + 1 / omega;
  const double start = size + gap;  // centre distance at t = 0: r + r + g
  const std::string material =
      fmt::format("{{density: {}, bulk_modulus: {}, shear_modulus: {}}}", density, bulk, bulk);
  const std::string yaml = fmt::format(
      "time: {{end: {0}, dt: {1}}}\nintegrator: {{type: velocity_verlet}}\n"
      "contact: {{self: true}}\nbodies:\n"
      "  - {{geometry: {{points: {{file: a.txt}}}}, resolution: {2}, material: {3}}}\n"
      "  - {{geometry: {{points: {{file: b.txt}}}}, resolution: {2}, material: {3}}}\n"
      "probes:\n"
      "  - {{name: a, region: {{sphere: {{center: [0, 0, 0], radius: {4}}}}}}}\n"
      "  - {{name: b, region: {{sphere: {{center: [{5}, 0, 0], radius: {4}}}}}}}\n"
      "output: {{every: {0}}}\n",
      end, h, size, material, 0.3 * size, start);
  const test::CaseRun run =
      test::run_case("ledger_self_contact", yaml, "",
                     {{"a.txt", pair(0, volume, v0)}, {"b.txt", pair(start, volume, -v0)}});
  ASSERT_EQ(run.outcome.exit_code, 0) << run.outcome.output;
  const auto columns = test::read_probes(run.out / "probes.csv");
  const double overlap =
      size - (start + columns.at("b.disp_x").back() - columns.at("a.disp_x").back());
  const double penalty = 2 * 0.5 * k * overlap * overlap;  // two contacts
  const double booked = run.energy.at("contact_loss");
  const double bound = 2 * k * (u * h) * (u * h) / 8;
  std::printf(
      "overlap %.6e m (analytic %.6e m): contact_loss %.6e J, 1/2 k p^2 %.6e J, "
      "excess %.3e of it (bound %.3e)\n",
      overlap, u / omega * std::sin(1.0), booked, penalty, booked / penalty - 1, bound / penalty);
  EXPECT_GE(booked, penalty);
  EXPECT_LE(booked, penalty + bound);
}

const char* kLatticeMaterial = "{density: 1000, bulk_modulus: 1.0e6, shear_modulus: 1.0e6}";

// A kinematic box moving at V along x strikes a free 4 × 4 × 4 lattice block at rest (no gravity)
// and throws it off at a centre-of-mass speed u; the run ends long after they parted. The box's
// force F on the block does the work ∫ F·v dt = ∫ F·V dt + ∫ F·(v − V) dt: force times the box's
// distance, V·∫F dt = V M u, plus the work of the penalty over the relative motion, which is
// what the penalty stores (`stored_energy`) and gives back: zero once the contact has opened. So
// collider_work, which books the first term (docs/output.md), is V M u, with u from the block's
// mean position over the last probe interval (free flight). Velocity Verlet's momentum gained is
// Σ h (F_n + F_{n+1})/2 = h Σ F_n (the force is zero at both ends) and the books take h V·F_{n+1}
// per step, so the two agree to round-off; u is known to the 9 significant digits of the probes'
// positions, 2 × 5e-10 m over 1 ms at 0.2 m/s: 5e-6 of it. A books that took the penalty's work
// (Σ F·Δy) or its force at the step's start would be off by the first-order term, 1.8e-3 at
// this h.
TEST(ContactLedger, ColliderWorkIsTheBoxSpeedTimesTheMomentumItGave) {
  const int n = 4;
  const double spacing = 0.01, speed = 0.1, end = 0.02, h = 4e-6;
  const double mass = n * n * n * 1000 * spacing * spacing * spacing;
  const std::string yaml = fmt::format(
      "time: {{end: {0}, dt: {1}}}\nintegrator: {{type: velocity_verlet}}\nbodies:\n"
      "  - {{geometry: {{points: {{file: block.txt}}}}, resolution: {2}, material: {3}}}\n"
      "colliders:\n"
      "  - {{box: {{min: [-0.1, -0.1, -0.1], max: [{4}, 0.1, 0.1]}}, velocity: [{5}, 0, 0]}}\n"
      "probes:\n  - {{name: block, region: {{box: {{min: [-1, -1, -1], max: [1, 1, 1]}}}}}}\n"
      "output: {{every: {0}, probe_every: {6}}}\n",
      end, h, spacing, kLatticeMaterial, -0.5 * spacing - 1e-4, speed, end / 20);
  const test::CaseRun run =
      test::run_case("ledger_box_push", yaml, "", {{"block.txt", lattice(n, spacing, 0.0)}});
  ASSERT_EQ(run.outcome.exit_code, 0) << run.outcome.output;
  const auto columns = test::read_probes(run.out / "probes.csv");
  const auto& t = columns.at("time");
  const auto& x = columns.at("block.pos_x");
  const std::size_t last = t.size() - 1;
  const double u = (x[last] - x[last - 1]) / (t[last] - t[last - 1]);
  const double expected = speed * mass * u, work = run.energy.at("collider_work");
  std::printf("h %.1e: block speed %.6f m/s; collider_work %.9e J, V M u %.9e J (relative %.3e)\n",
              h, u, work, expected, work / expected - 1);
  EXPECT_NEAR(work, expected, 5e-6 * expected);
  EXPECT_EQ(columns.at("stored_energy").back(), 0.0);  // parted: nothing stored
}

// A lattice block sliding at v0 on a ground plane with friction μ under gravity: the normal
// penalty carries its weight, N = M g on average, so friction μ N decelerates it at μ g
// (docs/config.md, `contact.friction`) until it stops after d = v0²/(2μg). Once stopped it
// rocks on its penalty springs, its mean x moving by a few μm: d is the mean of the rows after
// 1.2 × the stopping time v0/(μg), and their spread (plus v0 h, one step's travel) bounds how well
// d is known. collider_work is friction's work, −μ M g d, plus the normal force's: conservative,
// and no larger than what gravity put in pressing the block into the plane (gravity_work); the
// same budget covers N's fluctuation about M g while the block bounces. The books are a
// first-order quadrature (box test above), so collider_work is extrapolated from h and h/2,
// 2W(h/2) − W(h); its first-order error at h = stable/9 is 7e-4 of the work, its O(h²)
// remainder ~5e-7.
TEST(ContactLedger, FrictionWorkIsMuMGTimesTheSlidingDistance) {
  const int n = 4;
  const double spacing = 0.01, v0 = 0.3, mu = 0.5, g = 9.81, end = 0.1;
  const double mass = n * n * n * 1000 * spacing * spacing * spacing;
  double work[2], d = 0, spread = 0, pressing = 0, h = 0;
  for (const int halving : {0, 1}) {
    h = 1e-5 / (1 + halving);
    const std::string yaml = fmt::format(
        "time: {{end: {0}, dt: {1}}}\nintegrator: {{type: velocity_verlet}}\n"
        "gravity: [0, 0, {2}]\ncontact: {{friction: {3}}}\nbodies:\n"
        "  - {{geometry: {{points: {{file: block.txt}}}}, resolution: {4}, material: {5}}}\n"
        "colliders:\n  - {{plane: {{point: [0, 0, {6}], normal: [0, 0, 1]}}}}\n"
        "probes:\n  - {{name: block, region: {{box: {{min: [-1, -1, -1], max: [1, 1, 1]}}}}}}\n"
        "output: {{every: {0}, probe_every: {7}}}\n",
        end, h, -g, mu, spacing, kLatticeMaterial, -0.5 * spacing, end / 50);
    const test::CaseRun run = test::run_case(fmt::format("ledger_friction_{}", halving), yaml, "",
                                             {{"block.txt", lattice(n, spacing, v0)}});
    ASSERT_EQ(run.outcome.exit_code, 0) << run.outcome.output;
    const auto columns = test::read_probes(run.out / "probes.csv");
    const auto& t = columns.at("time");
    const auto& x = columns.at("block.disp_x");
    double sum = 0, lo = 1e300, hi = -1e300;
    int rows = 0;
    for (std::size_t r = 0; r < t.size(); ++r) {
      if (t[r] < 1.2 * v0 / (mu * g)) continue;
      sum += x[r], ++rows;
      lo = std::min(lo, x[r]), hi = std::max(hi, x[r]);
    }
    ASSERT_GE(rows, 5);
    d = sum / rows;
    spread = hi - lo;
    work[halving] = run.energy.at("collider_work");
    pressing = std::abs(run.energy.at("gravity_work"));
    std::printf("h %.1e: slid %.6e m (spread %.1e m), collider_work %.6e J, gravity_work %.3e J\n",
                h, d, spread, work[halving], pressing);
  }
  const double stop = v0 * v0 / (2 * mu * g), friction = -mu * mass * g * d;
  const double extrapolated = 2 * work[1] - work[0];
  const double budget = pressing + mu * mass * g * (spread + v0 * h);
  std::printf(
      "d %.6e m against v0^2/(2 mu g) %.6e m (bound %.1e m); extrapolated collider_work "
      "%.6e J against -mu M g d %.6e J: off by %.2e J (bound %.2e J)\n",
      d, stop, spread + v0 * h, extrapolated, friction, extrapolated - friction, budget);
  EXPECT_NEAR(d, stop, spread + v0 * h);
  EXPECT_NEAR(extrapolated, friction, budget);
}

}  // namespace
}  // namespace fissure
