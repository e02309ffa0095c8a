#include "integrators/threaded_aij.hpp"

#include <omp.h>

#include "integrators/petsc_session.hpp"

namespace fissure {

namespace {

// y = A x over the row triples of a matrix multiply_over_threads accepted.
PetscErrorCode multiply(Mat a, Vec x, Vec y) {
  PetscFunctionBeginUser;
  PetscInt rows;
  const PetscInt *offsets, *columns;
  PetscBool done;
  PetscCall(MatGetRowIJ(a, 0, PETSC_FALSE, PETSC_FALSE, &rows, &offsets, &columns, &done));
  PetscCheck(done, PETSC_COMM_SELF, PETSC_ERR_SUP, "MatGetRowIJ gave no rows");
  const PetscScalar *values, *in;
  PetscScalar* out;
  PetscCall(MatSeqAIJGetArrayRead(a, &values));
  PetscCall(VecGetArrayRead(x, &in));
  PetscCall(VecGetArrayWrite(y, &out));
#pragma omp parallel for schedule(static)
  for (PetscInt block = 0; block < rows / 3; ++block) {
    const PetscInt r = 3 * block, begin = offsets[r], length = offsets[r + 1] - begin;
    const PetscInt* column = columns + begin;
    const PetscScalar *row0 = values + begin, *row1 = values + offsets[r + 1],
                      *row2 = values + offsets[r + 2];
    PetscScalar sum0 = 0, sum1 = 0, sum2 = 0;
    for (PetscInt k = 0; k < length; ++k) {
      const PetscScalar v = in[column[k]];
      sum0 += row0[k] * v;
      sum1 += row1[k] * v;
      sum2 += row2[k] * v;
    }
    out[r] = sum0;
    out[r + 1] = sum1;
    out[r + 2] = sum2;
  }
  PetscCall(VecRestoreArrayWrite(y, &out));
  PetscCall(VecRestoreArrayRead(x, &in));
  PetscCall(MatSeqAIJRestoreArrayRead(a, &values));
  PetscCall(PetscLogFlops(2.0 * double(offsets[rows])));
  PetscCall(MatRestoreRowIJ(a, 0, PETSC_FALSE, PETSC_FALSE, &rows, &offsets, &columns, &done));
  PetscFunctionReturn(0);
}

}  // namespace

bool multiply_over_threads(Mat a) {
  MatType type;
  petsc_check(MatGetType(a, &type), "MatGetType");
  PetscBool seqaij;
  petsc_check(PetscStrcmp(type, MATSEQAIJ, &seqaij), "PetscStrcmp");
  if (!seqaij) return false;
  PetscInt rows;
  const PetscInt *offsets, *columns;
  PetscBool done;
  petsc_check(MatGetRowIJ(a, 0, PETSC_FALSE, PETSC_FALSE, &rows, &offsets, &columns, &done),
              "MatGetRowIJ");
  bool triples = done && rows % 3 == 0;
  for (PetscInt r = 0; triples && r < rows; r += 3) {
    const PetscInt length = offsets[r + 1] - offsets[r];
    for (int k = 1; k < 3 && triples; ++k) {
      triples = offsets[r + k + 1] - offsets[r + k] == length;
      for (PetscInt c = 0; triples && c < length; ++c)
        triples = columns[offsets[r + k] + c] == columns[offsets[r] + c];
    }
  }
  petsc_check(MatRestoreRowIJ(a, 0, PETSC_FALSE, PETSC_FALSE, &rows, &offsets, &columns, &done),
              "MatRestoreRowIJ");
  if (!triples || omp_get_max_threads() < 2) return false;
  petsc_check(MatSetOption(a, MAT_NEW_NONZERO_LOCATION_ERR, PETSC_TRUE), "MatSetOption");
  petsc_check(MatSetOperation(a, MATOP_MULT, reinterpret_cast<void (*)(void)>(multiply)),
              "MatSetOperation");
  return true;
}

}  // namespace fissure
