#!/usr/bin/env bash
# Whole-process comparison of `pkm hexapod fk` with LinuxCNC's own genhexkins on the same 100 000-row
# strut-length file: a smooth path sampled at 1 kHz on the LinuxCNC hexapod-sim geometry (circles of
# 3 in radius, tilts up to ~9 deg, yaw 11 deg), each row seeded by the previous solution as in a
# servo loop. Two inputs: the exact lengths of `pkm hexapod ik` (shortest round-trip decimals) and
# realistic readings (the same lengths + 2e-5 in Gaussian noise, 6 decimals, as an encoder gives).
# Runs alternate (genhexkins, pkm, genhexkins, ...); the medians and their ratio are printed, and
# the poses of both programs are compared row by row.
# The yardstick is $GENHEXKINS_BENCH: a script that loads Debian's genhexkins.so (LinuxCNC's own
# hexapod kinematics, default hexapod-sim geometry) and solves every row of a CSV `l0,...,l5` seeded
# by the previous solution, printing `x,y,z,a,b,c,status` (status 0 = converged). Without it only
# pkm is timed, and the script says so.
# Usage: benchmarks/fk_vs_genhexkins_whole_process.sh [path/to/pkm] [rows] [pairs]
set -euo pipefail
pkm=${1:-build/bin/pkm}
rows=${2:-100000}
pairs=${3:-7}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

bench=${GENHEXKINS_BENCH:-}
if [ -z "$bench" ] || [ ! -f "$bench" ]; then
  echo "fk vs genhexkins: reference skipped (set GENHEXKINS_BENCH to a genhexkins.so runner script)"
  bench=""
fi

awk -v n="$rows" 'BEGIN { print "x,y,z,a,b,c"; pi = atan2(0, -1);
  for (k = 0; k < n; k++) { t = 2 * pi * k / 10000;
    printf "%.12f,%.12f,%.12f,%.12f,%.12f,%.12f\n", 3*sin(t), 3*(1-cos(t)), 20+sin(2*t), 8.6*sin(t), 6.9*sin(3*t), 11.5*sin(t) } }' \
  > "$work/poses.csv"
"$pkm" hexapod ik --machine hexapod-linuxcnc-sim --poses "$work/poses.csv" | cut -d, -f1-6 > "$work/exact.csv"
awk -F, 'BEGIN { srand(20261126); pi = atan2(0, -1) }
  NR == 1 { print; next }
  { line = "";
    for (i = 1; i <= 6; i++) {
      g = sqrt(-2 * log(1 - rand())) * cos(2 * pi * rand());
      line = line (i > 1 ? "," : "") sprintf("%.6f", $i + 2e-5 * g) }
    print line }' "$work/exact.csv" > "$work/noisy.csv"

# Each timed run writes a new output file: before it (not timed) the last run's file is removed and
# the disks are synced, so that neither program pays for the other's (or its own last run's) output
# (truncating a 12 MB file that was just written costs 2-8 ms on an ext4 VM, and its writeback
# runs on the CPUs during the next run).
fresh() { rm -f "$1"; sync; }

# Times are read from bash's $EPOCHREALTIME (no process is started to read the clock, which would
# add a fork and exec of date(1) to every measured run).
export LC_ALL=C  # a decimal point in $EPOCHREALTIME
median() { printf '%s\n' "$@" | sort -g | awk '{ v[NR] = $1 } END { print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }

run_case() {
  local name=$1 lengths=$2
  local pkm_times=() ref_times=() s e
  for ((i = 0; i < pairs; i++)); do
    if [ -n "$bench" ]; then
      fresh "$work/ref.csv"
      s=$EPOCHREALTIME; bash "$bench" "$lengths" > "$work/ref.csv"; e=$EPOCHREALTIME
      ref_times+=("$(echo "$e - $s" | bc -l)")
    fi
    fresh "$work/pkm.csv"
    s=$EPOCHREALTIME
    "$pkm" hexapod fk --machine hexapod-linuxcnc-sim --lengths "$lengths" --seed 0,0,20,0,0,0 > "$work/pkm.csv"
    e=$EPOCHREALTIME
    pkm_times+=("$(echo "$e - $s" | bc -l)")
  done
  local pkm_med
  pkm_med=$(median "${pkm_times[@]}")
  paste -d, "$work/poses.csv" "$work/pkm.csv" | awk -F, -v name="$name" -v rows="$rows" -v t="$pkm_med" -v pairs="$pairs" '
    NR == 1 { next }
    { if ($14 != "ok") fail++; steps += $13
      for (i = 1; i <= 3; i++) { d = $i - $(i + 6); if (d < 0) d = -d; if (d > maxp) maxp = d }
      for (i = 4; i <= 6; i++) { d = $i - $(i + 6); if (d < 0) d = -d; if (d > maxa) maxa = d } }
    END {
      printf "pkm hexapod fk, %s lengths, whole process: %d rows, median of %d runs %.3f s = %.2f us per row\n", name, rows, pairs, t, 1e6 * t / rows
      printf "  pkm: %d not ok, %.2f Newton steps per row; max |pose - path| %.3g in, %.3g deg\n", fail, steps / rows, maxp, maxa }'
  [ -n "$bench" ] || { echo "  reference skipped"; return; }
  local ref_med
  ref_med=$(median "${ref_times[@]}")
  paste -d, "$work/pkm.csv" "$work/ref.csv" | awk -F, '
    NR == 1 { next }
    { if ($15 != 0) fail++
      for (i = 1; i <= 3; i++) { d = $i - $(i + 8); if (d < 0) d = -d; if (d > maxp) maxp = d }
      for (i = 4; i <= 6; i++) { d = $i - $(i + 8); if (d < 0) d = -d; if (d > maxa) maxa = d } }
    END { printf "  genhexkins: %d not converged; max |pkm - genhexkins| %.3g in, %.3g deg\n", fail, maxp, maxa }'
  printf '  genhexkins (Debian genhexkins.so, same rows and seeding): median %.3f s -> pkm is %.1fx faster\n' \
    "$ref_med" "$(echo "$ref_med / $pkm_med" | bc -l)"
  # For benchmarks/summary.sh: job | pkm s | reference | reference s | target ratio.
  printf 'bench-row|hexapod fk, %d-row path, %s lengths|%s|genhexkins (LinuxCNC)|%s|20\n' \
    "$rows" "$name" "$pkm_med" "$ref_med"
}

run_case exact "$work/exact.csv"
run_case noisy "$work/noisy.csv"
