#!/usr/bin/env bash
# Whole-process comparison of `pkm calibrate hexapod` with scipy on a full-pose laser-tracker data
# set: 80 random poses of the default hexapod (data/machines/hexapod-default.json) whose joints are
# off by up to 3.3 mm and whose strut offsets by up to 1.8 mm, measured by `pkm simulate` with the
# preset "laser-tracker" noise (7.5 µm + 3 µm/m, 3 µrad, 6-DOF orientation 0.005°) and struts with
# 1 µm encoders, 2 µm repeatability and 5 µm backlash; the tracker aligned to the world frame, so
# the fit has the 42 parameters (6 base joints xyz, 6 platform joints xyz, 6 strut offsets).
#
# pkm: `pkm calibrate hexapod --machine M --data F --out CAL.json --force` (the fit, its guards,
# identifiability, covariance, the uncertainty budgets and predicted TCP U, the workspace TCP map,
# CAL.json, CAL.hal, CAL.pkmhexkins.hal and CAL.summary.json; the report to a file).
# The reference is what a user would otherwise run: Debian's /usr/bin/python3 reads the same files
# (np.loadtxt, the machine's JSON) and minimises the same residuals as pkm's full-pose calibration,
# r_i = |p + R·(a_i − t) − b_i| − offset_i − q_i (R = Rz(c)·Ry(b)·Rx(a), t the tool offset plus the
# file's smr offset; docs/calibration.md "Measurement models"), with scipy.optimize.least_squares
# and the analytic Jacobian, writing its parameters to a file. Its method ("lm" or "trf") is the
# faster of the two on this problem, chosen by 3 whole runs of each before the timing.
# Both run as whole processes in alternating pairs; the medians, their ratio and the machine are
# printed, and the two fits are compared (every parameter within 1e-6 mm, else exit 1).
# Usage: benchmarks/calibration_vs_scipy_whole_process.sh [path/to/pkm] [pairs]
set -euo pipefail
pkm=${1:-build/bin/pkm}
pairs=${2:-11}
python=/usr/bin/python3
src=$(cd "$(dirname "$0")/.." && pwd)
machine="$src/data/machines/hexapod-default.json"
tolerance=1e-6  # mm: the largest parameter difference accepted as the same fit
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

cpu=$(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2- | sed 's/^ *//')
echo "machine: $(nproc) cores, ${cpu:-unknown CPU}, load average $(cut -d' ' -f1-3 /proc/loadavg)"
if ! "$python" -c 'import numpy, scipy.optimize' 2>/dev/null; then
  echo "calibration vs scipy: skipped (Debian's python3-numpy and python3-scipy are not installed; scripts/setup.sh installs them)"
  exit 0
fi

cat > "$work/scenario.json" <<'JSON'
{
  "schema": "pkm.scenario/1",
  "type": "simulation_scenario",
  "name": "bench-hexapod-calibration",
  "description": "80 tracker poses of the default hexapod with assembly errors, for the calibration benchmark",
  "seed": 42,
  "machine": {
    "kind": "hexapod",
    "machine": "hexapod-default",
    "errors": {
      "base_joint": [[2.4, -1.8, 0.9], [-1.5, 3.0, -0.6], [2.1, 1.2, 1.2], [-2.7, -0.9, -1.2], [1.2, -3.3, 0.6], [-1.8, 2.1, -0.9]],
      "platform_joint": [[-1.2, 0.9, 0.3], [0.6, -1.5, -0.3], [-0.9, -0.6, 0.6], [1.5, 0.3, -0.6], [-0.3, 1.2, 0.3], [0.9, -0.9, -0.3]],
      "length_offset": [1.2, -0.9, 1.8, -1.5, 0.6, -1.8]
    },
    "actuation": {"encoder_resolution": 0.001, "backlash": 0.005, "repeatability_sigma": 0.002}
  },
  "measurements": [
    {"name": "tracker-pose", "instrument": "laser_tracker", "mode": "pose",
     "random_poses": {"count": 80, "x": [-200, 200], "y": [-200, 200], "z": [120, 320],
                      "a": [-10, 10], "b": [-10, 10], "c": [-20, 20]},
     "smr_offset": [0, 60, 80], "noise": "laser-tracker"}
  ]
}
JSON
"$pkm" simulate "$work/scenario.json" --out "$work/sim" > /dev/null
data="$work/sim/tracker-pose.csv"

cat > "$work/reference.py" <<'PY'
import json
import re
import sys
import numpy as np
from scipy.optimize import least_squares

data_path, machine_path, out_path, method = sys.argv[1:5]
smr, header = np.zeros(3), 0
with open(data_path) as f:
    for line in f:
        header += 1
        if not line.startswith("#"):
            break  # the column names
        m = re.match(r"# smr offset mm: \((.*)\)", line)
        if m:
            smr = np.array([float(v) for v in m.group(1).split(",")])
table = np.loadtxt(data_path, delimiter=",", skiprows=header)
q, p, rpy = table[:, 0:6], table[:, 6:9], np.radians(table[:, 9:12])
ca, sa = np.cos(rpy[:, 0]), np.sin(rpy[:, 0])
cb, sb = np.cos(rpy[:, 1]), np.sin(rpy[:, 1])
cc, sc = np.cos(rpy[:, 2]), np.sin(rpy[:, 2])
R = np.empty((len(p), 3, 3))  # R = Rz(c) Ry(b) Rx(a)
R[:, 0, 0], R[:, 0, 1], R[:, 0, 2] = cc * cb, cc * sb * sa - sc * ca, cc * sb * ca + sc * sa
R[:, 1, 0], R[:, 1, 1], R[:, 1, 2] = sc * cb, sc * sb * sa + cc * ca, sc * sb * ca - cc * sa
R[:, 2, 0], R[:, 2, 1], R[:, 2, 2] = -sb, cb * sa, cb * ca
machine = json.load(open(machine_path))
tcp = np.array(machine["tool_offset"], float) + smr  # the tracker target is the fitted TCP
start = np.concatenate([np.r_[s["base"], s["platform"], s["length_offset"]] for s in machine["struts"]])


def legs(x):
    th = x.reshape(6, 7)  # per strut: base xyz, platform xyz, offset
    return p[:, None, :] + np.einsum("nij,kj->nki", R, th[:, 3:6] - tcp) - th[None, :, 0:3], th


def residual(x):
    v, th = legs(x)
    return (np.linalg.norm(v, axis=2) - th[None, :, 6] - q).ravel()


def jacobian(x):
    v, _ = legs(x)
    u = v / np.linalg.norm(v, axis=2)[..., None]
    J = np.zeros((len(p), 6, 6, 7))
    k = np.arange(6)
    J[:, k, k, 0:3] = -u
    J[:, k, k, 3:6] = np.einsum("nki,nij->nkj", u, R)
    J[:, k, k, 6] = -1.0
    return J.reshape(len(p) * 6, 42)


fit = least_squares(residual, start, jac=jacobian, method=method)
np.savetxt(out_path, fit.x, fmt="%.12f", header=f"nfev {fit.nfev} njev {fit.njev} status {fit.status}")
PY

# Times are read from bash's $EPOCHREALTIME (no process is started to read the clock).
export LC_ALL=C  # a decimal point in $EPOCHREALTIME
median() { printf '%s\n' "$@" | sort -g | awk '{ v[NR] = $1 } END { print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }
run_pkm() {
  "$pkm" calibrate hexapod --machine "$machine" --data "$data" --out "$work/pkm/CAL.json" --force \
    > "$work/pkm/report.txt" 2> "$work/pkm/notes.txt"
}
run_ref() { "$python" "$work/reference.py" "$data" "$machine" "$work/ref-$1.txt" "$1"; }
mkdir -p "$work/pkm"

# The reference at its fastest: 3 whole runs of each method, the lower median is timed below.
declare -A pick
for method in lm trf; do
  t=()
  for ((i = 0; i < 3; ++i)); do
    s=$EPOCHREALTIME; run_ref "$method"; e=$EPOCHREALTIME
    t+=("$(echo "$e - $s" | bc -l)")
  done
  pick[$method]=$(median "${t[@]}")
done
method=lm
if (($(echo "${pick[trf]} < ${pick[lm]}" | bc -l))); then method=trf; fi

pkm_times=()
ref_times=()
for ((i = 0; i < pairs; i++)); do
  s=$EPOCHREALTIME; run_pkm; e=$EPOCHREALTIME
  pkm_times+=("$(echo "$e - $s" | bc -l)")
  s=$EPOCHREALTIME; run_ref "$method"; e=$EPOCHREALTIME
  ref_times+=("$(echo "$e - $s" | bc -l)")
done
pkm_med=$(median "${pkm_times[@]}")
ref_med=$(median "${ref_times[@]}")
min_max() { printf '%s\n' "$@" | sort -g | awk 'NR == 1 { lo = $1 } { hi = $1 } END { printf "%.4f-%.4f", lo, hi }'; }

"$python" - "$work/pkm/CAL.json" "$work/ref-$method.txt" "$work/sim/truth.json" "$tolerance" <<'PY'
import json, sys
import numpy as np
cal, ref, truth, tol = sys.argv[1], sys.argv[2], sys.argv[3], float(sys.argv[4])
m = json.load(open(cal))
pkm = np.concatenate([np.r_[s["base"], s["platform"], s["length_offset"]] for s in m["struts"]])
scipy = np.loadtxt(ref)
with open(ref) as f:
    info = f.readline().strip("# \n")
d = np.abs(pkm - scipy).max()
print(f"  fits: 42 parameters; max |pkm - scipy| {d:.3g} mm",
      f"(agree: within {tol:g} mm)" if d <= tol else f"(DISAGREE: more than {tol:g} mm)",
      f"[scipy: {info}]")
if d > tol:
    sys.exit(1)
PY
iterations=$(grep -o 'solver: [0-9]* iterations' "$work/pkm/report.txt" | grep -o '[0-9]*' || echo '?')
printf '  pkm calibrate hexapod (80 poses, %s LM iterations, budgets and 4 files): median of %d runs %.4f s (range %s s)\n' \
  "$iterations" "$pairs" "$pkm_med" "$(min_max "${pkm_times[@]}")"
printf '  scipy (np.loadtxt + least_squares %s, analytic Jacobian; lm %.3f s, trf %.3f s in the pick): median %.4f s (range %s s)\n' \
  "$method" "${pick[lm]}" "${pick[trf]}" "$ref_med" "$(min_max "${ref_times[@]}")"
printf '  -> pkm is %.1fx faster (load average after: %s)\n' \
  "$(echo "$ref_med / $pkm_med" | bc -l)" "$(cut -d' ' -f1-3 /proc/loadavg)"
# For benchmarks/summary.sh: job | pkm s | reference | reference s | target ratio.
printf 'bench-row|calibrate hexapod, 80 tracker poses, 42 parameters|%s|scipy (loadtxt + least_squares %s, analytic Jacobian)|%s|50\n' \
  "$pkm_med" "$method" "$ref_med"
