#!/usr/bin/env bash
# Times the phases of `make test` on a fresh clone of the repository, as CI runs it: setup,
# Release build, Release tests, sanitizer build, sanitizer tests. ccache is disabled, so the
# figures are those of a machine that has never built pkm.
# Usage: scripts/measure-build.sh [CLONE_DIR]   (default: a new temporary folder; removed after)
set -euo pipefail
src=$(cd "$(dirname "$0")/.." && pwd)
dir=${1:-$(mktemp -d)}
rm -rf "$dir"
git clone -q "$src" "$dir"
cd "$dir"
export CI=true CCACHE_DISABLE=1
total=0
phase() {
  local name=$1
  shift
  local t0 t1
  t0=$(date +%s)
  "$@" >"$dir/$name.log" 2>&1 || { echo "$name failed: see $dir/$name.log"; tail -20 "$dir/$name.log"; exit 1; }
  t1=$(date +%s)
  total=$((total + t1 - t0))
  printf '%-16s %5d s\n' "$name" $((t1 - t0))
}
echo "fresh clone of $(git rev-parse --short HEAD) in $dir, $(nproc) cores"
phase setup make setup
phase release-build make build
phase release-tests make test-release
phase asan-build make build-asan
phase asan-tests make test-asan
printf '%-16s %5d s (%d min %d s)\n' total "$total" $((total / 60)) $((total % 60))
grep -h "tests passed" "$dir"/release-tests.log "$dir"/asan-tests.log
[ -z "${1:-}" ] && rm -rf "$dir"
exit 0
