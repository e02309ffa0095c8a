#!/usr/bin/env bash
# Weak scaling of the distributed explicit step (docs/mpi.md): bench_distributed_step
# on 1 to 4 ranks with the same particles per rank, one OpenMP thread per rank. Ranks beyond
# the machine's cores are oversubscribed, so their times show the sharing, not the scaling.
# Then the same bar through the whole run loop, `mpirun fissure run bench/distributed_bar.yaml`
# (its checks and energy ledger reduced over the ranks each step, frames at the start and end):
# seconds per step and peak memory per rank from summary.json. Last, implicit steps over the
# ranks: the same bar at λ = 0.02 (about 4,200 particles per rank), petsc_newton's Newmark at
# 0.5 ms (8.5× the explicit limit) for 10 steps, with GAMG (auto's choice over ranks), the
# majoriser's factor and the nearest members' (CHOLMOD on one rank, MUMPS's on several).
#   bench/run_distributed_bench.sh [particles_per_rank=20000] [steps=50]
set -euo pipefail
cd "$(dirname "$0")/.."
export OMP_NUM_THREADS=1 OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
for ranks in 1 2 3 4; do
  echo "== $ranks ranks"
  mpirun -np "$ranks" --oversubscribe build/bench_distributed_step "${1:-20000}" "${2:-50}"
done
echo "== fissure run (the whole run loop), about 100 steps"
for ranks in 1 2 3 4; do
  length=$(awk -v p="${1:-20000}" -v r="$ranks" 'BEGIN { print p * r / 1.48e5 }')
  out=$(mktemp -d)
  mpirun -np "$ranks" --oversubscribe build/fissure run bench/distributed_bar.yaml --out "$out" \
    --set "bodies.0.geometry.box.max=[$length, 0.1, 0.1]" >/dev/null
  python3 -c "import json, sys; s = json.load(open(sys.argv[1])); print('ranks', s['ranks'], \
'particles', s['particles'], 'steps', s['steps'], 'seconds_per_step', \
round(s['seconds_per_step'], 5), 'peak_rss_mb_per_rank', round(s['peak_rss_mb']))" "$out/summary.json"
  rm -rf "$out"
done
echo "== fissure run with petsc_newton (Newmark, dt 0.5 ms, 10 steps), about 4,200 particles per rank"
for preconditioner in gamg majoriser nearest; do
  for ranks in 1 2 3 4; do
    length=$(awk -v r="$ranks" 'BEGIN { print 5000 * r / 1.85e4 }')
    out=$(mktemp -d)
    mpirun -np "$ranks" --oversubscribe build/fissure run bench/distributed_bar.yaml --out "$out" \
      --set "bodies.0.geometry.box.max=[$length, 0.1, 0.1]" --set bodies.0.resolution=0.02 \
      --set integrator.type=petsc_newton --set integrator.scheme=newmark \
      --set "integrator.preconditioner=$preconditioner" --set time.dt=0.0005 \
      --set time.end=0.005 >/dev/null
    python3 -c "import json, sys; s = json.load(open(sys.argv[1])); i = dict(s['integrator_statistics']); \
print(sys.argv[2], 'ranks', s['ranks'], 'particles', s['particles'], 'seconds_per_step', \
round(s['seconds_per_step'], 4), 'newton', int(i['newton_iterations']), 'krylov', \
int(i['krylov_iterations']), 'peak_rss_mb_per_rank', round(s['peak_rss_mb']))" "$out/summary.json" "$preconditioner"
    rm -rf "$out"
  done
done
