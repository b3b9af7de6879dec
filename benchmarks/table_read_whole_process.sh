#!/usr/bin/env bash
# The table reader (io::NumberTable) against the physical limit, on the 1,000,000-point ring of
# circle_vs_scipy_whole_process.sh (20.7 MB, 6 decimals): the limit is the time to get the file's
# bytes from the page cache (`cat FILE > /dev/null`, median of alternating runs) plus one
# std::from_chars over each of its numbers on one core (benchmarks/read_limit.cpp, in memory).
# pkm's reader maps the file and parses it in chunks on the cores into one array of doubles.
# Prints both, and pkm's time as a fraction of the limit (below 1: faster than the limit's
# single-threaded parse).
# Usage: benchmarks/table_read_whole_process.sh [path/to/pkm] [points] [runs]
set -euo pipefail
pkm=${1:-build/bin/pkm}
points=${2:-1000000}
runs=${3:-9}
limit="$(dirname "$pkm")/read_limit"
python=/usr/bin/python3
if [ ! -x "$limit" ]; then
  echo "table read: skipped ($limit is built with -DPKM_BUILD_BENCHMARKS=ON: make bench)"
  exit 0
fi
if ! "$python" -c 'import numpy' 2>/dev/null; then
  echo "table read: skipped (Debian's python3-numpy is not installed)"
  exit 0
fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$python" "$(dirname "$0")/python/make_ring.py" "$work/ring.csv" "$points"
export LC_ALL=C
cat "$work/ring.csv" > /dev/null  # in the page cache, as for every reader timed here
cat_times=()
for ((i = 0; i < runs; i++)); do
  s=$EPOCHREALTIME; cat "$work/ring.csv" > /dev/null; e=$EPOCHREALTIME
  cat_times+=("$(echo "$e - $s" | bc -l)")
done
median() { printf '%s\n' "$@" | sort -g | awk '{ v[NR] = $1 } END { print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }
cat_med=$(median "${cat_times[@]}")
read -r _ read_s _ loop_s _ rows _ numbers _ < <("$limit" "$work/ring.csv" x y --runs "$runs")
bytes=$(stat -c %s "$work/ring.csv")
awk -v c="$cat_med" -v r="$read_s" -v l="$loop_s" -v rows="$rows" -v n="$numbers" -v b="$bytes" 'BEGIN {
  printf "table read: %d rows, %d numbers, %.1f MB; cat %.4f s + from_chars loop %.4f s = limit %.4f s\n", rows, n, b / 1e6, c, l, c + l
  printf "  pkm io::NumberTable::read %.4f s (%.0f MB/s) = %.2f of the limit\n", r, b / 1e6 / r, r / (c + l)
}'
# For benchmarks/summary.sh: job | pkm s | reference | reference s | target ratio (none).
printf 'bench-row|table read, %d rows (io::NumberTable)|%s|cat + one from_chars loop (the limit)|%s|-\n' \
  "$rows" "$read_s" "$(echo "$cat_med + $loop_s" | bc -l)"
echo "  machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //')"
