#!/usr/bin/env bash
# Whole-process timing of `pkm simulate` for every built-in scenario (target: simulating every
# built-in scenario takes well under a second). Prints the best of 5 wall times per scenario and
# for all of them together, process start and file writing included.
# Usage: benchmarks/simulate_whole_process.sh [path/to/pkm]
export LC_ALL=C  # $EPOCHREALTIME (the clock without starting date(1)) with a decimal point
set -euo pipefail
pkm=${1:-build/bin/pkm}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
scenarios=$("$pkm" simulate --list | cut -f1)

total_best=""
for run in 1 2 3 4 5; do
  rm -rf "$work"/*
  start=$EPOCHREALTIME
  for s in $scenarios; do "$pkm" simulate "$s" --out "$work/$s" > /dev/null; done
  end=$EPOCHREALTIME
  t=$(echo "$end - $start" | bc -l)
  if [ -z "$total_best" ] || [ "$(echo "$t < $total_best" | bc -l)" = 1 ]; then total_best=$t; fi
done
for s in $scenarios; do
  best=""
  for run in 1 2 3 4 5; do
    rm -rf "$work/$s"
    start=$EPOCHREALTIME
    "$pkm" simulate "$s" --out "$work/$s" > /dev/null
    end=$EPOCHREALTIME
    t=$(echo "$end - $start" | bc -l)
    if [ -z "$best" ] || [ "$(echo "$t < $best" | bc -l)" = 1 ]; then best=$t; fi
  done
  printf '%-32s %4d files  best %.4f s\n' "$s" "$(ls "$work/$s" | wc -l)" "$best"
done
printf 'all built-in scenarios: best %.4f s\n' "$total_best"
