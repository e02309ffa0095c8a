#include "parallel/collective.hpp"

#include <fmt/format.h>

#include <climits>
#include <stdexcept>

#include "core/error.hpp"
#include "parallel/index_exchange.hpp"

namespace fissure {

namespace {

void check(int code, const char* what) {
  if (code != MPI_SUCCESS) throw std::runtime_error(fmt::format("MPI: {} failed", what));
}

std::string message_of(const std::exception_ptr& error) {
  try {
    std::rethrow_exception(error);
  } catch (const std::exception& e) {
    return e.what();
  } catch (...) {
    return "an unknown error";
  }
}

}  // namespace

void agree_on_error(MPI_Comm comm, std::exception_ptr error) {
  int rank = 0;
  check(MPI_Comm_rank(comm, &rank), "MPI_Comm_rank");
  const int mine = error ? rank : INT_MAX;
  int first = INT_MAX;
  check(MPI_Allreduce(&mine, &first, 1, MPI_INT, MPI_MIN, comm), "MPI_Allreduce");
  if (first == INT_MAX) return;
  std::string message = rank == first ? message_of(error) : std::string();
  int length = static_cast<int>(message.size());
  check(MPI_Bcast(&length, 1, MPI_INT, first, comm), "MPI_Bcast");
  message.resize(length);
  check(MPI_Bcast(message.data(), length, MPI_CHAR, first, comm), "MPI_Bcast");
  if (error) std::rethrow_exception(error);
  throw RunError(fmt::format("rank {}: {}", first, message));
}

namespace {

// gather_owned for entries of type T, `width` per row, sent as bytes.
// `own`: this rank's first entry.
template <class T>
std::vector<T> gather_rows(MPI_Comm comm, const std::vector<int>& boundaries, const T* own,
                           int width) {
  if (boundaries.empty()) throw std::invalid_argument("gather_owned: no boundaries");
  const int rank = rank_in_split(comm, boundaries, boundaries.back(), "gather_owned");
  const int size = static_cast<int>(boundaries.size()) - 1;
  const int entry = width * static_cast<int>(sizeof(T));
  std::vector<int> counts(size), displacements(size);
  for (int r = 0; r < size; ++r) {
    counts[r] = (boundaries[r + 1] - boundaries[r]) * entry;
    displacements[r] = boundaries[r] * entry;
  }
  std::vector<T> gathered(rank == 0 ? static_cast<std::size_t>(boundaries.back()) * width : 0);
  check(MPI_Gatherv(own, counts[rank], MPI_BYTE, gathered.data(), counts.data(),
                    displacements.data(), MPI_BYTE, 0, comm),
        "MPI_Gatherv");
  return gathered;
}

}  // namespace

std::vector<double> gather_owned(MPI_Comm comm, const std::vector<int>& boundaries,
                                 const double* own, int width) {
  return gather_rows(comm, boundaries, own, width);
}

std::vector<std::uint8_t> gather_owned(MPI_Comm comm, const std::vector<int>& boundaries,
                                       const std::uint8_t* own, int width) {
  return gather_rows(comm, boundaries, own, width);
}

void sum_over_ranks(MPI_Comm comm, std::vector<double>& values) {
  int size = 1;
  check(MPI_Comm_size(comm, &size), "MPI_Comm_size");
  const int count = static_cast<int>(values.size());
  std::vector<double> all(static_cast<std::size_t>(size) * count);
  check(MPI_Allgather(values.data(), count, MPI_DOUBLE, all.data(), count, MPI_DOUBLE, comm),
        "MPI_Allgather");
  for (int k = 0; k < count; ++k) {
    double sum = all[k];
    for (int r = 1; r < size; ++r) sum += all[static_cast<std::size_t>(r) * count + k];
    values[k] = sum;
  }
}

double sum_over_ranks(MPI_Comm comm, double value) {
  std::vector<double> values = {value};
  sum_over_ranks(comm, values);
  return values[0];
}

bool any_over_ranks(MPI_Comm comm, bool value) {
  int mine = value, any = mine;
  check(MPI_Allreduce(&mine, &any, 1, MPI_INT, MPI_MAX, comm), "MPI_Allreduce");
  return any != 0;
}

double max_over_ranks(MPI_Comm comm, double value) {
  double largest = value;
  check(MPI_Allreduce(&value, &largest, 1, MPI_DOUBLE, MPI_MAX, comm), "MPI_Allreduce");
  return largest;
}

int min_over_ranks(MPI_Comm comm, int value) {
  int smallest = value;
  check(MPI_Allreduce(&value, &smallest, 1, MPI_INT, MPI_MIN, comm), "MPI_Allreduce");
  return smallest;
}

}  // namespace fissure
