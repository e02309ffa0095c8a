#pragma once
// The fracture criterion's prefilter over one row (BondBreaking::find): the least room
// min_b (bound_b − |y_j − y_i|) left between the row's deformed bond lengths and their lower
// bounds of the critical length; negative where some bond may have passed its criterion.
// A portable version and one with AVX-512, chosen at load; the minimum does not depend on the
// order, so both give the same bits.
namespace fissure {

using PrefilterRoom = double (*)(int begin, int end, const int* neighbor, const float* bound,
                                 const double* y, int i);

double prefilter_room_portable(int begin, int end, const int* neighbor, const float* bound,
                               const double* y, int i);
// Null where this build or this CPU has no AVX-512 (F, VL and DQ).
PrefilterRoom prefilter_room_avx512();
// AVX-512 where the CPU has it, else portable.
PrefilterRoom prefilter_room();

}  // namespace fissure
