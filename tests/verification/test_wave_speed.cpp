// A longitudinal wave in a long thin bar travels at the bar speed c = √(E/ρ).
#include <gtest/gtest.h>

#include <cmath>

#include "support/wave_speed.hpp"

namespace fissure {
namespace {

using test::wave_speed_ratio;

TEST(WaveSpeed, LongitudinalPulseTravelsAtBarSpeed) {
  const double ratio = wave_speed_ratio("");
  // The bar is 2.8 horizons across, where the surface effect stiffens it in uniaxial stress:
  // E_eff < 1.10 E (test SurfaceEffect; 1.096 in docs/model.md), never softer. So the speed lies
  // between √(E/ρ) and √(1.10 E/ρ) = 1.049 c.
  EXPECT_GT(ratio, 1.0);
  EXPECT_LT(ratio, std::sqrt(1.10));
}

// With the deviatoric calibration (surface_correction: full, docs/model.md deviation 8) the
// surface stiffening is gone: within the required 1.5% of √(E/ρ) (measured 0.991: the bar's four
// edges keep inexact rows). The `dilatation` model's 1.040 fails it.
TEST(WaveSpeed, FullSurfaceCorrectionTravelsAtBarSpeed) {
  EXPECT_NEAR(wave_speed_ratio(", surface_correction: full"), 1.0, 0.015);
}

}  // namespace
}  // namespace fissure
