#!/usr/bin/env bash
# Formats every C++ file of the project with the repository's .clang-format (clang-format 14).
# Usage: scripts/format.sh [--check]   (--check: report, change nothing, exit 1 if unformatted)
set -euo pipefail
cd "$(dirname "$0")/.."
mapfile -t files < <(git ls-files '*.cpp' '*.hpp')
[ ${#files[@]} -eq 0 ] && exit 0
if [ "${1:-}" = "--check" ]; then
  clang-format --dry-run --Werror "${files[@]}"
else
  clang-format -i "${files[@]}"
fi
