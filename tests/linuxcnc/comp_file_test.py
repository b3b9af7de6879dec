#!/usr/bin/python3
"""COMP_FILE tables written by `pkm compensate table` in a running LinuxCNC (docs/compensation.md).

Two struts of data/linuxcnc/hexapod-linuxcnc-sim get a joint error table: joint 0 a `--format
linuxcnc0` file (COMP_FILE_TYPE = 0), joint 1 a `--format linuxcnc1` file (type 1), each written
by pkm from ISO 230-2 positioning data with known errors e = reading − target per direction (5
runs, no noise, so the evaluated means are the errors). The tables' rows are the struts' readings
at Z = 16, 19, 22, 25 (X = Y = 0, no rotation) and two end rows. LinuxCNC is homed and moved along
Z up and down; after each move, at rows and between rows, checked for both joints:
  - joint.N.motor-pos-cmd − joint.N.motor-offset − joint.N.pos-cmd (motor-offset: the joint's
    home offset, LinuxCNC's motor command is pos-cmd + correction + motor-offset)
    = −e(direction, pos-cmd), e interpolated linearly
    between the rows in the commanded joint position, the forward (+) errors after a move that
    lengthened the strut and the reverse (−) errors after one that shortened it: the sign
    docs/compensation.md states (type 0 stores the actual position P + e, LinuxCNC's trim is
    nominal − actual = −e; type 1 stores the trim −e);
    (to the table's slope times the last servo step, STEP below);
  - −e equals the value interpolated from the written file itself (what LinuxCNC read), 1e-12;
  - joint.N.pos-fb = joint.N.pos-cmd to 1e-9 in: the feedback does not carry the correction.
LinuxCNC is run by lcnc_harness.py (exit 77 when it cannot run here).

Usage: comp_file_test.py PKM_BINARY HEXKINS_SO SOURCE_DIR
"""
import bisect
import os
import shutil
import subprocess
import sys
import time

import lcnc_harness as lh

Z_ROWS = [16.0, 19.0, 22.0, 25.0]  # strut readings at these Z are table rows
ENDS = [24.0, 35.0]  # inch: first and last row
# Errors e = reading − target (inch) per row, forward (+) and reverse (−), per joint.
ERRORS = {0: ([0.004, -0.006, 0.010, 0.002, -0.008, 0.003],
              [0.001, -0.003, 0.006, 0.005, -0.004, 0.000]),
          1: ([-0.005, 0.007, -0.002, 0.009, 0.001, -0.006],
              [-0.002, 0.004, 0.001, 0.006, -0.003, -0.004])}
FORMAT = {0: "linuxcnc0", 1: "linuxcnc1"}
# Z of the stops: down first (reverse), then up through rows and between rows (forward), down.
STOPS = [15.0, 16.0, 17.5, 19.0, 20.5, 22.0, 23.5, 25.0, 23.5, 22.0, 20.5, 19.0, 17.5, 16.0]
# LinuxCNC evaluates the table at the joint's commanded position while it moves and keeps the last
# value when it stops (control.c: no direction at zero velocity), so the correction belongs to the
# position of the last servo cycle that moved, a few µin before the end: the correction may differ
# from the table at the final position by the table's slope times that last step (≤ STEP).
STEP = 2e-5  # inch
TOL = 1e-12  # inch: −e against the written file (the table's own rounding)
SETTLE = 0.3  # s after a move: LinuxCNC ramps the correction within the joint's limits


def run(cmd):
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit(f"FAIL: {' '.join(cmd)} exited {r.returncode}\n{r.stdout}\n{r.stderr}")
    return r.stdout


def interpolate(xs, ys, x):
    """Linear interpolation in (xs, ys), the end values held outside (LinuxCNC's rule)."""
    if x <= xs[0]:
        return ys[0]
    if x >= xs[-1]:
        return ys[-1]
    k = bisect.bisect_right(xs, x) - 1
    return ys[k] + (ys[k + 1] - ys[k]) * (x - xs[k]) / (xs[k + 1] - xs[k])


def slope(xs, ys, x):
    """The largest |slope| of the table segments within STEP of x (0 outside the table)."""
    worst = 0.0
    for k in range(len(xs) - 1):
        if xs[k] - STEP <= x <= xs[k + 1] + STEP:
            worst = max(worst, abs((ys[k + 1] - ys[k]) / (xs[k + 1] - xs[k])))
    return worst


def write_data(path, targets, up, down):
    """ISO 230-2 positioning data (inch): 5 bidirectional runs reading target + e exactly."""
    with open(path, "w") as f:
        f.write("target_in,run,direction,reading_in\n")
        for run_number in range(1, 6):
            for t, e in zip(targets, up):
                f.write(f"{t!r},{run_number},+,{t + e!r}\n")
            for t, e in reversed(list(zip(targets, down))):
                f.write(f"{t!r},{run_number},-,{t + e!r}\n")


def read_table(path, comp_type):
    """The trims LinuxCNC takes from a COMP_FILE: (nominal, forward trim, reverse trim)."""
    nominal, forward, reverse = [], [], []
    with open(path) as f:
        for line in f:
            n, fw, rv = (float(v) for v in line.split())
            nominal.append(n)
            forward.append(n - fw if comp_type == 0 else fw)  # type 0: nominal − actual
            reverse.append(n - rv if comp_type == 0 else rv)
    return nominal, forward, reverse


def write_tables(pkm, work, cfg, ini):
    """Writes the COMP_FILE tables of joints 0 and 1 with pkm and sets them in `ini`. Returns
    {joint: (rows, −e forward, −e reverse)} (the docs' sign) and {joint: read_table(file)}."""
    poses = os.path.join(work, "poses.csv")
    with open(poses, "w") as f:
        f.write("x,y,z,a,b,c\n" + "".join(f"0,0,{z!r},0,0,0\n" for z in Z_ROWS))
    rows = run([pkm, "hexapod", "ik", "--machine", "hexapod-linuxcnc-sim", "--poses", poses])
    readings = [[float(v) for v in r.split(",")[:6]] for r in rows.strip().splitlines()[1:]]
    expected, tables = {}, {}
    for j in (0, 1):
        targets = [ENDS[0]] + [q[j] for q in readings] + [ENDS[1]]
        data = os.path.join(work, f"joint{j}.csv")
        write_data(data, targets, *ERRORS[j])
        table = os.path.join(cfg, f"joint{j}.comp")
        print(run([pkm, "compensate", "table", "--data", data, "--format", FORMAT[j], "--axis",
                   f"J{j}", "--ini", ini, "--out", table]).strip().replace("\n", "; "))
        os.chmod(table, 0o644)
        with open(table) as f:
            print(f"{FORMAT[j]} table of joint {j}:\n{f.read().rstrip()}")
        lh.set_ini(ini, f"JOINT_{j}", "COMP_FILE", table)
        lh.set_ini(ini, f"JOINT_{j}", "COMP_FILE_TYPE", str(j))
        up, down = ERRORS[j]
        expected[j] = (targets, [-e for e in up], [-e for e in down])  # the docs' sign: −e
        tables[j] = read_table(table, j)
    return expected, tables


def main():
    pkm, module, source_dir = (os.path.abspath(a) for a in sys.argv[1:4])
    lh.require([module])
    work = lh.workdir("pkm-comp-file-")
    sample = os.path.join(source_dir, "data/linuxcnc/hexapod-linuxcnc-sim")
    cfg = lh.copy_config(sample, work, "cfg")
    ini = os.path.join(cfg, "hexapod-linuxcnc-sim.ini")
    lh.make_headless(ini)
    expected, tables = write_tables(pkm, work, cfg, ini)

    checked = {"forward": 0, "reverse": 0, "at a row": 0, "between rows": 0}
    worst = [0.0]

    def body(cnc, failures):
        cnc.home()
        names = [f"joint.{j}.{p}" for j in (0, 1)
                 for p in ("pos-cmd", "motor-pos-cmd", "motor-offset", "pos-fb")]
        before = cnc.pins(names)
        for z in STOPS:
            cnc.mdi(f"G0 X0 Y0 Z{z!r} A0 B0 C0")
            time.sleep(SETTLE)
            pins = cnc.pins(names)
            for j in (0, 1):
                q = pins[f"joint.{j}.pos-cmd"]
                moved = q - before[f"joint.{j}.pos-cmd"]
                direction = "forward" if moved > 0 else "reverse"
                k = 1 if moved > 0 else 2
                trim = pins[f"joint.{j}.motor-pos-cmd"] - pins[f"joint.{j}.motor-offset"] - q
                want = interpolate(expected[j][0], expected[j][k], q)
                from_file = interpolate(tables[j][0], tables[j][k], q)
                feedback = pins[f"joint.{j}.pos-fb"] - q
                at_row = min(abs(q - t) for t in expected[j][0]) < 1e-9
                print(f"Z {z:5}: joint {j} ({FORMAT[j]}) at {q:.9f} moving {direction}"
                      f"{' (a row)' if at_row else ''}: correction {trim:+.12f}, "
                      f"−e {want:+.12f} (file {from_file:+.12f}), pos-fb − pos-cmd "
                      f"{feedback:+.1e}")
                allowed = slope(expected[j][0], expected[j][k], q) * STEP + TOL
                worst[0] = max(worst[0], abs(trim - want))
                if abs(trim - want) > allowed:
                    failures.append(f"joint {j} at Z {z}: correction {trim} is not −e = {want} "
                                    f"(allowed {allowed:.1e} for the last step)")
                if abs(want - from_file) > TOL:
                    failures.append(f"joint {j} at Z {z}: the file gives {from_file}, not −e = "
                                    f"{want}")
                if abs(feedback) > 1e-9:
                    failures.append(f"joint {j} at Z {z}: pos-fb carries {feedback}")
                if abs(want) < 1e-4:
                    failures.append(f"joint {j} at Z {z}: test error, correction too small")
                checked[direction] += 1
                checked["at a row" if at_row else "between rows"] += 1
            before = pins

    failures, log = lh.session(ini, [module], "comp-file", work, body)
    if "pkmhexkins:" in log:
        failures.append("the kinematics module reported an error")
    print(f"checked: {checked}; largest |correction − (−e)| {worst[0]:.1e} in")
    if min(checked.values()) < 4:
        failures.append(f"too few checks of a kind: {checked}")
    if failures:
        sys.exit("FAIL:\n" + "\n".join(failures) + "\n--- linuxcnc log ---\n" + log)
    shutil.rmtree(work, ignore_errors=True)
    print("ok: LinuxCNC applies pkm's COMP_FILE tables (types 0 and 1) on the motor side as -e")


if __name__ == "__main__":
    main()
