// The penalty's secant over a step (contact/secant_penalty.hpp): in every branch (both depths in
// contact, entering from a gap, leaving to one, out of contact throughout) its slope times the
// change of depth is the change of ½ k p₊², exactly; its slope and curvature are the derivatives
// of its energy (central differences); it is zero at the start depth and convex. A slope a few
// percent off, an energy integrated from the wrong point or a curvature of the plain penalty
// (k) fails.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "contact/secant_penalty.hpp"

namespace fissure {
namespace {

constexpr double kStiffness = 1.3e9;

double penalty(double p) { return p > 0 ? 0.5 * kStiffness * p * p : 0.0; }

// Start and end depths [m] covering each branch, the series for an entry from a wide gap
// (p < 1e-3 of the gap) and the start exactly touching (p0 = 0).
const double kDepths[] = {-2e-3, -5e-4, -1e-6, 0.0, 1e-9, 3e-7, 4e-4, 1.5e-3};

TEST(SecantPenalty, SlopeTimesTheChangeOfDepthIsTheChangeOfThePenalty) {
  for (double p0 : kDepths)
    for (double p : kDepths) {
      if (p == p0) continue;
      const SecantPenalty s = secant_penalty(kStiffness, p0, p);
      const double change = penalty(p) - penalty(p0);
      const double scale = std::max({penalty(p), penalty(p0), 1e-300});
      EXPECT_NEAR(s.slope * (p - p0), change, 1e-12 * scale) << p0 << " → " << p;
    }
}

TEST(SecantPenalty, SlopeAndCurvatureAreTheEnergysDerivatives) {
  for (double p0 : kDepths)
    for (double p : kDepths) {
      if (p == 0 && p0 <= 0) continue;  // the kink of ½ k p₊² itself
      const double eps = 1e-3 * std::max(std::abs(p), std::abs(p - p0)) + 1e-12;
      const SecantPenalty at = secant_penalty(kStiffness, p0, p);
      const SecantPenalty up = secant_penalty(kStiffness, p0, p + eps),
                          down = secant_penalty(kStiffness, p0, p - eps);
      if (p0 <= 0 && p - eps <= 0) continue;  // a difference across the kink
      // at p = 0 the curvature is continuous but not its derivative: a difference across it
      // errs by O(eps), so the curvature is checked only on one side of it
      const bool across = p - eps < 0 && p + eps > 0;
      // central differences err by O(eps²) relative to the third derivative's scale
      EXPECT_NEAR((up.energy - down.energy) / (2 * eps), at.slope,
                  1e-5 * std::abs(at.slope) + 1e-12 * kStiffness * eps)
          << p0 << " → " << p;
      if (!across) {
        EXPECT_NEAR((up.slope - down.slope) / (2 * eps), at.curvature,
                    1e-5 * std::abs(at.curvature) + 1e-9 * kStiffness)
            << p0 << " → " << p;
      }
    }
}

TEST(SecantPenalty, ZeroAtTheStartConvexAndTheMeanForceInContact) {
  for (double p0 : kDepths) {
    EXPECT_EQ(secant_penalty(kStiffness, p0, p0).energy, 0.0) << p0;
    for (double p : kDepths) {
      const SecantPenalty s = secant_penalty(kStiffness, p0, p);
      EXPECT_GE(s.curvature, 0.0) << p0 << " → " << p;
      // above its tangent at p0, whose slope is the penalty's force there
      const double tangent = (p0 > 0 ? kStiffness * p0 : 0.0) * (p - p0);
      EXPECT_GE(s.energy, tangent - 1e-12 * std::abs(tangent)) << p0 << " → " << p;
      if (p0 > 0 && p > 0) {  // trapezoidal: the mean of k p0 and k p
        EXPECT_DOUBLE_EQ(s.slope, 0.5 * kStiffness * (p0 + p)) << p0 << " → " << p;
      }
    }
  }
}

}  // namespace
}  // namespace fissure
