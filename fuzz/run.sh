#!/usr/bin/env bash
# `make fuzz` (docs/fuzzing.md): builds the libFuzzer harnesses fuzz/fuzz_<name>.cpp with clang++-14,
# AddressSanitizer and UndefinedBehaviorSanitizer (CMake option PKM_BUILD_FUZZERS, in build-fuzz/)
# and runs each, one after the other, for SECONDS on its saved corpus fuzz/corpus/<name>/ (read
# only: new inputs go to build-fuzz/fuzz-work/<name>/corpus/, crashes, hangs and out-of-memory
# inputs to build-fuzz/fuzz-work/<name>/artifacts/). Prints the executions, coverage and findings
# per harness; exits 1 when a harness found something.
# Usage: fuzz/run.sh [SECONDS [HARNESS...]]   (SECONDS default 60; harnesses default: all)
# Environment: FUZZ_BUILD (build-fuzz), FUZZ_JOBS (build jobs, 1), FUZZ_CXX (clang++-14),
#              FUZZ_FLAGS (extra libFuzzer flags, e.g. -max_len=4096).
set -euo pipefail
seconds=${1:-60}
shift || true
root=$(cd "$(dirname "$0")/.." && pwd)
build=${FUZZ_BUILD:-build-fuzz}
case "$build" in /*) ;; *) build="$root/$build" ;; esac
jobs=${FUZZ_JOBS:-1}
cxx=${FUZZ_CXX:-clang++-14}

# -O1 -g1 and assertions on, as the sanitizer build of `make test`; shared module libraries keep
# the twenty programs small.
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_CXX_COMPILER="$cxx" -DCMAKE_BUILD_TYPE=Debug \
  "-DCMAKE_CXX_FLAGS_DEBUG=-O1 -g1" "-DPKM_SANITIZERS=address;undefined" -DPKM_BUILD_FUZZERS=ON \
  -DPKM_BUILD_TESTS=OFF -DPKM_BUILD_EXAMPLES=OFF -DPKM_SHARED_LIBS=ON >/dev/null
cmake --build "$build" --target pkm_fuzzers -j "$jobs"

if [ $# -gt 0 ]; then
  harnesses=("$@")
else
  harnesses=()
  for f in "$root"/fuzz/fuzz_*.cpp; do
    n=$(basename "$f" .cpp)
    harnesses+=("${n#fuzz_}")
  done
fi

export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1}
summary=()
failed=0
for name in "${harnesses[@]}"; do
  work="$build/fuzz-work/$name"
  mkdir -p "$work/corpus" "$work/artifacts"
  log="$work/fuzz.log"
  # Findings of this run only: artifacts of earlier runs stay where they are, older than the stamp.
  touch "$work/.start"
  echo "== fuzz_$name: ${seconds} s"
  status=0
  # -timeout: an input taking 10 s is a hang; -rss_limit_mb / -malloc_limit_mb: an input needing
  # more than 2 GB (or one allocation of 2 GB) is an unbounded allocation.
  # shellcheck disable=SC2086
  "$build/fuzz/fuzz_$name" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
    -malloc_limit_mb=2048 -max_len=8192 -print_final_stats=1 -dict="$root/fuzz/fuzz.dict" \
    -artifact_prefix="$work/artifacts/" ${FUZZ_FLAGS:-} "$work/corpus" "$root/fuzz/corpus/$name" \
    >"$log" 2>&1 || status=$?
  execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
  rss=$(sed -n 's/^stat::peak_rss_mb: *//p' "$log" | tail -1)
  cov=$(grep -oE 'cov: [0-9]+ ft: [0-9]+' "$log" | tail -1 || true)
  findings=$(find "$work/artifacts" -type f -newer "$work/.start" | wc -l)
  line="fuzz_$name: ${execs:-?} executions, ${cov:-no coverage line}, peak RSS ${rss:-?} MB, $findings finding(s)"
  if [ "$status" -ne 0 ] || [ "$findings" -ne 0 ]; then
    failed=1
    line="$line (exit $status; see $log and $work/artifacts/)"
    grep -m1 -E 'ERROR: (AddressSanitizer|libFuzzer|LeakSanitizer)|runtime error|fuzz invariant' \
      "$log" || true
  fi
  echo "$line"
  summary+=("$line")
done
echo
echo "== summary (${seconds} s each)"
printf '%s\n' "${summary[@]}"
exit "$failed"
