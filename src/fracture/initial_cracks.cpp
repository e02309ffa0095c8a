#include "fracture/initial_cracks.hpp"

#include <algorithm>
#include <cmath>

namespace fissure {

namespace {

bool crosses_plane(const Crack& crack, const double* a, const double* b) {
  double da = 0, db = 0;
  for (int k = 0; k < 3; ++k) {
    da += (a[k] - crack.point[k]) * crack.normal[k];
    db += (b[k] - crack.point[k]) * crack.normal[k];
  }
  if ((da > 0) == (db > 0) || da == db) return false;
  if (!crack.bounded) return true;
  const double t = da / (da - db);
  double p[3];
  for (int k = 0; k < 3; ++k) p[k] = a[k] + t * (b[k] - a[k]);
  return crack.region.contains(p);
}

// Slab test: the segment a + t(b − a), t ∈ [0, 1], meets the axis-aligned box.
bool meets_box(const Region& box, const double* a, const double* b) {
  double enter = 0, leave = 1;
  for (int k = 0; k < 3; ++k) {
    const double d = b[k] - a[k];
    if (d == 0) {
      if (a[k] < box.min[k] || a[k] > box.max[k]) return false;
      continue;
    }
    double t0 = (box.min[k] - a[k]) / d, t1 = (box.max[k] - a[k]) / d;
    if (t0 > t1) std::swap(t0, t1);
    enter = std::max(enter, t0);
    leave = std::min(leave, t1);
    if (enter > leave) return false;
  }
  return true;
}

}  // namespace

bool crosses(const Crack& crack, const double* a, const double* b) {
  return crack.kind == Crack::Kind::plane ? crosses_plane(crack, a, b)
                                          : meets_box(crack.region, a, b);
}

}  // namespace fissure
