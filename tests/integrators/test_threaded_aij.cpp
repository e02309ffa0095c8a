// The preconditioner matrix's threaded product (integrators/threaded_aij.hpp): installed only on
// a MATSEQAIJ whose rows come in threes with one column pattern (not where a row is shorter, has
// another column, or is left over, nor on another type or one thread), kept when values change
// in place, and equal, row by row to round-off, to PETSc's own product of the same matrix. A
// product that skipped a row of a triple, read another row's values or was never installed
// fails.
#include <gtest/gtest.h>
#include <omp.h>
#include <petscmat.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "integrators/petsc_session.hpp"
#include "integrators/threaded_aij.hpp"

namespace fissure {
namespace {

// What keeps a matrix's rows from coming in threes with one column pattern each.
enum class Defect { none, shorter_row, other_column, extra_row };

// A 3N×3N matrix of 3×3 blocks: block row i couples to i and to the particles i ± 1, i ± 7 and
// i ± 40 that exist (a banded, family-like pattern), every entry different. The defects touch
// the last row of block row 5 (its last member is particle 45): shorter_row drops its last entry,
// other_column moves that entry to the next column (particle 46's first, not a member), and
// extra_row adds a row 3N with its diagonal only.
Mat block_matrix(int particles, Defect defect) {
  std::vector<PetscInt> offsets{0}, columns;
  std::vector<PetscScalar> values;
  const int size = 3 * particles + (defect == Defect::extra_row);
  for (int row = 0; row < size; ++row) {
    const int i = row / 3;
    std::vector<int> members;
    for (const int d : {-40, -7, -1, 0, 1, 7, 40})
      if (i + d >= 0 && i + d < particles) members.push_back(i + d);
    if (row == 3 * particles) members = {};
    for (const int j : members)
      for (int c = 0; c < 3; ++c) {
        const bool last = row == 3 * 5 + 2 && j == members.back() && c == 2;
        if (last && defect == Defect::shorter_row) continue;
        columns.push_back(3 * j + c + (last && defect == Defect::other_column));
        values.push_back(std::sin(0.37 * row + 1.3 * columns.back()) + (3 * j + c == row ? 20 : 0));
      }
    if (row == 3 * particles) {
      columns.push_back(row);
      values.push_back(1.0);
    }
    offsets.push_back(static_cast<PetscInt>(columns.size()));
  }
  Mat a;
  petsc_check(MatCreate(PETSC_COMM_SELF, &a), "MatCreate");
  petsc_check(MatSetSizes(a, size, size, size, size), "MatSetSizes");
  petsc_check(MatSetType(a, MATSEQAIJ), "MatSetType");
  if (defect != Defect::extra_row) petsc_check(MatSetBlockSize(a, 3), "MatSetBlockSize");
  petsc_check(MatSeqAIJSetPreallocationCSR(a, offsets.data(), columns.data(), values.data()),
              "MatSeqAIJSetPreallocationCSR");
  return a;
}

using Multiply = void (*)(void);

Multiply product_of(Mat a) {
  Multiply f;
  petsc_check(MatGetOperation(a, MATOP_MULT, &f), "MatGetOperation");
  return f;
}

TEST(ThreadedAij, EqualsPetscsProductRowByRowToRoundOff) {
  ensure_petsc();
  const int threads = omp_get_max_threads();
  omp_set_num_threads(std::max(threads, 2));  // scripts/test runs with OMP_NUM_THREADS=1
  const int particles = 1000;
  Mat threaded = block_matrix(particles, Defect::none), petsc;
  petsc_check(MatDuplicate(threaded, MAT_COPY_VALUES, &petsc), "MatDuplicate");
  ASSERT_TRUE(multiply_over_threads(threaded));
  EXPECT_NE(product_of(threaded), product_of(petsc)) << "PETSc's product was kept";
  Vec x, y_threaded, y_petsc;
  petsc_check(MatCreateVecs(threaded, &x, &y_threaded), "MatCreateVecs");
  petsc_check(VecDuplicate(y_threaded, &y_petsc), "VecDuplicate");
  PetscScalar* in;
  petsc_check(VecGetArray(x, &in), "VecGetArray");
  for (int k = 0; k < 3 * particles; ++k) in[k] = std::cos(2.1 * k);
  petsc_check(VecRestoreArray(x, &in), "VecRestoreArray");
  // values changed in place, as copy_values() does, keep the threaded product
  PetscScalar* values;
  for (Mat a : {threaded, petsc}) {
    petsc_check(MatSeqAIJGetArray(a, &values), "MatSeqAIJGetArray");
    values[7] += 0.5;
    petsc_check(MatSeqAIJRestoreArray(a, &values), "MatSeqAIJRestoreArray");
  }
  EXPECT_NE(product_of(threaded), product_of(petsc)) << "lost with the values";
  petsc_check(MatMult(threaded, x, y_threaded), "MatMult");
  petsc_check(MatMult(petsc, x, y_petsc), "MatMult");
  const PetscScalar *a_values, *t, *p, *xs;
  const PetscInt *offsets, *columns;
  PetscInt rows;
  PetscBool done;
  petsc_check(MatGetRowIJ(petsc, 0, PETSC_FALSE, PETSC_FALSE, &rows, &offsets, &columns, &done),
              "MatGetRowIJ");
  petsc_check(MatSeqAIJGetArrayRead(petsc, &a_values), "MatSeqAIJGetArrayRead");
  petsc_check(VecGetArrayRead(y_threaded, &t), "VecGetArrayRead");
  petsc_check(VecGetArrayRead(y_petsc, &p), "VecGetArrayRead");
  petsc_check(VecGetArrayRead(x, &xs), "VecGetArrayRead");
  double worst = 0;  // |difference| / Σ|a x| of the row
  for (PetscInt r = 0; r < rows; ++r) {
    double size = 0;
    for (PetscInt k = offsets[r]; k < offsets[r + 1]; ++k)
      size += std::abs(a_values[k] * xs[columns[k]]);
    worst = std::max(worst, std::abs(t[r] - p[r]) / size);
  }
  std::printf("%d rows: largest |threaded - PETSc| / sum |a x| of a row %.2e\n", int(rows), worst);
  // |fl(Σ) − Σ| ≤ n u Σ|a x| for either order of a sum of n = 21 products, u = 2⁻⁵³
  EXPECT_LE(worst, 2 * 21 * std::ldexp(1.0, -53));
  petsc_check(VecRestoreArrayRead(x, &xs), "VecRestoreArrayRead");
  petsc_check(VecRestoreArrayRead(y_petsc, &p), "VecRestoreArrayRead");
  petsc_check(VecRestoreArrayRead(y_threaded, &t), "VecRestoreArrayRead");
  petsc_check(MatSeqAIJRestoreArrayRead(petsc, &a_values), "MatSeqAIJRestoreArrayRead");
  petsc_check(MatRestoreRowIJ(petsc, 0, PETSC_FALSE, PETSC_FALSE, &rows, &offsets, &columns, &done),
              "MatRestoreRowIJ");
  for (Vec* v : {&x, &y_threaded, &y_petsc}) petsc_check(VecDestroy(v), "VecDestroy");
  petsc_check(MatDestroy(&threaded), "MatDestroy");
  petsc_check(MatDestroy(&petsc), "MatDestroy");
  omp_set_num_threads(threads);
}

TEST(ThreadedAij, KeepsPetscsProductWhereRowsDoNotComeInThreesOrOneThreadRuns) {
  ensure_petsc();
  const int threads = omp_get_max_threads();
  omp_set_num_threads(std::max(threads, 2));
  for (const Defect defect : {Defect::shorter_row, Defect::other_column, Defect::extra_row}) {
    Mat a = block_matrix(50, defect);
    const Multiply petscs = product_of(a);
    EXPECT_FALSE(multiply_over_threads(a)) << "defect " << int(defect);
    EXPECT_EQ(product_of(a), petscs) << "defect " << int(defect);
    petsc_check(MatDestroy(&a), "MatDestroy");
  }
  Mat whole = block_matrix(50, Defect::none), blocked;
  petsc_check(MatConvert(whole, MATSEQBAIJ, MAT_INITIAL_MATRIX, &blocked), "MatConvert");
  const Multiply blocks = product_of(blocked);
  EXPECT_FALSE(multiply_over_threads(blocked)) << "not MATSEQAIJ";
  EXPECT_EQ(product_of(blocked), blocks);
  petsc_check(MatDestroy(&blocked), "MatDestroy");
  const Multiply petscs = product_of(whole);
  omp_set_num_threads(1);
  EXPECT_FALSE(multiply_over_threads(whole));
  EXPECT_EQ(product_of(whole), petscs) << "one thread: PETSc's product";
  omp_set_num_threads(threads);
  petsc_check(MatDestroy(&whole), "MatDestroy");
}

}  // namespace
}  // namespace fissure
