#pragma once
// An OpenMP product for the preconditioner's MATSEQAIJ matrix. Debian's PETSc 3.18 multiplies
// an AIJ matrix on one thread; GAMG multiplies by its finest level's matrix (the `nearest`
// stiffness) in every smoothing sweep and residual of every cycle, most of a V-cycle's time at
// 1e5 particles (docs/integrators.md, "The linear solves").
#include <petscmat.h>

namespace fissure {

// Makes MatMult of `a` (MATSEQAIJ, assembled) run over the threads, each row summed in column
// order: true where its rows come in threes sharing one column pattern (a 3×3 block per pair of
// particles, read once per three rows as PETSc's own inode product does) and two or more threads
// run. Elsewhere `a` keeps PETSc's product and false is returned. The product relies on the
// pattern it was installed on, so installing it freezes that pattern
// (MAT_NEW_NONZERO_LOCATION_ERR); values may change (MatSeqAIJGetArray, MatSetValues on the
// pattern, assemblies), and it stays installed, correct on any number of threads.
bool multiply_over_threads(Mat a);

}  // namespace fissure
