#!/usr/bin/env bash
# The campaign step of the MXT700S parallelism paper on a PKM that is not calibrated, as the
# paper's was (its §4 names the PKM's own accuracy as the limit of the compensation): the built-in
# seed000-parallelism scenario with ILLUSTRATIVE Exechon tripod assembly errors of SCALE times
# those of the built-in exechon-calibration scenario (default 0.25: joint positions off by up to
# 0.3 mm, leg lengths by up to 0.28 mm, wrist zeros 0.15-0.2 mrad), in the realistic workshop.
# Prints the step's rows; docs/campaign.md ("Against the papers") quotes them. Not a timing
# benchmark.
# Usage: benchmarks/seed000_uncalibrated_pkm.sh [path/to/pkm] [SCALE]
set -euo pipefail
pkm=$(realpath "${1:-build/bin/pkm}")
scale=${2:-0.25}
src=$(cd "$(dirname "$0")/.." && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
/usr/bin/python3 - "$src" "$work" "$scale" <<'PY'
import json, sys
src, work, scale = sys.argv[1], sys.argv[2], float(sys.argv[3])
scenario = json.load(open(f"{src}/data/scenarios/seed000-parallelism.json"))
tripod = json.load(open(f"{src}/data/scenarios/exechon-calibration.json"))["machine"]["tripod_errors"]
scenario["name"] = "seed000-uncalibrated-pkm"
scenario["machine"]["tripod_errors"] = {
    k: [x * scale for x in v] if isinstance(v, list) else v * scale for k, v in tripod.items()}
json.dump(scenario, open(f"{work}/scenario.json", "w"), indent=1)
json.dump({"schema": "pkm.campaign/1", "name": "seed000-uncalibrated-pkm",
           "description": "seed 000 on an uncalibrated PKM",
           "steps": [{"id": "seed000", "kind": "hybrid-squareness", "scenario": "scenario.json",
                      "environment": "realistic"}]},
          open(f"{work}/campaign.json", "w"))
PY
cd "$work"
"$pkm" campaign run campaign.json --out out | grep -E '^seed000' || true
