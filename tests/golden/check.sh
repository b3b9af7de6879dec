#!/usr/bin/env bash
# The command-line contract test: runs tests/golden/cases.sh with the given pkm program and
# compares every record, byte for byte, with the one kept in tests/data/golden/. Prints the first
# differences and exits 1 when any record differs. To accept an intended change of output:
#   tests/golden/cases.sh build/bin/pkm tests/data/golden
# and review the diff before committing it.
set -euo pipefail
pkm=$1
src=$(cd "$(dirname "$0")/../.." && pwd)
expected="$src/tests/data/golden"
actual=$(mktemp -d)
trap 'rm -rf "$actual"' EXIT
bash "$src/tests/golden/cases.sh" "$pkm" "$actual/records"
if diff -r -u "$expected" "$actual/records" >"$actual/diff"; then
  echo "golden: $(ls "$expected" | wc -l) records identical"
  exit 0
fi
echo "golden: the output of pkm differs from tests/data/golden (first 200 lines of the diff):"
head -n 200 "$actual/diff"
exit 1
