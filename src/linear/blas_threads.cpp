#include "linear/blas_threads.hpp"

// Declared weak: the symbol is resolved only when the process's BLAS is OpenBLAS.
extern "C" void openblas_set_num_threads(int) __attribute__((weak));

namespace fissure {

void set_blas_threads(int threads) {
  if (openblas_set_num_threads) openblas_set_num_threads(threads);
}

}  // namespace fissure
