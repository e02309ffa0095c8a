#include "fracture/prefilter_room.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace fissure {

double prefilter_room_portable(int begin, int end, const int* neighbor, const float* bound,
                               const double* y, int i) {
  const double yi0 = y[3 * i], yi1 = y[3 * i + 1], yi2 = y[3 * i + 2];
  double room = std::numeric_limits<double>::infinity();
  for (int b = begin; b < end; ++b) {
    const double* yj = y + 3 * neighbor[b];
    const double d0 = yj[0] - yi0, d1 = yj[1] - yi1, d2 = yj[2] - yi2;
    room = std::min(room, bound[b] - std::sqrt(d0 * d0 + d1 * d1 + d2 * d2));
  }
  return room;
}

PrefilterRoom prefilter_room() {
  const PrefilterRoom simd = prefilter_room_avx512();
  return simd ? simd : prefilter_room_portable;
}

}  // namespace fissure
