#!/usr/bin/env bash
# Whole-process benchmark of `pkm hexapod fk` on a 100 000-row strut-length file: a smooth path sampled
# at 1 kHz on the LinuxCNC hexapod-sim geometry (file I/O included), plus an accuracy check of the
# result against the poses the lengths were made from.
# Usage: benchmarks/fk_whole_process.sh [path/to/pkm] [rows]
set -euo pipefail
pkm=${1:-build/bin/pkm}
rows=${2:-100000}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# Poses: 100 s of motion at 1 kHz, circles of 3 in radius with tilts up to ~9 deg and yaw 11 deg.
awk -v n="$rows" 'BEGIN { print "x,y,z,a,b,c"; pi = atan2(0, -1);
  for (k = 0; k < n; k++) { t = 2 * pi * k / 10000;
    printf "%.12f,%.12f,%.12f,%.12f,%.12f,%.12f\n", 3*sin(t), 3*(1-cos(t)), 20+sin(2*t), 8.6*sin(t), 6.9*sin(3*t), 11.5*sin(t) } }' \
  > "$work/poses.csv"
"$pkm" hexapod ik --machine hexapod-linuxcnc-sim --poses "$work/poses.csv" | cut -d, -f1-6 > "$work/lengths.csv"

best=""
for run in 1 2 3 4 5; do
  start=$(date +%s.%N)
  "$pkm" hexapod fk --machine hexapod-linuxcnc-sim --lengths "$work/lengths.csv" > "$work/fk.csv"
  end=$(date +%s.%N)
  t=$(echo "$end - $start" | bc -l)
  if [ -z "$best" ] || [ "$(echo "$t < $best" | bc -l)" = 1 ]; then best=$t; fi
done

paste -d, "$work/poses.csv" "$work/fk.csv" | awk -F, -v rows="$rows" -v best="$best" '
  NR == 1 { next }
  { if ($14 != "ok") fail++;
    for (i = 1; i <= 3; i++) { d = $i - $(i + 6); if (d < 0) d = -d; if (d > maxp) maxp = d }
    for (i = 4; i <= 6; i++) { d = $i - $(i + 6); if (d < 0) d = -d; if (d > maxa) maxa = d }
    steps += $13 }
  END {
    printf "pkm hexapod fk, whole process: %d rows in %.3f s (best of 5) = %.2f us per row\n", rows, best, 1e6 * best / rows;
    printf "  failures: %d; mean Newton steps per row: %.2f\n", fail, steps / rows;
    printf "  max |position error| %.3g in, max |angle error| %.3g deg (inputs printed with 12 decimals)\n", maxp, maxa;
    printf "  reference: genhexkins about 18 us per row whole process -> speed-up %.1fx\n", 18 / (1e6 * best / rows) }'
