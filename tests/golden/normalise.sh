#!/usr/bin/env bash
# Masks what legitimately differs between two runs of the same program (tests/golden/cases.sh):
# the scratch folder (argument 1), the source tree, and the wall-clock times that the campaign's
# progress lines and the calibrations' solver lines and JSON "seconds" report. Reads standard
# input, writes standard output.
set -euo pipefail
work=$1
src=$(cd "$(dirname "$0")/../.." && pwd)
sed -E \
  -e "s#${work}#<WORK>#g" \
  -e "s#${src}#<SRC>#g" \
  -e 's#^(  \[[0-9]+/[0-9]+ [a-z0-9-]+) +[0-9.]+ s\]#\1 <T> s]#' \
  -e 's#done in [0-9.]+ s#done in <T> s#' \
  -e 's# in [0-9.]+ s; report:# in <T> s; report:#' \
  -e 's#(iterations, )[0-9.]+ s#\1<T> s#' \
  -e 's#"seconds": -?[0-9.eE+-]+#"seconds": <T>#g'
