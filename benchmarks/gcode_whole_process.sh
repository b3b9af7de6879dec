#!/usr/bin/env bash
# Whole-process benchmark of `pkm gcode moves` on a generated 1e6-line program (plain G1 moves
# with some rapids and arcs; file reading, parsing, interpretation and CSV writing included).
# Usage: benchmarks/gcode_whole_process.sh [path/to/pkm] [lines]
export LC_ALL=C  # $EPOCHREALTIME (the clock without starting date(1)) with a decimal point
set -euo pipefail
pkm=${1:-build/bin/pkm}
lines=${2:-1000000}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

awk -v n="$lines" 'BEGIN { print "G21 G90 G17 G94 F1200";
  for (i = 1; i < n - 1; i++) { x = (i % 1000) * 0.05; y = int(i / 1000) * 0.05;
    if (i % 100 == 0) printf "G0 X%.3f Y%.3f Z2.000\n", x, y;
    else if (i % 50 == 0) printf "G2 X%.3f Y%.3f I0.025 J0\n", x, y;
    else printf "G1 X%.3f Y%.3f Z%.3f\n", x, y, -0.001 * (i % 7) }
  print "M2" }' > "$work/prog.ngc"

best=""
for run in 1 2 3; do
  start=$EPOCHREALTIME
  "$pkm" gcode moves "$work/prog.ngc" > "$work/moves.csv" 2> "$work/err.txt"
  end=$EPOCHREALTIME
  t=$(echo "$end - $start" | bc -l)
  if [ -z "$best" ] || [ "$(echo "$t < $best" | bc -l)" = 1 ]; then best=$t; fi
done
rows=$(($(wc -l < "$work/moves.csv") - 1))
echo "pkm gcode moves, whole process: $lines lines -> $rows moves in $(printf %.3f "$best") s (best of 3)"
echo "  $(echo "$lines / $best" | bc) lines/s, $(echo "$rows / $best" | bc) moves/s; $(cat "$work/err.txt")"
