#!/usr/bin/env bash
# Builds the libFuzzer harness of the G-code interpreter with clang++-14 (ASan + UBSan) and runs
# it for SECONDS (default 180) on a corpus seeded with the shipped programs.
# Usage: fuzz/run.sh [SECONDS]   (from the repository root; writes build-fuzz/)
set -euo pipefail
seconds=${1:-180}
root=$(cd "$(dirname "$0")/.." && pwd)
out="$root/build-fuzz"
mkdir -p "$out/corpus"
cp "$root"/examples/gcode/*.ngc "$root"/tests/cnc/corpus/*.ngc "$out/corpus/"
# The interpreter's sources only: the joint-space conversion, cycle time and program compensation
# need the kinematics, which the harness does not exercise.
sources=()
for f in "$root"/src/cnc/*.cpp; do
  case "$(basename "$f")" in
    cycle_time.cpp | exechon_*.cpp | joint_*.cpp | *program_compensation.cpp) ;;
    *) sources+=("$f") ;;
  esac
done
clang++-14 -std=c++20 -O1 -g -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=undefined \
  -I"$root/include" -I"$root/src" -isystem /usr/include/eigen3 \
  "$root/fuzz/fuzz_gcode.cpp" "${sources[@]}" "$root/src/core/error.cpp" \
  -lfmt -o "$out/fuzz_gcode"
"$out/fuzz_gcode" -max_total_time="$seconds" -max_len=2048 -timeout=10 -rss_limit_mb=2048 \
  -print_final_stats=1 "$out/corpus"
