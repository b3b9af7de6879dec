#!/usr/bin/env bash
# The command-line contract, byte for byte: runs a fixed set of `pkm` commands (every analysis
# kind, both calibrations, `gcode run --report`, `simulate` of every built-in scenario, the default
# campaign, ...) in a scratch folder and records, per case, the exit code, standard output,
# standard error and every file the case wrote. Times and the scratch folder's path are masked
# (normalise.sh), so two runs of the same program give the same record.
#
# Usage: tests/golden/cases.sh PKM OUT_DIR
#   Writes one text record per case, OUT_DIR/<case>.txt: the command, the exit code, standard
#   output, standard error and every file the case wrote, each after a "=== " header line.
# tests/golden/check.sh compares such records with the ones kept in tests/data/golden/.
# PKM_GOLDEN_SKIP: an extended regular expression; cases whose whole name matches are not run.
set -euo pipefail
pkm=$(realpath "$1")
out=$(realpath -m "$2")
src=$(cd "$(dirname "$0")/../.." && pwd)
norm="$src/tests/golden/normalise.sh"
rm -rf "$out"
mkdir -p "$out"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"

# run NAME ARGS...: one case. Files the case writes go to $work/NAME/ (the case's current folder).
run() {
  local name=$1
  shift
  if [ -n "${PKM_GOLDEN_SKIP:-}" ] && [[ $name =~ ^(${PKM_GOLDEN_SKIP})$ ]]; then return 0; fi
  local dir="$work/$name" rec="$out/$name.txt"
  mkdir -p "$dir"
  local rc=0
  (cd "$dir" && "$pkm" "$@" >"$work/.stdout" 2>"$work/.stderr" </dev/null) || rc=$?
  {
    printf '=== command\npkm %s\n=== exit code\n%s\n=== stdout\n' "$*" "$rc"
    cat "$work/.stdout"
    printf '=== stderr\n'
    cat "$work/.stderr"
    local f
    while IFS= read -r f; do
      printf '=== file %s\n' "$f"
      cat "$dir/$f"
    done < <(cd "$dir" && find . -type f | LC_ALL=C sort)
  } | bash "$norm" "$work" >"$rec"
}

# Simulated inputs, each also a case.
for s in seed000-parallelism seed001-diagonals seed003-probe-offset seed004-hexapod-calibration \
  exechon-calibration; do
  run "simulate-$s" simulate "$s" --out sim
done
s0="$work/simulate-seed000-parallelism/sim"
s1="$work/simulate-seed001-diagonals/sim"
s3="$work/simulate-seed003-probe-offset/sim"
s4="$work/simulate-seed004-hexapod-calibration/sim"
se="$work/simulate-exechon-calibration/sim"

# Every analysis kind, as a table and as JSON.
for fmt in table json; do
  j=()
  [ "$fmt" = json ] && j=(--json)
  run "analyze-iso230-2-$fmt" analyze iso230-2 --data "$s0"/linear-x2_run*.csv "${j[@]}"
  run "analyze-straightness-$fmt" analyze straightness --data "$s0"/straightness-x2-h_run*.csv \
    "${j[@]}"
  run "analyze-parallelism-$fmt" analyze parallelism --reference "$s0"/straightness-y2-h_run*.csv \
    --axis "$s0"/straightness-py-h_run*.csv "${j[@]}"
  run "analyze-squareness-$fmt" analyze squareness --data "$s0"/diagonal-x2-y2_run*.csv \
    "${j[@]}"
  run "analyze-diagonals-$fmt" analyze diagonals --size 500,400,300 \
    --data "$s1"/diag-*_run*.csv "${j[@]}"
  run "analyze-circle-$fmt" analyze circle --data "$s3/probe_circle_uncompensated.csv" "${j[@]}"
  run "analyze-circular-$fmt" analyze circular --data "$s3/probe_circle_uncompensated.csv" \
    "$s3/probe_circle_compensated.csv" --nominal-radius 20 "${j[@]}"
  run "analyze-probe-offset-$fmt" analyze probe-offset --data "$s3/probe_offset.csv" "${j[@]}"
done

# Both calibrations, as text and as JSON (with the files they write).
run calibrate-hexapod calibrate hexapod --machine hexapod-default --data "$s4/tracker-pose.csv" \
  --holdout "$s4/tracker-holdout.csv" --frame tracker \
  --registration "$s4/tracker-pose-registration.csv" --out cal.json
run calibrate-hexapod-json calibrate hexapod --machine hexapod-default \
  --data "$s4/tracker-pose.csv" --holdout "$s4/tracker-holdout.csv" \
  --registration "$s4/tracker-pose-registration.csv" --out cal.json --backlash --json
run calibrate-hexapod-unregistered calibrate hexapod --machine hexapod-default \
  --data "$s4/tracker-pose.csv" --holdout "$s4/tracker-holdout.csv" --out cal.json
run calibrate-exechon calibrate exechon --machine mxt700s-like --data "$se/tracker-fit.csv" \
  --holdout "$se/tracker-holdout.csv" --out cal.json
run calibrate-exechon-json calibrate exechon --machine mxt700s-like --data "$se/tracker-fit.csv" \
  --holdout "$se/tracker-holdout.csv" --out cal.json --json
run calibrate-exechon-hybrid calibrate exechon --machine mxt700s-like --data "$se/tracker-fit.csv" \
  "$se/tracker-hybrid.csv" --holdout "$se/tracker-hybrid-holdout.csv" --errors mxt700s-seed000 \
  --out cal.json
run calibrate-exechon-hybrid-json calibrate exechon --machine mxt700s-like \
  --data "$se/tracker-fit.csv" "$se/tracker-hybrid.csv" --holdout "$se/tracker-hybrid-holdout.csv" \
  --errors mxt700s-seed000 --out cal.json --json
run calibrate-exechon-monte-carlo calibrate exechon --machine mxt700s-like \
  --data "$se/tracker-fit.csv" --out cal.json --monte-carlo 3 --threads 2
run calibrate-hexapod-monte-carlo calibrate hexapod --machine hexapod-default \
  --data "$s4/tracker-pose.csv" --out cal.json --monte-carlo 4 --threads 2
run analyze-circular-one-file analyze circular --data "$s3/probe_circle_compensated.csv"
run calibrate-hexapod-missing calibrate hexapod --machine hexapod-default --data nothing.csv \
  --out cal.json

# Pose planning, controller tables, G-code.
run plan-poses plan-poses --machine hexapod-default --count 12 --index O1 --gcode plan.ngc
run compensate-table compensate table --data "$s0"/linear-x2_run*.csv --format linuxcnc1 \
  --axis X --out x.comp
run gcode-moves gcode moves "$src/examples/gcode/drilling.ngc" --out moves.csv
run gcode-run-hexapod gcode run "$src/examples/gcode/hexapod_contour.ngc" \
  --machine hexapod-default --report report.json --out joints.csv
run gcode-run-exechon gcode run "$src/examples/gcode/exechon_contour.ngc" \
  --machine mxt700s-like --report report.json
run gcode-compensate gcode compensate "$src/examples/gcode/hexapod_contour.ngc" \
  --machine "$work/calibrate-hexapod/cal.json" --nominal hexapod-default --out comp.ngc
run gcode-make-sphere gcode make sphere --radius 10 --z 190 --tool-radius 2 --levels 3
run gcode-run-machining gcode run "$src/examples/gcode/sphere.ngc" \
  --stock box:25,15,-10,75,65,20 --stock-cell 0.5
run gcode-flatten gcode flatten "$src/examples/gcode/sphere.ngc" \
  --tool-table "$src/examples/gcode/tools.tbl"

# The default campaign (its report.html is checked through report-data.json and its size).
run campaign-default campaign run default --out out --no-db
run campaign-list campaign list
