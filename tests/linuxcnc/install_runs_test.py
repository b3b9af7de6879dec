#!/usr/bin/python3
"""`pkm linuxcnc install` proven in a running LinuxCNC (docs/linuxcnc.md).

A copy of LinuxCNC's own hexapod-sim configuration is patched with a calibration whose joints
differ from the sample's, LinuxCNC is started on it headless (linuxcncrsh, POSIX non-realtime),
homed, and sent to three poses by MDI; the joint positions it reports must be pkm's inverse
kinematics of the *calibrated* machine (and not of the nominal one). LinuxCNC is started, stopped
and cleaned up by lcnc_harness.py; exit 77 (skipped) when LinuxCNC is not installed or, as root,
the unprivileged user scripts/setup.sh creates is missing.

Usage: install_runs_test.py PKM_BINARY
"""
import json
import os
import shutil
import subprocess
import sys

import lcnc_harness as lh

POSES = [(1, 1, 21, 0, 0, 0), (-2, 1.5, 19, 3, -2, 5), (0.5, -2, 22.5, -4, 1, -3)]
# Joint positions agree to what linuxcncrsh prints (6 decimals) plus genhexkins' own forward
# kinematics tolerance on the commanded pose (its default convergence criterion 1e-9 in).
JOINT_TOL = 2e-6  # inch
# The calibration moves joints by 0.05 in: a nominal configuration would miss by far more.
CHANGE_MIN = 1e-3  # inch


def run(cmd, **kw):
    r = subprocess.run(cmd, capture_output=True, text=True, **kw)
    if r.returncode != 0:
        sys.exit(f"FAIL: {' '.join(cmd)} exited {r.returncode}\n{r.stdout}\n{r.stderr}")
    return r.stdout


def main():
    pkm = os.path.abspath(sys.argv[1])
    lh.require()
    work, cfg, ini = lh.hexapod_sample("pkm-linuxcnc-")

    # A calibration: the sample's machine with three joints moved.
    machine = json.loads(run([pkm, "hexapod", "describe", "--json", "--machine",
                              os.path.join(cfg, "kinematics.hal"), "--ini", ini]))
    nominal_path = os.path.join(work, "nominal.json")
    with open(nominal_path, "w") as f:
        json.dump(machine, f)
    machine["name"] += "-calibrated"
    machine["struts"][0]["base"][1] += 0.05
    machine["struts"][3]["platform"][0] -= 0.04
    machine["struts"][5]["base"][2] += 0.03
    cal = os.path.join(work, "cal.json")
    with open(cal, "w") as f:
        json.dump(machine, f)
    run([pkm, "linuxcnc", "install", "--calibration", cal, "--ini", ini, "--force"])
    assert os.path.exists(os.path.join(cfg, "kinematics.hal.pkm-backup"))

    poses_csv = os.path.join(work, "poses.csv")
    with open(poses_csv, "w") as f:
        f.write("x,y,z,a,b,c\n" + "".join(",".join(map(str, p)) + "\n" for p in POSES))

    def ik(machine_file):
        rows = run([pkm, "hexapod", "ik", "--machine", machine_file, "--poses", poses_csv])
        return [[float(v) for v in r.split(",")[:6]] for r in rows.strip().splitlines()[1:]]

    expected, nominal = ik(cal), ik(nominal_path)

    def body(cnc, failures):
        cnc.home()
        for pose, want, nom in zip(POSES, expected, nominal):
            cnc.mdi("G0 X{} Y{} Z{} A{} B{} C{}".format(*pose))
            got = cnc.joints()
            err = max(abs(g - w) for g, w in zip(got, want))
            off = max(abs(g - n) for g, n in zip(got, nom))
            print(f"pose {pose}: LinuxCNC {got}; pkm calibrated IK {want}; "
                  f"max difference {err:.2e} in (nominal IK differs by {off:.2e} in)")
            if err > JOINT_TOL:
                failures.append(f"pose {pose}: joints differ from pkm's by {err} in")
            if off < CHANGE_MIN:
                failures.append(f"pose {pose}: the calibration did not change the joints")

    failures, log = lh.session(ini, [], "install", work, body)
    if failures:
        sys.exit("FAIL:\n" + "\n".join(failures) + "\n--- linuxcnc log ---\n" + log)
    shutil.rmtree(work, ignore_errors=True)
    print("ok: the patched configuration runs in LinuxCNC with pkm's calibrated joints")


if __name__ == "__main__":
    main()
