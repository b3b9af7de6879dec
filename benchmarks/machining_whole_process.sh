#!/usr/bin/env bash
# The machining preview's cost on examples/gcode/sphere.ngc (docs/machining.md): whole-process
# `pkm gcode run` with and without --stock, alternating, 5 runs each, medians; the difference is
# the removal (interpreting, checking and printing are the same work in both). Cells of 0.25 mm
# (the page's 200 cells over a 50 mm stock) and 0.1 mm, on a box around the 20 mm sphere.
# Usage: benchmarks/machining_whole_process.sh [path/to/pkm]
export LC_ALL=C
set -euo pipefail
pkm=${1:-build/bin/pkm}
src=$(cd "$(dirname "$0")/.." && pwd)
prog="$src/examples/gcode/sphere.ngc"
tbl="$src/examples/gcode/tools.tbl"
median() { sort -g | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}'; }
time_one() {
  local start end
  start=$EPOCHREALTIME
  "$pkm" gcode run "$prog" --tool-table "$tbl" "$@" > /dev/null
  end=$EPOCHREALTIME
  echo "$end - $start" | bc -l
}
echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //')"
for cell in 0.25 0.1; do
  plain=() stock=()
  for run in 1 2 3 4 5; do
    plain+=("$(time_one)")
    stock+=("$(time_one --stock box:25,15,-10,75,65,20 --stock-cell "$cell")")
  done
  p=$(printf '%s\n' "${plain[@]}" | median)
  s=$(printf '%s\n' "${stock[@]}" | median)
  printf 'sphere.ngc, cell %s mm: gcode run %.3f s, with the machining preview %.3f s, removal %.3f s\n' \
    "$cell" "$p" "$s" "$(echo "$s - $p" | bc -l)"
done
