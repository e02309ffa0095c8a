#pragma once
// What all ranks must agree on: an error raised on one rank stops every rank
// with its message, never a hang; and the owned pieces of an array brought together on rank 0.
#include <mpi.h>

#include <cstdint>
#include <exception>
#include <string>
#include <vector>

namespace fissure {

// After `work` threw (error) or not (nullptr) on this rank: if it threw on any rank, every rank
// throws, the rank that threw its own exception and the others a RunError "rank R: <what>" with
// the message of the lowest rank that threw. Collective: every rank calls it once per agreement.
void agree_on_error(MPI_Comm comm, std::exception_ptr error);

// Runs `work` on this rank and agrees on its outcome (agree_on_error). `work` must not make
// collective calls itself: a rank that threw before one would leave the others waiting in it.
template <class Work>
void agree(MPI_Comm comm, Work&& work) {
  std::exception_ptr error;
  try {
    work();
  } catch (...) {
    error = std::current_exception();
  }
  agree_on_error(comm, error);
}

// The entries [boundaries[r] * width, boundaries[r + 1] * width) of an array split over the
// ranks, each rank r's from `own` (its first owned entry, wherever its own numbering keeps it:
// Families), gathered on rank 0 in the global numbering (boundaries.back() * width values);
// empty on the other ranks. Collective.
std::vector<double> gather_owned(MPI_Comm comm, const std::vector<int>& boundaries,
                                 const double* own, int width);
// The same for bytes (per-bond flags, with the rows' first bonds as the boundaries).
std::vector<std::uint8_t> gather_owned(MPI_Comm comm, const std::vector<int>& boundaries,
                                       const std::uint8_t* own, int width);

// Each entry summed over the ranks in rank order, the same bits on every rank whatever the MPI
// library's reduction order. Collective.
void sum_over_ranks(MPI_Comm comm, std::vector<double>& values);
double sum_over_ranks(MPI_Comm comm, double value);
// Whether `value` holds on some rank (every rank gets the same answer). Collective.
bool any_over_ranks(MPI_Comm comm, bool value);
double max_over_ranks(MPI_Comm comm, double value);
int min_over_ranks(MPI_Comm comm, int value);

}  // namespace fissure
