#!/usr/bin/env bash
# Cost of one implicit step against the scene's size: bench_implicit_step on the glass cantilever
# at about 1e3, 1e4 and 1e5 particles (one process each, so each peak memory is its own), with
# the default preconditioner (auto) and with `gamg`, `nearest` and `scalar` at every size, backward Euler
# at 300× the explicit estimate. Prints one table: particles, preconditioner, seconds of the first step (it
# factorizes) and of a later one (the second step, repeated: bench_implicit_step.cpp), µs per particle of a later step and its ratio to the smallest
# scene's, Newton and Krylov iterations per step, peak memory. Then, per preconditioner, the spread of
# µs per particle over the sizes (the largest over the smallest: the target is 3) and the
# largest size's peak memory (the target is 8 GB).
#   bench/run_implicit_bench.sh [BUILD_DIR] [SIZES...]     (default: build 1000 10000 100000)
set -euo pipefail
build=${1:-build}
shift || true
sizes=("$@")
((${#sizes[@]})) || sizes=(1000 10000 100000)
# Smallest first: the ratio column is to the smallest scene, the spread's peak the largest's.
mapfile -t sizes < <(printf '%s\n' "${sizes[@]}" | sort -n)
printf '%-10s %-15s %12s %10s %12s %8s %8s %8s %8s\n' particles preconditioner first_step_s step_s \
  us_per_particle ratio newton krylov peak_gb
spreads=()
for preconditioner in auto gamg nearest scalar; do
  base=""
  lowest=""
  highest=""
  for n in "${sizes[@]}"; do
    # Several later steps where one is short, so that the per-step time is not one sample.
    steps=$((n <= 2000 ? 10 : n <= 20000 ? 3 : 1))
    out=$("$build/bench_implicit_step" "$n" "$steps" 300 backward_euler "$preconditioner")
    get() { awk -v k="$1" '$1 == k {print $2}' <<<"$out"; }
    # The integrator's counts are over the first step and all the later ones.
    later=$(awk '$1 == "later_steps" {print $2}' <<<"$out")
    per_step() { awk -v k="$1" -v s="$later" '$1 == k {printf "%.0f", $2 / (s + 1)}' <<<"$out"; }
    per=$(get step_us_per_particle)
    used=$(get preconditioner_chosen)
    used=${used:-$preconditioner}
    [[ -n $base ]] || base=$per
    read -r lowest highest < <(awk -v l="${lowest:-$per}" -v h="${highest:-$per}" -v p="$per" \
      'BEGIN {print (p < l ? p : l), (p > h ? p : h)}')
    peak=$(get peak_memory_gb)
    printf '%-10s %-15s %12s %10s %12s %8.2f %8s %8s %8s\n' "$(get particles)" "$used" \
      "$(get first_step_seconds)" "$(get step_seconds)" "$per" "$(echo "$per / $base" | bc -l)" \
      "$(per_step newton_iterations)" "$(per_step krylov_iterations)" "$peak"
  done
  spreads+=("$(printf '%-15s %6.2f %8s' "$preconditioner" "$(echo "$highest / $lowest" | bc -l)" "$peak")")
done
echo
echo "preconditioner  spread  peak_gb   (spread: largest µs per particle over the smallest across the sizes;"
echo "                                   peak_gb: at the largest size)"
printf '%s\n' "${spreads[@]}"
