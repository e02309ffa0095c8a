// ARKODE's adaptive runs against their tolerances on a small elastic vibration: the error of a
// probe particle stays within 10× of what rtol and atol allow, and tightening the tolerances in
// the middle of a run makes ARKODE reject the step sized for the looser ones.
#include <gtest/gtest.h>

#include <cmath>

#include "integrators/arkode.hpp"
#include "support/vibration.hpp"

namespace fissure {
namespace {

ArkodeSettings adaptive(const char* method, double rtol, double atol) {
  ArkodeSettings s;
  s.method = &arkode_method(method, "test");
  s.rtol = rtol;
  s.atol = atol;
  s.reuse_factor = true;  // what settings made in code had before arkode's own default
  return s;
}

// Index of the particle that the initial deformation moves most: the probe.
int probe_particle(const test::Vibration& v) {
  int best = 0;
  double largest = 0;
  for (int i = 0; i < v.scene.particles.count(); ++i) {
    double d = 0;
    for (int k = 0; k < 3; ++k)
      d += std::pow(v.initial.position[3 * i + k] - v.scene.particles.reference[3 * i + k], 2);
    if (d > largest) largest = d, best = i;
  }
  return best;
}

// The probe's positions at the frame times, integrated adaptively (one ARKODE step per call,
// stopping exactly on each frame).
std::vector<std::array<double, 3>> probe_track(test::Vibration& v, Integrator& integrator,
                                               int probe, double frame, int frames) {
  State s = v.initial;
  std::vector<std::array<double, 3>> track;
  for (int f = 1; f <= frames; ++f) {
    while (f * frame - s.time > 1e-12 * frame) integrator.step(*v.dynamics, s, f * frame - s.time);
    track.push_back({s.position[3 * probe], s.position[3 * probe + 1], s.position[3 * probe + 2]});
  }
  return track;
}

class ArkodeAdaptive : public ::testing::TestWithParam<const char*> {};

// Over two periods of the block's slowest mode (about 2.4 ms), the probe's position error
// |y − y_ref| stays below 10 (rtol A + atol) at every frame, A the probe's largest displacement
// from its start, for rtol = 1e-4 and 1e-6.
// The reference is VERNER_8_5_6 at rtol 1e-12. ARKODE controls the local error per step, so the
// global error may exceed one tolerance; the required factor 10 bounds that growth.
TEST_P(ArkodeAdaptive, ProbeErrorWithinTenTimesTheTolerance) {
  auto v = test::make_vibration();
  const int probe = probe_particle(*v);
  const double frame = 5e-4;
  const int frames = 10;
  auto reference_integrator = make_integrator(
      integrator_settings("arkode", adaptive("VERNER_8_5_6", 1e-12, 1e-15)), "test");
  const auto reference = probe_track(*v, *reference_integrator, probe, frame, frames);
  for (const double rtol : {1e-4, 1e-6}) {
    const double atol = 1e-3 * rtol;
    auto integrator =
        make_integrator(integrator_settings("arkode", adaptive(GetParam(), rtol, atol)), "test");
    const auto track = probe_track(*v, *integrator, probe, frame, frames);
    // ARKODE integrates the displacement from the first state (docs/integrators.md), so rtol
    // weighs the probe's motion: its amplitude over the run is the scale.
    double amplitude = 0, worst = 0;
    for (int f = 0; f < frames; ++f) {
      double error = 0, motion = 0;
      for (int k = 0; k < 3; ++k) {
        error += std::pow(track[f][k] - reference[f][k], 2);
        motion += std::pow(reference[f][k] - v->initial.position[3 * probe + k], 2);
      }
      amplitude = std::max(amplitude, std::sqrt(motion));
      worst = std::max(worst, std::sqrt(error));
    }
    worst /= rtol * amplitude + atol;
    std::printf("%s rtol %.0e: worst probe error %.2f of (rtol × amplitude + atol)\n", GetParam(),
                rtol, worst);
    EXPECT_LT(worst, 10.0) << "rtol " << rtol;
  }
}

// A run at rtol 1e-3 whose tolerances drop to 1e-9 halfway: the step sized for 1e-3 fails the
// error test under 1e-9, so the error-test failures grow.
TEST_P(ArkodeAdaptive, TighteningTheToleranceRejectsSteps) {
  auto v = test::make_vibration();
  Arkode integrator(adaptive(GetParam(), 1e-3, 1e-6), "test");
  State s = v->initial;
  const double half = 2.5e-3;
  while (half - s.time > 1e-12 * half) integrator.step(*v->dynamics, s, half - s.time);
  auto failures = [&] {
    for (const auto& [name, value] : integrator.statistics())
      if (name == "error_test_failures") return value;
    return -1.0;
  };
  const double before = failures();
  integrator.set_tolerances(1e-9, 1e-12);
  integrator.step(*v->dynamics, s, half);
  const double after = failures();
  std::printf("%s: error-test failures %.0f before tightening, %.0f after one step\n", GetParam(),
              before, after);
  EXPECT_GT(after, before);
}

INSTANTIATE_TEST_SUITE_P(Methods, ArkodeAdaptive,
                         ::testing::Values("DORMAND_PRINCE_7_4_5", "ARK436L2SA"),
                         [](const auto& info) { return std::string(info.param); });

}  // namespace
}  // namespace fissure
