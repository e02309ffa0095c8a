#!/usr/bin/env bash
# Weak scaling of the distributed explicit step (issue 18; docs/mpi.md): bench_distributed_step
# on 1 to 4 ranks with the same particles per rank, one OpenMP thread per rank. Ranks beyond
# the machine's cores are oversubscribed, so their times show the sharing, not the scaling.
#   bench/run_distributed_bench.sh [particles_per_rank=20000] [steps=50]
set -euo pipefail
cd "$(dirname "$0")/.."
export OMP_NUM_THREADS=1 OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
for ranks in 1 2 3 4; do
  echo "== $ranks ranks"
  mpirun -np "$ranks" --oversubscribe build/bench_distributed_step "${1:-20000}" "${2:-50}"
done
