#!/usr/bin/env bash
# Compare Fissure's elastic explicit step against LAMMPS pair_style peri/lps.
#
# Usage: bench/run_bench.sh [BUILD_DIR]        (BUILD_DIR defaults to "build")
#
#   (a) runs $BUILD_DIR/bench_elastic_step and echoes its "key value" output;
#   (b) runs LAMMPS serially (1 rank, OMP_NUM_THREADS=1) on a simple-cubic
#       block with the same particle count (bench/lammps/in.peri_lps), with
#       pair_style peri/pmb (bond-based, the bound) and peri/lps (the same
#       model as Fissure's), and converts each Pair time into ns per directed
#       bond per step;
#   (c) prints lammps_ns_per_bond, lammps_pmb_ns_per_bond, both ratios of one
#       thread and the two-thread speed-up against their targets.
#
# Environment overrides:
#   LMP            LAMMPS executable            (default: lmp)
#   LAMMPS_N       particles per edge           (default: cube root of Fissure's
#                                                particle count, else 46)
#   LAMMPS_HORIZON horizon / lattice spacing    (default: 3.0 -> 122 bonds in
#                                                the interior)
#   LAMMPS_STEPS   timed steps                  (default: 20)
#   KEEP_LOGS=1    keep the temp dir with the LAMMPS log instead of deleting it
#
# Exit status: 0 on success, 1 if the Fissure benchmark is missing or failed (the LAMMPS part
# still runs), >1 on LAMMPS/usage errors.
set -euo pipefail

script_dir=$(cd -- "$(dirname -- "${BASH_SOURCE[0]}")" && pwd)
repo_root=$(cd -- "$script_dir/.." && pwd)

if [[ $# -gt 1 || ${1:-} == -h || ${1:-} == --help ]]; then
  sed -n '2,25p' "${BASH_SOURCE[0]}" | sed 's/^# \{0,1\}//'
  exit 2
fi

build_dir=${1:-build}
# Relative paths: try the current directory first, then the repo root.
if [[ $build_dir != /* && ! -d $build_dir && -d $repo_root/$build_dir ]]; then
  build_dir=$repo_root/$build_dir
fi

lmp_bin=${LMP:-lmp}
lammps_input=$repo_root/bench/lammps/in.peri_lps
horizon_h=${LAMMPS_HORIZON:-3.0}
steps=${LAMMPS_STEPS:-20}

tmpdir=$(mktemp -d "${TMPDIR:-/tmp}/fissure_bench.XXXXXX")
# shellcheck disable=SC2317  # invoked via trap
cleanup() {
  if [[ ${KEEP_LOGS:-0} == 1 ]]; then
    echo "# logs kept in $tmpdir" >&2
  else
    rm -rf -- "$tmpdir"
  fi
}
trap cleanup EXIT

# Last value of "key value" in a file; empty if absent.
get_key() { awk -v k="$2" '$1 == k { v = $2 } END { if (v != "") print v }' "$1"; }

# --------------------------------------------------------------------------
# (a) Fissure
# --------------------------------------------------------------------------
fissure_status=ok
fissure_bin=$build_dir/bench_elastic_step
fissure_out=$tmpdir/fissure.txt
: >"$fissure_out"

echo "=== Fissure: $fissure_bin"
if [[ ! -x $fissure_bin ]]; then
  fissure_status=missing
  echo "!!! Fissure benchmark binary not found (or not executable): $fissure_bin"
  echo "!!! Build it first (e.g. cmake --build $build_dir --target bench_elastic_step)."
  echo "!!! Continuing with the LAMMPS part only."
else
  # Pinned threads: unpinned, the OS migrates them and the 2-thread figure swings by ±15%.
  if OMP_PROC_BIND=${OMP_PROC_BIND:-true} "$fissure_bin" | tee "$fissure_out"; then
    :
  else
    rc=$?
    fissure_status=failed
    echo "!!! $fissure_bin exited with status $rc; its figures are not used."
  fi
fi

f_particles='' f_bonds='' f_t1=''
if [[ $fissure_status == ok ]]; then
  f_particles=$(get_key "$fissure_out" particles)
  f_bonds=$(get_key "$fissure_out" directed_bonds)
  f_t1=$(get_key "$fissure_out" ns_per_bond_1thread)
  if [[ -z $f_t1 ]]; then
    echo "!!! Fissure output has no 'ns_per_bond_1thread' line; ratio unavailable."
  fi
fi

# --------------------------------------------------------------------------
# (b) LAMMPS peri/lps, serial, single thread
# --------------------------------------------------------------------------
if ! command -v "$lmp_bin" >/dev/null 2>&1; then
  echo "error: LAMMPS executable '$lmp_bin' not found (set LMP=...)" >&2
  exit 3
fi
if [[ ! -f $lammps_input ]]; then
  echo "error: LAMMPS input not found: $lammps_input" >&2
  exit 3
fi

if [[ -n ${LAMMPS_N:-} ]]; then
  n=$LAMMPS_N
elif [[ -n $f_particles ]]; then
  # nearest integer cube root of Fissure's particle count
  n=$(awk -v p="$f_particles" 'BEGIN { c = int(exp(log(p) / 3) + 0.5);
        while ((c + 1)^3 <= p) c++; while (c > 1 && c^3 > p) c--;
        if ((c + 1)^3 - p < p - c^3) c++; print c }')
else
  n=46
fi

# One serial LAMMPS run of pair style $1 (lps or pmb); prints its figures as "<$2>key value" lines
# and leaves its Pair ns per directed bond per step in lammps_ns, its counts in l_atoms, l_bonds.
run_lammps() {
  local style=$1 prefix=$2
  local lammps_log=$tmpdir/log.$style.lammps lammps_screen=$tmpdir/screen.$style.lammps
  echo
  echo "=== LAMMPS: $lmp_bin, pair_style peri/$style, n=$n (n^3=$((n * n * n)) particles), horizon=${horizon_h}a, steps=$steps"
  echo "    OMP_NUM_THREADS=1 $lmp_bin -in $lammps_input -var style $style -var n $n -var horizon_h $horizon_h -var steps $steps -log $lammps_log"
  local t_start t_end
  t_start=$(date +%s.%N)
  if ! (cd "$tmpdir" && OMP_NUM_THREADS=1 "$lmp_bin" -in "$lammps_input" -var style "$style" \
          -var n "$n" -var horizon_h "$horizon_h" -var steps "$steps" \
          -log "$lammps_log" >"$lammps_screen" 2>&1); then
    echo "error: LAMMPS run failed; last lines of its output:" >&2
    tail -n 20 "$lammps_screen" >&2
    KEEP_LOGS=1
    exit 4
  fi
  t_end=$(date +%s.%N)

  # Parse the log.  The timed run is the last "Loop time" / "Pair |" block
  # ("run 0 post no" before it prints a Loop line but no breakdown).
  local l_pair l_loop l_steps
  read -r l_pair l_loop l_steps l_atoms l_bonds < <(awk '
    /^Loop time of / {
      loop = $4
      for (i = 1; i <= NF; i++) {
        if ($i == "for")  steps = $(i + 1)
        if ($i == "with") atoms = $(i + 1)
      }
    }
    /^Pair[ \t]*\|/ { split($0, f, "|"); pair = f[3] + 0 }
    /^[ \t]*total # of bonds =/ { bonds = $NF }
    END { printf "%s %s %s %s %s\n",
          (pair == "" ? "NA" : pair), (loop == "" ? "NA" : loop),
          (steps == "" ? "NA" : steps), (atoms == "" ? "NA" : atoms),
          (bonds == "" ? "NA" : bonds) }' "$lammps_log")

  local v
  for v in "$l_pair" "$l_loop" "$l_steps" "$l_atoms" "$l_bonds"; do
    if [[ $v == NA ]]; then
      echo "error: could not parse the LAMMPS log (pair=$l_pair loop=$l_loop steps=$l_steps atoms=$l_atoms bonds=$l_bonds)" >&2
      KEEP_LOGS=1
      exit 5
    fi
  done

  # Sanity check: no bond may break (broken bonds are skipped and would make
  # LAMMPS look faster).  Last value of the c_dmgsum thermo column.
  local damage
  damage=$(awk '
    $1 == "Step" { col = 0; for (i = 1; i <= NF; i++) if ($i == "c_dmgsum") col = i; next }
    col && $1 ~ /^[0-9]+$/ && NF >= col { d = $col }
    /^Loop time/ { col = 0 }
    END { print (d == "" ? "NA" : d) }' "$lammps_log")
  if [[ $damage == NA ]]; then
    echo "warning: could not read the damage sum from the LAMMPS log"
  elif awk -v d="$damage" 'BEGIN { exit !(d + 0 != 0) }'; then
    echo "warning: LAMMPS damage sum is $damage (bonds broke); the timing is not comparable"
  fi

  awk -v pair="$l_pair" -v loop="$l_loop" -v steps="$l_steps" -v p="$prefix" \
      -v atoms="$l_atoms" -v bonds="$l_bonds" -v t0="$t_start" -v t1="$t_end" \
      -v damage="$damage" 'BEGIN {
    printf "%sparticles %d\n", p, atoms
    printf "%sdirected_bonds %d\n", p, bonds
    printf "%sbonds_per_particle %.3f\n", p, bonds / atoms
    printf "%ssteps %d\n", p, steps
    printf "%spair_seconds %.6g\n", p, pair
    printf "%sloop_seconds %.6g\n", p, loop
    printf "%swall_seconds %.2f\n", p, t1 - t0
    printf "%sdamage_sum %s\n", p, damage
    printf "%sns_per_bond_looptime %.3f\n", p, loop / steps / bonds * 1e9
  }'
  lammps_ns=$(awk -v pair="$l_pair" -v steps="$l_steps" -v bonds="$l_bonds" \
                  'BEGIN { printf "%.3f", pair / steps / bonds * 1e9 }')
}

# The bond-based PMB model first: a lower bound on what any peridynamic kernel costs there.
run_lammps pmb lammps_pmb_
pmb_ns=$lammps_ns
run_lammps lps lammps_

# --------------------------------------------------------------------------
# (c) Comparison
# --------------------------------------------------------------------------
echo
echo "=== Comparison (ns per directed bond per step; LAMMPS: Pair time, 1 rank, 1 thread)"
echo "lammps_ns_per_bond $lammps_ns"
echo "lammps_pmb_ns_per_bond $pmb_ns"
if [[ -n $f_t1 ]]; then
  f_t2=$(get_key "$fissure_out" ns_per_bond_2threads)
  awk -v l="$lammps_ns" -v f="$f_t1" -v pmb="$pmb_ns" -v f2="$f_t2" 'BEGIN {
    if (f + 0 > 0) {
      printf "ratio_lammps_over_fissure_1thread %.3f\n", l / f
      printf "ratio_fissure_over_lammps_1thread %.3f (target <= 0.12)\n", f / l
      printf "ratio_fissure_over_lammps_pmb_1thread %.3f\n", f / pmb
      if (f2 + 0 > 0) printf "speedup_2threads %.2f (target >= 1.85)\n", f / f2
    } else print "ratio_lammps_over_fissure_1thread NA"
  }'
  if [[ -n $f_particles && $f_particles != "$l_atoms" ]]; then
    echo "note: particle counts differ (fissure $f_particles, lammps $l_atoms)"
  fi
  if [[ -n $f_particles && -n $f_bonds ]]; then
    awk -v b="$f_bonds" -v p="$f_particles" -v lb="$l_bonds" -v lp="$l_atoms" 'BEGIN {
      printf "note: bonds/particle fissure %.2f vs lammps %.2f\n", b / p, lb / lp }'
  fi
else
  echo "ratio_lammps_over_fissure_1thread NA   (fissure figures unavailable: $fissure_status)"
fi

if [[ $fissure_status != ok ]]; then
  exit 1
fi
exit 0
