#pragma once
// An OpenMP product for the preconditioner's MATSEQAIJ matrix. Debian's PETSc 3.18 multiplies
// an AIJ matrix on one thread; GAMG multiplies by its finest level's matrix (the `nearest`
// stiffness) in every smoothing sweep and residual of every cycle, most of a V-cycle's time at
// 1e5 particles (docs/integrators.md, "The linear solves").
#include <petscmat.h>

namespace fissure {

// Makes MatMult of `a` (MATSEQAIJ, assembled) run over the threads, each row summed in column
// order: true where its rows come in threes sharing one column pattern (a 3×3 block per pair of
// particles, read once per three rows as PETSc's own inode product does). Elsewhere `a` keeps
// PETSc's product and false is returned. Call again after an assembly (MatAssemblyEnd may set
// PETSc's product back); values changed in place (MatSeqAIJGetArray) keep it.
bool multiply_over_threads(Mat a);

}  // namespace fissure
