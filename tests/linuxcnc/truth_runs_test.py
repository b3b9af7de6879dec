#!/usr/bin/python3
"""The simulated physical machine in LinuxCNC's loop (docs/linuxcnc.md, "A simulated machine in
the loop").

`pkm simulate seed004-hexapod-calibration` gives the truth of Lee et al.'s machine ("Development of
a Parallel-Typed CNC Machine": joint centres off by up to 33 mm, strut offsets up to 18 mm); its
actuation effects are set to zero here so that the sensors can be predicted exactly.
`pkm linuxcnc config --machine hexapod-default --simulate-truth TRUTH` writes the nominal machine's
configuration with pkm-truth in the loop. LinuxCNC is homed, the gauges and laser are zeroed
(pkmtruth.zero) and the platform is moved by MDI: in the table plane (x, y, c), up, tilted. At each
pose the joints LinuxCNC commands are read (HAL, full precision) and the TRUE machine's forward
kinematics of them (`pkm hexapod fk` on a machine file of the true geometry: not pkm-truth's code
path) gives the pose the sensors must read: pkmtruth.x..c, the three gauges n·(R t + p) − that at
zero (tips t of Lee et al.'s triangle) and the laser's x, within TOL.

Usage: truth_runs_test.py PKM_BINARY PKMHEXKINS_SO SOURCE_DIR
"""
import json
import math
import os
import shutil
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import config_helpers as ch  # noqa: E402
import lcnc_harness as lh  # noqa: E402

TOL = 1e-6  # mm: both forward kinematics converge to 1e-9 mm
TIPS = [(150, 0, 0), (-75, 129.9, 0), (-75, -129.9, 0)]  # the gauge tips, tool frame, mm
MOVES = [(30, 0, 0, 0, 0, 0), (30, 20, 0, 0, 0, 4), (-20, 25, 5, 0, 0, -3), (0, 0, 10, 2, -1.5, 0),
         (0, 0, 0, 0, 0, 0)]  # from home: dx dy dz (mm) da db dc (deg)


def rotation(a, b, c):
    """R = Rz(c)·Ry(b)·Rx(a), degrees (docs/conventions.md)."""
    a, b, c = (math.radians(v) for v in (a, b, c))
    ca, sa, cb, sb, cc, sc = math.cos(a), math.sin(a), math.cos(b), math.sin(b), math.cos(c), math.sin(c)
    return [[cc * cb, cc * sb * sa - sc * ca, cc * sb * ca + sc * sa],
            [sc * cb, sc * sb * sa + cc * ca, sc * sb * ca - cc * sa],
            [-sb, cb * sa, cb * ca]]


def tip_heights(pose):
    r = rotation(*pose[3:])
    return [sum(r[2][k] * t[k] for k in range(3)) + pose[2] for t in TIPS]


def truth_files(pkm, source_dir, work):
    """(the exact truth.json, the true machine's JSON)."""
    sim = os.path.join(work, "sim")
    ch.run([pkm, "simulate", "seed004-hexapod-calibration", "--out", sim])
    with open(os.path.join(sim, "truth.json")) as f:
        truth = json.load(f)
    truth["actuation"] = {"encoder_resolution": 0, "backlash": [0] * 6, "repeatability_sigma": 0}
    exact = os.path.join(work, "truth-exact.json")
    with open(exact, "w") as f:
        json.dump(truth, f)
    with open(os.path.join(source_dir, "data/machines/hexapod-default.json")) as f:
        true = json.load(f)
    g = truth["true_geometry"]
    for i, s in enumerate(true["struts"]):
        s["base"], s["platform"], s["length_offset"] = g["base"][i], g["platform"][i], g["length_offset"][i]
    true["name"] = "true-machine"
    true_path = os.path.join(work, "true.json")
    with open(true_path, "w") as f:
        json.dump(true, f)
    return exact, true_path


def main():
    pkm, hexkins, source_dir = (os.path.abspath(a) for a in sys.argv[1:4])
    lh.require(modules=[hexkins], deadline=170)
    truth_program = os.path.join(os.path.dirname(pkm), "pkm-truth")
    if not os.path.exists(truth_program):
        lh.skip(f"{truth_program} was not built (no LinuxCNC HAL headers)")
    work = lh.workdir("pkm-truth-")
    exact, true_machine = truth_files(pkm, source_dir, work)
    ini = ch.config(pkm, "hexapod-default", work, "cfg", ["--simulate-truth", exact])
    home = [float(v) for v in ch.ini_values(ini)["TRAJ"]["HOME"].split()]
    pins = [f"pkmtruth.{n}" for n in ("gauge-0", "gauge-1", "gauge-2", "laser-x",
                                      "x", "y", "z", "a", "b", "c", "ok")]
    readings = []

    def body(cnc, failures):
        cnc.home()
        cnc.setp("pkmtruth.zero", True)  # the operator zeroes the dials at home
        for move in MOVES:
            pose = [h + d for h, d in zip(home, move)]
            cnc.mdi("G0 X{} Y{} Z{} A{} B{} C{}".format(*pose))
            q = ch.joint_pins(cnc, 6)
            readings.append((pose, q, cnc.pins(pins)))
        cnc.setp("pkmtruth.zero", False)

    failures, log = lh.session(ini, [hexkins], "truth", work, body)
    if not readings or failures:
        sys.exit("FAIL:\n" + "\n".join(failures) + "\n--- linuxcnc log ---\n" + log)
    home_q = ch.hexapod_ik(pkm, "hexapod-default", [home], work)
    true_poses = ch.hexapod_fk(pkm, true_machine, home_q + [q for _, q, _ in readings], work)
    zero_pose, true_poses = true_poses[0], true_poses[1:]
    zero_heights = tip_heights(zero_pose)
    worst = 0.0
    for (pose, _, got), want in zip(readings, true_poses):
        gauges = [h - h0 for h, h0 in zip(tip_heights(want), zero_heights)]
        expected = gauges + [want[0] - zero_pose[0]] + want
        names = pins[:-1]
        for name, e in zip(names, expected):
            err = abs(float(got[name]) - e)
            worst = max(worst, err)
            if err > TOL:
                failures.append(f"command {pose}: {name} {got[name]}, the true machine {e}")
        if not got["pkmtruth.ok"]:
            failures.append(f"command {pose}: pkmtruth.ok is false")
        print(f"command {[round(v, 3) for v in pose]}: gauges "
              f"{[round(float(got[n]), 4) for n in names[:3]]} mm, laser {float(got['pkmtruth.laser-x']):.4f} mm")
    print(f"largest difference from the true machine's forward kinematics: {worst:.2e}")
    if failures:
        sys.exit("FAIL:\n" + "\n".join(failures) + "\n--- linuxcnc log ---\n" + log)
    shutil.rmtree(work, ignore_errors=True)
    print("ok: pkm-truth reads what the true machine does with LinuxCNC's joints")


if __name__ == "__main__":
    main()
