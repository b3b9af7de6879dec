#!/usr/bin/env bash
# Whole-process comparison of `pkm analyze circle` with scipy on 1 000 000 noisy points of a
# measured-like ring (50 mm radius, 3- and 5-lobe form of 10 µm, 1 µm noise, 6 decimals as a CMM
# writes them). The reference is what a user would otherwise run: np.loadtxt and
# scipy.optimize.least_squares (method "lm", analytic Jacobian), in Debian's /usr/bin/python3.
# Both run as whole processes in alternating pairs; the medians and their ratio are printed, and
# the least-squares centres and radii are compared (they must agree within 1e-6 of the radius).
# pkm is timed with `--fit lsc` (the least-squares circle and its budget: the reference's work) and
# with the default `--fit both` (the minimum-zone circle and roundness too, which the reference
# does not compute); the ratio is of the first.
# Usage: benchmarks/circle_vs_scipy_whole_process.sh [path/to/pkm] [points] [pairs]
set -euo pipefail
pkm=${1:-build/bin/pkm}
points=${2:-1000000}
pairs=${3:-7}
python=/usr/bin/python3
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

if ! "$python" -c 'import numpy' 2>/dev/null; then
  echo "circle vs scipy: skipped (Debian's python3-numpy is not installed; scripts/setup.sh installs it)"
  exit 0
fi
"$python" "$(dirname "$0")/python/make_ring.py" "$work/ring.csv" "$points"
cp "$(dirname "$0")/python/circle_reference.py" "$work/reference.py"
have_scipy=1
"$python" -c 'import scipy.optimize' 2>/dev/null || have_scipy=0

# Times are read from bash's $EPOCHREALTIME (no process is started to read the clock, which would
# add a fork and exec of date(1) to every measured run).
export LC_ALL=C  # a decimal point in $EPOCHREALTIME
pkm_times=()
both_times=()
ref_times=()
for ((i = 0; i < pairs; i++)); do
  s=$EPOCHREALTIME; "$pkm" analyze circle --data "$work/ring.csv" --fit lsc --json > "$work/pkm.json"; e=$EPOCHREALTIME
  pkm_times+=("$(echo "$e - $s" | bc -l)")
  s=$EPOCHREALTIME; "$pkm" analyze circle --data "$work/ring.csv" --json > "$work/both.json"; e=$EPOCHREALTIME
  both_times+=("$(echo "$e - $s" | bc -l)")
  if [ "$have_scipy" = 1 ]; then
    s=$EPOCHREALTIME; "$python" "$work/reference.py" "$work/ring.csv" > "$work/ref.txt"; e=$EPOCHREALTIME
    ref_times+=("$(echo "$e - $s" | bc -l)")
  fi
done
median() { printf '%s\n' "$@" | sort -g | awk '{ v[NR] = $1 } END { print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }
pkm_med=$(median "${pkm_times[@]}")
both_med=$(median "${both_times[@]}")
read -r cx cy radius iterations converged < <("$python" -c '
import json, sys
d = json.load(open(sys.argv[1]))
print(repr(d["center"][0]), repr(d["center"][1]), repr(d["radius"]), d["iterations"], d["converged"])' "$work/pkm.json")
printf 'pkm analyze circle --fit lsc, whole process: %d points, median of %d runs %.3f s (LSC %d iterations, converged %s); with the minimum zone (--fit both) %.3f s\n' \
  "$points" "$pairs" "$pkm_med" "$iterations" "$converged" "$both_med"
if [ "$have_scipy" = 0 ]; then
  echo "  reference skipped: scipy is not installed (Debian's python3-scipy; scripts/setup.sh installs it)"
  exit 0
fi
ref_med=$(median "${ref_times[@]}")
read -r rx ry rr nfev < "$work/ref.txt"
"$python" - "$cx" "$cy" "$radius" "$rx" "$ry" "$rr" <<'PY'
import sys
cx, cy, r, rx, ry, rr = map(float, sys.argv[1:])
d = max(abs(cx - rx), abs(cy - ry), abs(r - rr))
print(f"  pkm vs scipy: max |difference| of centre and radius {d:.3g} mm = {d / rr:.3g} of the radius",
      "(agree)" if d <= 1e-6 * rr else "(DISAGREE: more than 1e-6 of the radius)")
if d > 1e-6 * rr:
    sys.exit(1)
PY
printf '  scipy (np.loadtxt + least_squares lm, %s evaluations): median %.3f s -> pkm --fit lsc is %.1fx faster\n' \
  "$nfev" "$ref_med" "$(echo "$ref_med / $pkm_med" | bc -l)"
# For benchmarks/summary.sh: job | pkm s | reference | reference s | target ratio.
printf 'bench-row|analyze circle --fit lsc, %d noisy points|%s|scipy (loadtxt + least_squares)|%s|10\n' \
  "$points" "$pkm_med" "$ref_med"
