#include "integrators/sdirk_tableau.hpp"

#include <cmath>

namespace fissure {

namespace {

// Alexander, SIAM J. Numer. Anal. 14 (1977), Theorem 5: γ the root of γ³ − 3γ² + 3γ/2 − 1/6 in
// (1/6, 1/2), τ = (1 + γ)/2, b₁ = −(6γ² − 16γ + 1)/4, b₂ = (6γ² − 20γ + 5)/4.
SdirkTableau alexander() {
  const double g = 0.43586652150845899942;
  const double t = 0.5 * (1 + g);
  const double b1 = -(6 * g * g - 16 * g + 1) / 4, b2 = (6 * g * g - 20 * g + 5) / 4;
  return {"sdirk3", 3, 3, g, {g, 0, 0, t - g, g, 0, b1, b2, g}, {b1, b2, g}, true};
}

// Hairer & Wanner, Table IV.6.5 (γ = 1/4, c = 1/4, 3/4, 11/20, 1/2, 1), with its embedded
// third-order weights.
SdirkTableau hairer_wanner() {
  return {"sdirk4",
          5,
          4,
          0.25,
          {1. / 4,      0,
           0,           0,
           0,  //
           1. / 2,      1. / 4,
           0,           0,
           0,  //
           17. / 50,    -1. / 25,
           1. / 4,      0,
           0,  //
           371. / 1360, -137. / 2720,
           15. / 544,   1. / 4,
           0,  //
           25. / 24,    -49. / 48,
           125. / 16,   -85. / 12,
           1. / 4},
          {25. / 24, -49. / 48, 125. / 16, -85. / 12, 1. / 4},
          true,
          {59. / 48, -17. / 96, 225. / 32, -85. / 12, 0}};
}

// Kennedy & Carpenter, Appl. Numer. Math. 44 (2003), ARK4(3)6L[2]SA, its implicit tableau
// (ESDIRK): an explicit first stage, then five with γ = 1/4 (c = 1/2, 83/250, 31/50, 17/20, 1),
// stiffly accurate, L-stable, stage order 2; with its embedded third-order weights b̂.
SdirkTableau kennedy_carpenter() {
  // clang-format off
  const std::vector<double> a = {
      0,                           0,                      0,                      0,                  0,             0,
      1. / 4,                      1. / 4,                 0,                      0,                  0,             0,
      8611. / 62500,               -1743. / 31250,         1. / 4,                 0,                  0,             0,
      5012029. / 34652500,         -654441. / 2922500,     174375. / 388108,       1. / 4,             0,             0,
      15267082809. / 155376265600, -71443401. / 120774400, 730878875. / 902184768, 2285395. / 8070912, 1. / 4,        0,
      82889. / 524892,             0,                      15625. / 83664,         69875. / 102672,    -2260. / 8211, 1. / 4};
  // clang-format on
  const std::vector<double> b_embedded = {4586570599. / 29645900160, 0,
                                          178811875. / 945068544,    814220225. / 1159782912,
                                          -3700637. / 11593932,      61727. / 225920};
  return {"esdirk4", 6, 4, 0.25, a, std::vector<double>(a.end() - 6, a.end()), true, b_embedded};
}

}  // namespace

const SdirkTableau& esdirk4_tableau() {
  static const SdirkTableau tableau = kennedy_carpenter();
  return tableau;
}

const SdirkTableau& sdirk3_tableau() {
  static const SdirkTableau tableau = alexander();
  return tableau;
}

const SdirkTableau& sdirk4_tableau() {
  static const SdirkTableau tableau = hairer_wanner();
  return tableau;
}

}  // namespace fissure
