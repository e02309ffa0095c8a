// The MPI tests' main: PETSc (and with it MPI) is initialised around GoogleTest, and only rank 0
// prints the results; a failure on any rank makes that rank, and so mpirun, exit non-zero.
#include <gtest/gtest.h>
#include <petscsys.h>

#include <cstdio>

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  if (PetscInitialize(&argc, &argv, nullptr, nullptr) != 0) return 2;
  int rank = 0;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  if (rank != 0)
    delete ::testing::UnitTest::GetInstance()->listeners().Release(
        ::testing::UnitTest::GetInstance()->listeners().default_result_printer());
  const int result = RUN_ALL_TESTS();
  int failed = result != 0, any_failed = 0;
  MPI_Allreduce(&failed, &any_failed, 1, MPI_INT, MPI_MAX, PETSC_COMM_WORLD);
  if (any_failed && rank == 0 && !failed) std::printf("[  FAILED  ] on another rank\n");
  PetscFinalize();
  return any_failed;
}
