#!/usr/bin/python3
"""The pkmhexkins kinematics module in a running LinuxCNC (docs/linuxcnc.md).

A calibrated hexapod-sim machine (all 42 parameters moved, the platform's tool point too) gets its
configuration from `pkm linuxcnc config`, switched to the pins route: the geometry as the
module's HAL pins (`pkm hexapod hal --kins pkmhexkins`) instead of the parameter file (that
route: config_runs_test.py, load_failures_test.py). LinuxCNC is started on it headless (linuxcncrsh, POSIX
non-realtime) with the module built by this build tree, homed, and moved by MDI. Checked:
  - after homing, LinuxCNC's world position (its forward kinematics) is [TRAJ] HOME;
  - at each pose, the joint positions equal pkm's inverse kinematics of the calibrated machine,
    and the world position LinuxCNC reports equals the commanded pose (forward kinematics in the
    loop);
  - with a G43 tool length offset, the joints equal pkm's IK of the machine with the tool length
    added to its spindle offset (genhexkins' tool-offset convention).
All to 1e-6 in (linuxcncrsh prints 6 decimals).

LinuxCNC is started, stopped and cleaned up by lcnc_harness.py (this build's module loaded through
a private mount namespace, LinuxCNC run as the unprivileged test user; exit 77, skipped, without
LinuxCNC, the module, the user or a way to load the module).

Usage: hexkins_runs_test.py PKM_BINARY MODULE_SO SOURCE_DIR
"""
import json
import os
import random
import re
import shutil
import subprocess
import sys
import time

import lcnc_harness as lh

HOME = (0.0, 0.0, 20.0, 0.0, 0.0, 0.0)
POSES = [(1, 1, 21, 0, 0, 0), (-2, 1.5, 19, 3, -2, 5), (0.5, -2, 22.5, -4, 1, -3),
         (2.5, 0.5, 20.5, 6, 4, -8)]
TOOL_POSES = [(0.5, -0.5, 20, 0, 0, 0), (-1, 1, 21, 5, -4, 2)]
TOOL_LENGTH = 0.5  # T1 in the tool table write_config writes
TOL = 1e-6  # inch: 6 printed decimals (5e-7) plus the FK tolerance (1e-9)


def run(cmd):
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit(f"FAIL: {' '.join(cmd)} exited {r.returncode}\n{r.stdout}\n{r.stderr}")
    return r.stdout


def calibrated_machine(source_dir):
    """The hexapod-sim machine with all 42 parameters and the tool point moved (fixed seed)."""
    with open(os.path.join(source_dir, "data/machines/hexapod-linuxcnc-sim.json")) as f:
        m = json.load(f)
    rng = random.Random(20261127)
    m["name"] += "-calibrated"
    for s in m["struts"]:
        s["base"] = [v + rng.uniform(-0.05, 0.05) for v in s["base"]]
        s["platform"] = [v + rng.uniform(-0.05, 0.05) for v in s["platform"]]
        s["length_offset"] = rng.uniform(-0.05, 0.05)
    m["tool_offset"] = [0.02, -0.01, 0.03]
    return m


def write_machine(machine, work, name):
    path = os.path.join(work, name + ".json")
    with open(path, "w") as f:
        json.dump(machine, f)
    return path


def pkm_ik(pkm, machine, poses, work):
    path = write_machine(machine, work, "ik-machine")
    csv = os.path.join(work, "poses.csv")
    with open(csv, "w") as f:
        f.write("x,y,z,a,b,c\n" + "".join(",".join(map(repr, p)) + "\n" for p in poses))
    rows = run([pkm, "hexapod", "ik", "--machine", path, "--poses", csv]).strip().splitlines()
    return [[float(v) for v in r.split(",")[:6]] for r in rows[1:]]


def write_config(pkm, machine_path, work, name, setp=None):
    """`pkm linuxcnc config` of the machine, switched to the pins route: [KINS] KINEMATICS =
    pkmhexkins (no parameter file), its geometry the `setp` block of `pkm hexapod hal --kins
    pkmhexkins` (or `setp`, a block given instead); T1 is a TOOL_LENGTH tool."""
    cfg = os.path.join(work, name)
    run([pkm, "linuxcnc", "config", "--machine", machine_path, "--out", cfg, "--display",
         "linuxcncrsh"])
    ini = os.path.join(cfg, next(f for f in os.listdir(cfg) if f.endswith(".ini")))
    if setp is None:
        setp = run([pkm, "hexapod", "hal", "--kins", "pkmhexkins", "--machine", machine_path])
    with open(os.path.join(cfg, "kinematics.hal"), "w") as f:
        f.write("loadrt [KINS]KINEMATICS\n" + setp)
    with open(os.path.join(cfg, "tool.tbl"), "w") as f:
        f.write(f"T1 P1 Z{TOOL_LENGTH!r} ;test tool\n")
    lh.set_ini(ini, "KINS", "KINEMATICS", "pkmhexkins")
    cfg = lh.copy_config(cfg, work, name + "-run")  # readable by the LinuxCNC user
    return os.path.join(cfg, os.path.basename(ini))


def strut_copied(setp, src, dst):
    """The setp block with strut `dst`'s joint centres set to strut `src`'s."""
    values = dict(l.split()[1:3] for l in setp.splitlines() if l.startswith("setp "))
    out = []
    for line in setp.splitlines(keepends=True):
        parts = line.split()
        if len(parts) == 3 and re.fullmatch(rf"pkmhexkins\.(base|platform)\.{dst}\.[xyz]", parts[1]):
            line = f"setp {parts[1]} {values[parts[1].replace(f'.{dst}.', f'.{src}.')]}\n"
        out.append(line)
    return "".join(out)


def check(failures, what, got, want):
    err = max(abs(g - w) for g, w in zip(got, want))
    print(f"{what}: LinuxCNC {got}; pkm {want}; max difference {err:.1e}")
    if err > TOL:
        failures.append(f"{what}: differs from pkm by {err}")


def pkm_pins(cnc, names):
    return {n: cnc.pin(f"pkmhexkins.{n}") for n in names}


def moves(expected, expected_tool):
    """Home, the MDI poses and the tool poses, each checked against pkm."""

    def body(cnc, failures):
        cnc.home()
        check(failures, "world after homing", cnc.world(), HOME)
        for pose, want in zip(POSES, expected[1:]):
            cnc.mdi("G0 X{} Y{} Z{} A{} B{} C{}".format(*pose))
            check(failures, f"joints at {pose}", cnc.joints(), want)
            check(failures, f"world at {pose}", cnc.world(), pose)
        pins = pkm_pins(cnc, ["fwd-kins-fail", "geometry-ok", "max-iterations",
                              "last-iterations", "fwd-kins-failures"])
        print(f"pkmhexkins pins: {pins}")
        if pins["fwd-kins-fail"] is not False or pins["geometry-ok"] is not True:
            failures.append(f"forward kinematics reports a failure: {pins}")
        if not isinstance(pins["max-iterations"], int) or pins["max-iterations"] < 1:
            failures.append("LinuxCNC never ran the module's forward kinematics")
        cnc.mdi("T1 M6")
        cnc.mdi("G43")
        for pose, want in zip(TOOL_POSES, expected_tool):
            cnc.mdi("G0 X{} Y{} Z{} A{} B{} C{}".format(*pose))
            check(failures, f"joints at {pose} with G43 (tool {TOOL_LENGTH} in)", cnc.joints(),
                  want)

    return body


def refused(cnc, failures):
    """A geometry the module refuses: no motion, geometry-ok false."""
    for c in ["set estop off", "set machine on", "set mode manual", "set home -1"]:
        cnc.ask(c)
    time.sleep(1.0)
    ok = cnc.pin("pkmhexkins.geometry-ok")
    if ok is not False:
        failures.append(f"a bad geometry was accepted: geometry-ok is {ok}")
    cnc.ask("set mode mdi")
    if "NAK" not in cnc.ask("set mdi G0 X1 Y1 Z21"):
        cnc.ask("set wait done")
        if any(abs(v) > 1e-9 for v in cnc.joints()[:3]) and "NO" in cnc.ask(
                "get joint_homed").split():
            failures.append("a bad geometry moved the machine")


def main():
    pkm, module, source_dir = (os.path.abspath(a) for a in sys.argv[1:4])
    lh.require([module])
    work = lh.workdir("pkm-hexkins-")
    machine = calibrated_machine(source_dir)
    expected = pkm_ik(pkm, machine, [HOME] + POSES, work)
    tooled = dict(machine, spindle_offset=TOOL_LENGTH)
    tool_poses = [(x, y, z + TOOL_LENGTH, a, b, c) for x, y, z, a, b, c in TOOL_POSES]
    expected_tool = pkm_ik(pkm, tooled, tool_poses, work)
    machine_path = write_machine(machine, work, "calibrated")

    ini = write_config(pkm, machine_path, work, "cfg")
    failures, text = lh.session(ini, [module], "calibrated", work, moves(expected, expected_tool))
    if "pkmhexkins:" in text:
        failures.append("the module reported an error")
    if failures:
        sys.exit("FAIL:\n" + "\n".join(failures) + "\n--- linuxcnc log ---\n" + text)

    # A geometry that does not assemble, set by pins: strut 4 given as a second copy of strut 3.
    setp = run([pkm, "hexapod", "hal", "--kins", "pkmhexkins", "--machine", machine_path])
    bad_ini = write_config(pkm, machine_path, work, "bad", strut_copied(setp, 3, 4))
    failures, text = lh.session(bad_ini, [module], "bad-geometry", work, refused)
    message = "pkmhexkins: unusable geometry: struts 3 and 4 join the same joints"
    if message not in text:
        failures.append(f"the log does not say '{message}'")
    if failures:
        sys.exit("FAIL (bad geometry):\n" + "\n".join(failures) + "\n--- linuxcnc log ---\n" + text)
    print(f"bad geometry: refused with '{message}' in LinuxCNC's log")
    shutil.rmtree(work, ignore_errors=True)
    print("ok: pkmhexkins runs in LinuxCNC with pkm's kinematics of the calibrated machine")


if __name__ == "__main__":
    main()
