#!/usr/bin/env bash
# The full coverage validation of docs/coverage.md: `pkm validate coverage` over 200 seeds of the
# default scenarios, in each scenario's own environment and in the "realistic" workshop. Prints
# the tables and writes coverage.json and report.html per environment into OUT (default
# coverage-200/). Not a timing benchmark: the figures of docs/coverage.md come from it. The
# realistic workshop's budgets state its machines as an engineer states them (the screws' grade,
# the Exechon head's weight: data/uncertainty/realistic-workshop.json).
# Usage: benchmarks/coverage_full.sh [path/to/pkm] [OUT] [SEEDS]
set -euo pipefail
pkm=${1:-build/bin/pkm}
out=${2:-coverage-200}
seeds=${3:-200}
for env in own realistic; do
  args=(validate coverage --seeds "$seeds" --out "$out/$env" --force)
  [ "$env" = realistic ] &&
    args+=(--environment realistic --uncertainty "$(dirname "$0")/../data/uncertainty/realistic-workshop.json")
  echo "== environment: $env, $seeds seeds"
  "$pkm" "${args[@]}"
done
