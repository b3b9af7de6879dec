#!/usr/bin/env bash
# Whole-process comparison of `pkm gcode moves` with LinuxCNC's own interpreter, the standalone
# `rs274` of Debian's linuxcnc-uspace package, on the same generated CAM-style program (~220 000
# lines: G21/G90/G17 header, line numbers, comments, mostly G1 X Y Z with changing F words, G0
# repositioning, G2/G3 arcs). Runs alternate (rs274, pkm, rs274, ...) so that a change of machine
# load hits both; prints the medians and their ratio. Checks that both produce the same motions:
# the counts of rs274's STRAIGHT_TRAVERSE/STRAIGHT_FEED/ARC_FEED calls and pkm's CSV rows, and
# every motion's kind, end point, arc centre, turns and feed (rs274 prints 4 decimals).
# rs274 is $RS274, else the one on PATH (Debian: /usr/bin/rs274), else the unpacked package of
# scripts/fetch-linuxcnc.sh (.cache/linuxcnc); without one (or with RS274=none) only pkm is timed.
# PROGRAM=FILE times that program instead of the generated one (the motion check assumes the XY
# plane, mm and no offsets, as in the generated program). COMP=1 generates a cutter-compensated
# program instead: gear-shaped contours of lines and shallow arcs (convex and concave corners),
# each entered with G41.1 D6 (or G42.1) and left with G40, at several depths.
# Usage: [PROGRAM=FILE|COMP=1] benchmarks/gcode_vs_rs274_whole_process.sh [pkm] [lines] [pairs]
set -euo pipefail
pkm=${1:-build/bin/pkm}
lines=${2:-220000}
pairs=${3:-7}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

rs274=${RS274:-}
rs274_env=()
if [ "$rs274" = none ]; then
  rs274=""
elif [ -z "$rs274" ]; then
  if command -v rs274 > /dev/null 2>&1; then
    rs274=$(command -v rs274)
  elif [ -x .cache/linuxcnc/usr/bin/rs274 ]; then
    rs274=.cache/linuxcnc/usr/bin/rs274
    rs274_env=("LD_LIBRARY_PATH=.cache/linuxcnc/usr/lib")
  fi
fi

# A contour-parallel pocket as a CAM post-processor writes it: N numbers in steps of 10, a comment
# per pass, 3 decimals, F on about one line in five, an arc (I, J from the current point) every 23
# lines (never followed by a modal continuation line), a retract and rapid reposition every 997
# lines.
awk -v n="$lines" 'BEGIN {
  pi = atan2(0, -1); k = 0; N = 0;
  print "%";
  print "(pkm benchmark: contour-parallel pocket, generated)";
  print "(T1 D=6 flat end mill; ZMIN=-6)";
  print "G21 G90 G17 G94";
  print "G54";
  print "S12000 M3";
  print "G0 Z15.000";
  k = 7; x = 50; y = 0; z = 2; t = 0; pass = 0;
  while (k < n - 4) {
    if (k % 997 == 7) {
      pass++;
      printf "(pass %d)\n", pass; k++;
      printf "N%d G0 Z5.000\n", N += 10; k++;
      printf "N%d G0 X%.3f Y%.3f\n", N += 10, x, y; k++;
      z = -0.5 - (pass % 12) * 0.45;
      printf "N%d G1 Z%.3f F300\n", N += 10, z; k++;
      g1 = 1;
      continue;
    }
    if (k % 23 == 0) {
      r = 1.5 + (k % 5) * 0.4; sweep = (0.3 + (k % 7) * 0.35);
      cx = x + r; cy = y; cw = (k % 2 == 0);
      a = pi + (cw ? -sweep : sweep);
      x = cx + r * cos(a); y = cy + r * sin(a);
      printf "N%d %s X%.3f Y%.3f I%.3f J0.\n", N += 10, cw ? "G2" : "G3", x, y, r; k++;
      # the next point is taken where the arc ended (printed to 3 decimals)
      x = sprintf("%.3f", x) + 0; y = sprintf("%.3f", y) + 0;
      g1 = 0;
      continue;
    }
    t += 0.0125;
    rad = 40 + 8 * sin(t / 37);
    x = 50 + rad * cos(t) + 0.02 * (k % 11); y = rad * sin(t);
    z1 = z + 0.05 * sin(3 * t);
    if (k % 5 == 0)
      printf "N%d G1 X%.3f Y%.3f Z%.3f F%d\n", N += 10, x, y, z1, 900 + 100 * (k % 9);
    else if (k % 13 == 1 && g1)  # modal G1
      printf "N%d X%.3f Y%.3f Z%.3f\n", N += 10, x, y, z1;
    else
      printf "N%d G1 X%.3f Y%.3f Z%.3f\n", N += 10, x, y, z1;
    k++; g1 = 1;
  }
  printf "N%d G0 Z15.000\n", N += 10;
  printf "N%d M5\n", N += 10;
  printf "N%d M30\n", N += 10;
  print "%" }' > "$work/prog.ngc"
if [ -n "${COMP:-}" ]; then
  # 60-tooth gears (radius 40/31 mm alternating), every third side a shallow arc (R about twice
  # the chord), each contour at a new depth, tool left or right in turn, centres on a grid.
  awk -v n="$lines" 'BEGIN {
    pi = atan2(0, -1); k = 0; N = 0; c = 0;
    print "%"; print "(pkm benchmark: cutter-compensated contours, generated)";
    print "G21 G90 G17 G94 G40"; print "S10000 M3"; print "G0 Z10.000"; k = 5;
    while (k < n - 70) {
      cx = (c % 10) * 100; cy = int(c / 10) % 10 * 100; z = -0.5 - (c % 7) * 0.5;
      side = (c % 2 == 0) ? "G41.1" : "G42.1"; c++;
      printf "N%d G0 X%.3f Y%.3f\n", N += 10, cx + 55, cy; printf "N%d G1 Z%.3f F400\n", N += 10, z;
      printf "N%d %s D6 G1 X%.3f Y%.3f F1200\n", N += 10, side, cx + 40, cy; k += 3;
      for (i = 1; i <= 60; i++) {
        a = 2 * pi * i / 60; r = (i % 2 == 0) ? 40 : 31;
        x = cx + r * cos(a); y = cy + r * sin(a);
        if (i % 3 == 0) {
          chord = sqrt((x - px) ^ 2 + (y - py) ^ 2);
          printf "N%d %s X%.3f Y%.3f R%.3f\n", N += 10, (i % 2 ? "G2" : "G3"), x, y, 2 * chord;
        } else {
          printf "N%d G1 X%.3f Y%.3f\n", N += 10, x, y;
        }
        px = x; py = y; k++;
        if (i == 1) { px = x; py = y }
      }
      printf "N%d G40 G1 X%.3f Y%.3f\n", N += 10, cx + 55, cy; printf "N%d G0 Z5.000\n", N += 10; k += 2;
    }
    printf "N%d G0 Z15.000\n", N += 10; printf "N%d M5\n", N += 10; printf "N%d M30\n", N += 10;
    print "%" }' > "$work/prog.ngc"
fi
if [ -n "${PROGRAM:-}" ]; then cp "$PROGRAM" "$work/prog.ngc"; fi
: > "$work/empty.tbl"

# Times are read from bash's $EPOCHREALTIME (no process is started to read the clock, which would
# add a fork and exec of date(1) to every measured run).
export LC_ALL=C  # a decimal point in $EPOCHREALTIME
now_us() { local t=$EPOCHREALTIME; REPLY=${t/./}; }  # microseconds, in $REPLY
# Both programs write their output file themselves: rs274 through its output-file argument (its
# fastest documented mode; through standard output it is about 4.4 times slower), pkm through
# --out.
run_pkm() { "$pkm" gcode moves "$work/prog.ngc" --out "$work/moves.csv" --force 2> "$work/pkm_err.txt"; }
run_rs274() {
  : > "$work/rs274.var"
  env "${rs274_env[@]}" "$rs274" -t "$work/empty.tbl" -v "$work/rs274.var" -g "$work/prog.ngc" \
    "$work/rs274.txt" > "$work/rs274_out.txt" 2> "$work/rs274_err.txt" < /dev/null
}
median() { sort -n | awk '{ v[NR] = $1 } END { print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }

echo "load average before: $(cut -d' ' -f1-3 /proc/loadavg)"
: > "$work/t_pkm"
: > "$work/t_rs274"
for ((i = 0; i < pairs; i++)); do
  if [ -n "$rs274" ]; then
    now_us; s=$REPLY; run_rs274; now_us; e=$REPLY
    echo $((e - s)) >> "$work/t_rs274"
  fi
  now_us; s=$REPLY; run_pkm; now_us; e=$REPLY
  echo $((e - s)) >> "$work/t_pkm"
done
echo "load average after:  $(cut -d' ' -f1-3 /proc/loadavg)"

plines=$(wc -l < "$work/prog.ngc")
pkm_us=$(median < "$work/t_pkm")
rows=$(($(wc -l < "$work/moves.csv") - 1))
printf 'pkm gcode moves, whole process: %d lines -> %d moves in %.3f s (median of %d; runs %s s)\n' \
  "$plines" "$rows" "$(echo "$pkm_us / 1000000" | bc -l)" "$pairs" \
  "$(awk '{ printf "%s%.3f", (NR > 1 ? " " : ""), $1 / 1e6 }' "$work/t_pkm")"
echo "  $(cat "$work/pkm_err.txt")"
if [ -z "$rs274" ]; then
  echo "  reference: LinuxCNC rs274 not installed (Debian linuxcnc-uspace, or scripts/fetch-linuxcnc.sh); skipped"
  exit 0
fi
rs_us=$(median < "$work/t_rs274")
ref=$(grep -cE '(STRAIGHT_TRAVERSE|STRAIGHT_FEED|ARC_FEED)\(' "$work/rs274.txt" || true)
printf 'LinuxCNC rs274 (%s), whole process: %d moves in %.3f s (median of %d; runs %s s)\n' \
  "$rs274" "$ref" "$(echo "$rs_us / 1000000" | bc -l)" "$pairs" \
  "$(awk '{ printf "%s%.3f", (NR > 1 ? " " : ""), $1 / 1e6 }' "$work/t_rs274")"
printf '  speed-up of pkm over rs274: %.1fx\n' "$(echo "$rs_us / $pkm_us" | bc -l)"
# For benchmarks/summary.sh: job | pkm s | reference | reference s | target ratio.
printf 'bench-row|gcode moves, %d-line CAM program|%s|rs274 (LinuxCNC), output-file argument|%s|20\n' \
  "$lines" "$(echo "$pkm_us / 1000000" | bc -l)" "$(echo "$rs_us / 1000000" | bc -l)"

# Same motions: rs274's canonical calls (XY plane, no offsets in this program, so its program
# coordinates are machine coordinates) against pkm's rows, within rs274's printing precision.
awk -F'[(,)]' '
  /SET_FEED_RATE\(/ { feed = $2 + 0 }
  /STRAIGHT_TRAVERSE\(/ { printf "rapid %s %s %s - - 0 -\n", $2, $3, $4 }
  /STRAIGHT_FEED\(/ { printf "linear %s %s %s - - 0 %s\n", $2, $3, $4, feed }
  /ARC_FEED\(/ { printf "arc %s %s %s %s %s %s %s\n", $2, $3, $7, $4, $5, $6, feed }' \
  "$work/rs274.txt" > "$work/ref.txt"
awk -F, 'NR > 1 { printf "%s %s %s %s %s %s %s %s\n", $2, $3, $4, $5, ($9 == "" ? "-" : $9),
  ($10 == "" ? "-" : $10), $12, ($14 == "" ? "-" : $14) }' "$work/moves.csv" > "$work/got.txt"
paste -d' ' "$work/ref.txt" "$work/got.txt" | awk -v nref="$ref" -v ngot="$rows" '
  function near(a, b) { if (a == "-" || b == "-") return a == b; d = a - b; return (d < 0 ? -d : d) <= 1.5e-4 }
  { ok = ($1 == $9 && $7 == $15);
    for (i = 2; i <= 8; i++) if (i != 7 && !near($i, $(i + 8))) ok = 0;
    if (!ok) { bad++; if (bad <= 3) printf "  motion %d differs: rs274 [%s %s %s %s %s %s %s %s] pkm [%s %s %s %s %s %s %s %s]\n", NR, $1, $2, $3, $4, $5, $6, $7, $8, $9, $10, $11, $12, $13, $14, $15, $16 } }
  END { printf "  motions: rs274 %d, pkm %d; %s\n", nref, ngot,
          ((nref == ngot && bad == 0) ? "same kind, end point, centre, turns and feed for every motion" : (bad + 0) " motions differ");
        exit (nref == ngot && bad == 0) ? 0 : 1 }'
