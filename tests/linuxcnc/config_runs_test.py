#!/usr/bin/python3
"""Configurations written by `pkm linuxcnc config` run in LinuxCNC (docs/linuxcnc.md, "From
`pkm linuxcnc config` to a running machine").

For each sample machine (hexapod-default in mm, the LinuxCNC hexapod-sim geometry in inch, the
Exechon mxt700s-like), a configuration is written fresh by `pkm linuxcnc config` (the same
command that wrote data/linuxcnc/; tests/workflow/linuxcnc_config_test.cpp checks that those
equal it), started headless with this build's kinematics modules, and checked:
  - after homing, the joints are the INI's HOME values and LinuxCNC's world position (forward
    kinematics) is the machine's home pose ([TRAJ] HOME);
  - MDI moves: the joints equal pkm's inverse kinematics of the commanded poses (hexapods:
    `pkm hexapod ik`; Exechon: `pkm gcode run --orientation axes`, world A/C being the wrist
    readings), and the world position equals the commanded pose;
  - a program (hexapod-default: examples/gcode/hexapod_contour.ngc; hexapod-sim: the
    calibration plan `pkm plan-poses --gcode` writes, with its M0 stops; Exechon:
    examples/gcode/exechon_contour.ngc read as wrist readings), stopped by M0 at the end of every
    motion: the joints equal the joints of `pkm gcode run` at that end point and the world
    position equals the program's pose;
  - Exechon: with a G43 tool length, the joints equal pkm's for the machine with the longer tool;
  - hexapod-sim: G0 from home to each of the 64 corners of the axis limits (A, B, C at theirs too): the
    world position is the commanded pose (no mirror pose through the base plane) and the joints
    equal `pkm hexapod ik`.
Joints are read from HAL at full precision; world positions through linuxcncrsh (6 decimals).
Tolerance 1e-6 of the machine unit (and degree).

Usage: config_runs_test.py PKM_BINARY PKMHEXKINS_SO PKMEXECHONKINS_SO SOURCE_DIR
"""
import json
import os
import shutil
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import config_helpers as ch  # noqa: E402
import lcnc_harness as lh  # noqa: E402

TOOL_LENGTH = 37.5  # mm, the Exechon's G43 test tool


def hexapod_body(pkm, machine, work, ini, poses, program, joints=6):
    """Home, MDI `poses`, then `program` with stops (a hexapod)."""
    values = ch.ini_values(ini)
    home = [float(v) for v in values["TRAJ"]["HOME"].split()]
    home_joints = [float(values[f"JOINT_{j}"]["HOME"]) for j in range(joints)]
    expected = ch.hexapod_ik(pkm, machine, poses, work)
    ends = ch.joint_ends(pkm, machine, program, work, inch=values["TRAJ"]["LINEAR_UNITS"] == "inch")
    stopped = ch.with_stops(program, ends, os.path.join(os.path.dirname(ini), "program.ngc"))

    def body(cnc, failures):
        cnc.home()
        ch.check(failures, "joints after homing", ch.joint_pins(cnc, joints), home_joints,
                 ch.PIN_TOL)
        ch.check(failures, "world after homing", cnc.world(6), home)
        for pose, want in zip(poses, expected):
            cnc.mdi("G0 X{} Y{} Z{} A{} B{} C{}".format(*pose))
            ch.check(failures, f"joints at MDI {pose}", lambda: ch.joint_pins(cnc, joints), want)
            ch.check(failures, f"world at MDI {pose}", lambda: cnc.world(6), pose)
        cnc.mdi("G0 X{} Y{} Z{} A{} B{} C{}".format(*home))  # the program starts at home

        def at_stop(k):
            line, pose, want = ends[k]
            ch.check(failures, f"joints at the end of line {line}", ch.joint_pins(cnc, joints),
                     want)
            ch.check(failures, f"world at the end of line {line}", cnc.world(6), pose)

        ch.run_program(cnc, stopped, len(ends), at_stop)
        print(f"{os.path.basename(program)}: {len(ends)} end points checked")

    return body


def corners(values):
    """16 of the 64 corners of the INI's X Y Z A B C limit box: the 2^(6-2) fractional factorial
    with A = XYZ and B = YZC (resolution IV), so that every three axes are seen at all eight
    combinations of their limits. All 64 corners are checked against pkm's kinematics without
    LinuxCNC (`pkm linuxcnc config` refuses a configuration whose limit box has a corner it cannot
    reach, tests/io/linuxcnc_config_test.cpp); here each corner costs two real-time rapids."""
    lim = [(float(values[f"AXIS_{a}"]["MIN_LIMIT"]), float(values[f"AXIS_{a}"]["MAX_LIMIT"]))
           for a in "XYZABC"]
    out = []
    for n in range(16):
        x, y, z, c = ((n >> k) & 1 for k in range(4))
        bits = (x, y, z, x ^ y ^ z, y ^ z ^ c, c)
        out.append(tuple(lim[k][bits[k]] for k in range(6)))
    return out


def corners_body(pkm, machine, work, ini):
    """G0 from home to every corner of the axis limits and back: LinuxCNC's world pose is the
    commanded one (a mirror pose through the base plane would show z negated) and the joints are
    `pkm hexapod ik`'s. From home, not corner to corner: the limit box is checked at its corners
    (`pkm linuxcnc config`), and a straight move between two corners that differ by 86 degrees
    in C at A, B = -43, +43 degrees crosses a singular configuration, which pkmhexkins refuses
    (an error, the move stopped) as it should."""
    values = ch.ini_values(ini)
    home = [float(v) for v in values["TRAJ"]["HOME"].split()]
    box = corners(values)
    expected = ch.hexapod_ik(pkm, machine, box, work)

    def body(cnc, failures):
        cnc.home()
        for pose, want in zip(box, expected):
            cnc.mdi("G0 X{} Y{} Z{} A{} B{} C{}".format(*pose))
            ch.check(failures, f"world at corner {pose}", lambda: cnc.world(6), pose)
            ch.check(failures, f"joints at corner {pose}", lambda: ch.joint_pins(cnc, 6), want)
            cnc.mdi("G0 X{} Y{} Z{} A{} B{} C{}".format(*home))
        print(f"{len(box)} corners of the axis limits checked")

    return body


def exechon_body(pkm, machine, work, ini, poses, program, source_dir):
    """Home, MDI `poses` (X Y Z A C), the program with stops, then G43 with a longer tool."""
    values = ch.ini_values(ini)
    home = [float(v) for v in values["TRAJ"]["HOME"].split()]
    home_joints = [float(values[f"JOINT_{j}"]["HOME"]) for j in range(5)]
    mdi = os.path.join(work, "exechon-mdi.ngc")
    with open(mdi, "w") as f:
        f.write("G21 G90\n" + "".join("G1 X{} Y{} Z{} A{} C{} F1000\n".format(*p) for p in poses)
                + "M2\n")
    expected = [q for _, _, q in ch.joint_ends(pkm, machine, mdi, work, exechon=True)]
    ends = ch.joint_ends(pkm, machine, program, work, exechon=True)
    stopped = ch.with_stops(program, ends, os.path.join(os.path.dirname(ini), "program.ngc"))
    # G43: LinuxCNC shifts the programmed Z by the tool length and the component adds it along
    # the tool: pkm's joints of the machine with the longer tool at the shifted point.
    with open(os.path.join(source_dir, "data/machines/mxt700s-like.json")) as f:
        longer = json.load(f)
    longer["wrist"]["tool_length"] += TOOL_LENGTH
    longer_path = os.path.join(work, "mxt700s-longer-tool.json")
    with open(longer_path, "w") as f:
        json.dump(longer, f)
    tool_pose = poses[-1]
    tool_mdi = os.path.join(work, "exechon-tool.ngc")
    with open(tool_mdi, "w") as f:
        f.write("G21 G90\n" + "".join("G1 X{} Y{} Z{} A{} C{} F1000\n".format(*p) for p in poses)
                + "G1 X{} Y{} Z{} A{} C{}\n".format(tool_pose[0], tool_pose[1],
                                                     tool_pose[2] + TOOL_LENGTH, tool_pose[3],
                                                     tool_pose[4]) + "M2\n")
    expected_tool = ch.joint_ends(pkm, longer_path, tool_mdi, work, exechon=True)[-1][2]

    def world5(cnc):
        w = cnc.world(6)
        return [w[0], w[1], w[2], w[3], w[5]]  # X Y Z A C (B is not a coordinate)

    def body(cnc, failures):
        cnc.home()
        ch.check(failures, "joints after homing", ch.joint_pins(cnc, 5), home_joints, ch.PIN_TOL)
        ch.check(failures, "world after homing", world5(cnc), home[:4] + home[5:])
        for pose, want in zip(poses, expected):
            cnc.mdi("G0 X{} Y{} Z{} A{} C{}".format(*pose))
            ch.check(failures, f"joints at MDI {pose}", ch.joint_pins(cnc, 5), want)
            ch.check(failures, f"world at MDI {pose}", world5(cnc), list(pose))
        cnc.mdi("G0 X{} Y{} Z{} A{} C{}".format(*home[:4], home[5]))  # the program starts at home

        def at_stop(k):
            line, pose, want = ends[k]
            ch.check(failures, f"joints at the end of line {line}", ch.joint_pins(cnc, 5), want)
            ch.check(failures, f"world at the end of line {line}", world5(cnc),
                     pose[:4] + pose[5:])

        ch.run_program(cnc, stopped, len(ends), at_stop)
        print(f"{os.path.basename(program)}: {len(ends)} end points checked")
        pins = cnc.pins(["pkmexechonkins.inv-kins-fail", "pkmexechonkins.fwd-kins-fail"])
        if any(pins.values()):
            failures.append(f"the component reports a failure: {pins}")
        cnc.mdi(f"G10 L1 P1 Z{TOOL_LENGTH}")
        cnc.mdi("T1 M6")
        cnc.mdi("G43")
        cnc.mdi("G0 X{} Y{} Z{} A{} C{}".format(*tool_pose))
        ch.check(failures, f"joints at {tool_pose} with G43 (tool {TOOL_LENGTH} mm)",
                 ch.joint_pins(cnc, 5), expected_tool)
        offset = cnc.pin("pkmexechonkins.tool-offset")
        if abs(offset - TOOL_LENGTH) > ch.PIN_TOL:
            failures.append(f"pkmexechonkins.tool-offset is {offset}, not {TOOL_LENGTH}")

    return body


def main():
    pkm, hexkins, exechonkins, source_dir = (os.path.abspath(a) for a in sys.argv[1:5])
    modules = [hexkins, exechonkins]
    lh.require(modules=modules, deadline=400)
    work = lh.workdir("pkm-config-runs-")
    examples = os.path.join(source_dir, "examples/gcode")
    all_failures = []

    # The default hexapod (mm): MDI poses and the contour example.
    ini = ch.config(pkm, "hexapod-default", work, "hexapod-default")
    poses = [(10, 5, 210, 0, 0, 0), (-40, 25, 180, 4, -3, 8), (60, -30, 230, -5, 2, -12)]
    body = hexapod_body(pkm, "hexapod-default", work, ini, poses,
                        os.path.join(examples, "hexapod_contour.ngc"))
    failures, log = lh.session(ini, modules, "hexapod-default", work, body)
    all_failures += [f"hexapod-default: {f}" for f in failures]

    # LinuxCNC's hexapod-sim geometry (inch): MDI poses and pkm's calibration plan program.
    plan = os.path.join(work, "plan.ngc")
    ch.run([pkm, "plan-poses", "--machine", "hexapod-linuxcnc-sim", "--count", "5", "--index",
            "O1", "--gcode", plan])
    ini = ch.config(pkm, "hexapod-linuxcnc-sim", work, "hexapod-linuxcnc-sim")
    poses = [(1, 1, 21, 0, 0, 0), (-2, 1.5, 19, 3, -2, 5), (2.5, 0.5, 20.5, 6, 4, -8)]
    body = hexapod_body(pkm, "hexapod-linuxcnc-sim", work, ini, poses, plan)
    failures, log2 = lh.session(ini, modules, "hexapod-linuxcnc-sim", work, body)
    all_failures += [f"hexapod-linuxcnc-sim: {f}" for f in failures]
    # The corners of its axis limits (the Z limit once reached across the base plane, z = 0).
    body = corners_body(pkm, "hexapod-linuxcnc-sim", work, ini)
    failures, _ = lh.session(ini, modules, "hexapod-linuxcnc-sim corners", work, body)
    all_failures += [f"hexapod-linuxcnc-sim corners: {f}" for f in failures]

    # The Exechon (mm): MDI tool points with wrist readings, the contour example, G43.
    ini = ch.config(pkm, "mxt700s-like", work, "exechon-mxt700s")
    poses = [(20, 80, 30, 0, 0), (-50, 40, 0, -20, 30), (0, 0, 50, 10, -45)]
    body = exechon_body(pkm, "mxt700s-like", work, ini, poses,
                        os.path.join(examples, "exechon_contour.ngc"), source_dir)
    failures, log3 = lh.session(ini, modules, "exechon-mxt700s", work, body)
    all_failures += [f"exechon-mxt700s: {f}" for f in failures]
    for text in (log, log2, log3):
        for line in text.splitlines():
            if "pkmhexkins:" in line or "pkmexechonkins:" in line:
                all_failures.append(f"the kinematics reported: {line}")

    if all_failures:
        sys.exit("FAIL:\n" + "\n".join(all_failures) + "\n--- last LinuxCNC log ---\n" + log3)
    shutil.rmtree(work, ignore_errors=True)
    print("ok: the configurations pkm linuxcnc config writes run in LinuxCNC with pkm's "
          "kinematics")


if __name__ == "__main__":
    main()
