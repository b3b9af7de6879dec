#!/usr/bin/env bash
# The command-line contract test: runs tests/golden/cases.sh with the given pkm program and
# compares every record, byte for byte, with the one kept in tests/data/golden/. Prints the first
# differences and exits 1 when any record differs. To accept an intended change of output:
#   tests/golden/cases.sh build/bin/pkm tests/data/golden
# and review the diff before committing it.
#
# Usage: tests/golden/check.sh PKM [--skip REGEX]
#   --skip: cases whose name matches the extended regular expression are neither run nor compared
#   (the sanitizer build skips the slowest twin of a case whose code another case runs).
set -euo pipefail
pkm=$1
skip=${3:-}
if [ "${2:-}" != "" ] && [ "$2" != --skip ]; then
  echo "check.sh: unknown option $2 (usage: check.sh PKM [--skip REGEX])" >&2
  exit 2
fi
src=$(cd "$(dirname "$0")/../.." && pwd)
actual=$(mktemp -d)
trap 'rm -rf "$actual"' EXIT
expected="$actual/expected"
mkdir "$expected"
for f in "$src"/tests/data/golden/*.txt; do
  case_name=$(basename "$f" .txt)
  if [ -n "$skip" ] && [[ $case_name =~ ^($skip)$ ]]; then continue; fi
  cp "$f" "$expected/"
done
PKM_GOLDEN_SKIP=$skip bash "$src/tests/golden/cases.sh" "$pkm" "$actual/records"
if diff -r -u "$expected" "$actual/records" >"$actual/diff"; then
  echo "golden: $(ls "$expected" | wc -l) records identical${skip:+ (skipped: $skip)}"
  exit 0
fi
echo "golden: the output of pkm differs from tests/data/golden (first 200 lines of the diff):"
head -n 200 "$actual/diff"
exit 1
