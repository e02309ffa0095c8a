#pragma once
// OpenBLAS runs its own thread pool beside OpenMP's. A supernodal triangular solve is a chain
// of small BLAS-2 calls, and waking the pool for each costs more than it saves (measured on the
// 857-particle glass bar: 1.66 s with two BLAS threads, 0.95 s with one, same answer); a
// factorization's BLAS-3 calls gain from it. Without OpenBLAS these do nothing.
namespace fissure {

// Sets OpenBLAS's thread count, if the BLAS in use is OpenBLAS.
void set_blas_threads(int threads);

}  // namespace fissure
