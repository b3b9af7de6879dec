#!/usr/bin/env bash
# The speed table of docs/performance.md, measured now: each job of pkm against its reference
# program in the same run (the whole-process scripts of benchmarks/ and the Python benchmarks of
# benchmarks/python/, each alternating pkm and the reference and reporting medians), then one
# table with the ratios and whether each target holds. Every script's own report is printed as
# it runs; the rows come from its "bench-row|job|pkm s|reference|reference s|target" lines.
# The LinuxCNC genhexkins reference needs a runner script (GENHEXKINS_BENCH, see
# fk_vs_genhexkins_whole_process.sh); without it that row says "skipped".
# Usage: benchmarks/summary.sh [build dir (with bin/pkm and python/)]
set -uo pipefail
build=${1:-build-bench}
pkm="$build/bin/pkm"
here=$(cd "$(dirname "$0")" && pwd)
log=$(mktemp)
trap 'rm -f "$log"' EXIT
failed=0
run() {
  echo "== $*"
  "$@" 2>&1 | tee -a "$log" || failed=1
}
run bash "$here/fk_vs_genhexkins_whole_process.sh" "$pkm"
run bash "$here/gcode_vs_rs274_whole_process.sh" "$pkm"
run bash "$here/circle_vs_scipy_whole_process.sh" "$pkm"
run bash "$here/table_read_whole_process.sh" "$pkm"
[ -f "$here/calibration_vs_scipy_whole_process.sh" ] &&
  run bash "$here/calibration_vs_scipy_whole_process.sh" "$pkm"
if [ -d "$build/python/pkm" ]; then
  run env PYTHONPATH="$build/python" /usr/bin/python3 "$here/python/bench_circle.py"
  run env PYTHONPATH="$build/python" /usr/bin/python3 "$here/python/bench_hexapod.py"
else
  echo "Python benchmarks skipped: no $build/python/pkm (the bindings are built with Debian's pybind11)"
fi

echo
echo "## pkm against the reference programs, $(date -u +%Y-%m-%d), $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'), load before: $(cut -d' ' -f1-3 /proc/loadavg)"
echo
echo "| job | pkm | reference | reference time | ratio | target | holds |"
echo "|---|---|---|---|---|---|---|"
grep '^bench-row|' "$log" | awk -F'|' '{
  ratio = ($3 > 0) ? $5 / $3 : 0
  target = $6
  holds = (target == "-") ? "-" : ((ratio >= target) ? "yes" : "NO")
  if (target == "-") { shown = sprintf("%.2f of the limit", $3 / $5) } else { shown = sprintf("%.1fx", ratio) }
  printf "| %s | %.3f s | %s | %.3f s | %s | %s | %s |\n", $2, $3, $4, $5, shown, (target == "-" ? "-" : ">= " target "x"), holds
}'
# A comparison whose reference is not installed prints no row: say which.
for job in "hexapod fk:genhexkins (GENHEXKINS_BENCH unset or not found)" \
           "gcode moves:LinuxCNC's rs274 (Debian linuxcnc-uspace)" \
           "analyze circle:scipy (Debian python3-scipy)" \
           "calibrate hexapod:scipy (Debian python3-scipy)" \
           "Hexapod.ik:the Python module (pybind11)"; do
  grep -q "^bench-row|${job%%:*}" "$log" || echo "(no ${job%%:*} row: ${job#*:} missing)"
done
exit "$failed"
