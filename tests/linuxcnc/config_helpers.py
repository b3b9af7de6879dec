"""Helpers of the tests that run configurations written by `pkm linuxcnc config` in LinuxCNC
(config_runs_test.py, calibration_roundtrip_test.py; docs/linuxcnc.md, "From `pkm linuxcnc
config` to a running machine"): the configuration, pkm's joints for poses and programs, a
program stopped (M0) at the end of every motion, and the checks. LinuxCNC itself is started
and stopped by lcnc_harness."""
import csv
import io
import os
import re
import subprocess
import sys
import time

import lcnc_harness as lh

TOL = 1e-6  # machine unit (and degrees): linuxcncrsh prints 6 decimals (5e-7)
PIN_TOL = 1e-9  # joint positions read from HAL at full precision


def run(cmd):
    """Runs a command; exits the test (FAIL) when it fails; returns its standard output."""
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit(f"FAIL: {' '.join(cmd)} exited {r.returncode}\n{r.stdout}\n{r.stderr}")
    return r.stdout


def config(pkm, machine, work, name, extra=()):
    """`pkm linuxcnc config --machine MACHINE --display linuxcncrsh` into work/name; the INI."""
    written = os.path.join(work, name + ".written")
    out = run([pkm, "linuxcnc", "config", "--machine", machine, "--out", written, "--display",
               "linuxcncrsh", *extra])
    ini_name = os.path.basename(re.search(r"run it with: linuxcnc (\S+)", out).group(1))
    cfg = lh.copy_config(written, work, name)  # LinuxCNC's user writes linuxcnc.var and tool.tbl
    ini = os.path.join(cfg, ini_name)
    lh.set_ini(ini, "DISPLAY", "MAX_FEED_OVERRIDE", "5")  # programs run at up to 5x their feed
    return ini


def ini_values(ini):
    """{section: {key: value}} of an INI (the first value of a key)."""
    values, section = {}, None
    with open(ini) as f:
        for line in f:
            line = line.strip()
            if line.startswith("["):
                section = line.strip("[]")
                values.setdefault(section, {})
            elif "=" in line and not line.startswith("#") and section:
                key, value = (s.strip() for s in line.split("=", 1))
                values[section].setdefault(key, value)
    return values


def hexapod_ik(pkm, machine, poses, work):
    """pkm hexapod ik: the strut readings of each pose (x y z a b c)."""
    path = os.path.join(work, "ik-poses.csv")
    with open(path, "w") as f:
        f.write("x,y,z,a,b,c\n" + "".join(",".join(map(repr, p)) + "\n" for p in poses))
    rows = run([pkm, "hexapod", "ik", "--machine", machine, "--poses", path]).splitlines()[1:]
    return [[float(v) for v in r.split(",")[:6]] for r in rows]


def hexapod_fk(pkm, machine, joints, work):
    """pkm hexapod fk: the pose (x y z a b c) of each set of strut readings."""
    path = os.path.join(work, "fk-joints.csv")
    with open(path, "w") as f:
        f.write("l0,l1,l2,l3,l4,l5\n" + "".join(",".join(map(repr, q)) + "\n" for q in joints))
    rows = run([pkm, "hexapod", "fk", "--machine", machine, "--lengths", path]).splitlines()[1:]
    return [[float(v) for v in r.split(",")[:6]] for r in rows]


def joint_ends(pkm, machine, program, work, exechon=False, inch=False):
    """`pkm gcode run` of `program`: for each motion in order, (line, pose, joints) at its end.
    pose is x y z a b c of the program in the machine's unit (gcode run's CSV gives x y z in mm:
    `inch` converts them); joints in LinuxCNC's order (hexapod q0..q5; Exechon legs q0 q1 q2,
    wrist C, wrist A, degrees: `--orientation axes`, the A/C words are the wrist's)."""
    out = os.path.join(work, os.path.basename(program) + ".joints.csv")
    cmd = [pkm, "gcode", "run", program, "--machine", machine, "--out", out]
    if exechon:
        cmd += ["--orientation", "axes"]
    run(cmd)
    cols = ["q1", "q2", "q3", "wrist_c", "wrist_a"] if exechon else [f"q{i}" for i in range(6)]
    ends = []
    with open(out) as f:
        for row in csv.DictReader(f):
            pose = [float(row[k]) for k in "xyzabc"]
            if inch:
                pose[:3] = [v / 25.4 for v in pose[:3]]
            end = (int(row["line"]), pose, [float(row[k]) for k in cols])
            if ends and ends[-1][0] == end[0]:
                ends[-1] = end
            else:
                ends.append(end)
    return ends


def with_stops(program, ends, out):
    """A copy of `program` with M0 after each line in `ends` (unless an M0 follows already)."""
    stop_after = {line for line, _, _ in ends}
    with open(program) as f:
        lines = f.read().splitlines()
    text = []
    for number, line in enumerate(lines, 1):
        text.append(line)
        following = lines[number].strip().upper() if number < len(lines) else ""
        if number in stop_after and not following.startswith("M0"):
            text.append("M0 (pkm test: stop at the end of the motion above)")
    with open(out, "w") as f:
        f.write("\n".join(text) + "\n")
    os.chmod(out, 0o644)
    return out


# A value read from LinuxCNC right after a move is read again this many times, SETTLE s apart,
# before it counts as wrong: under load the non-realtime servo thread may still be finishing the
# move's last cycles when the MDI command reports done (seen once: a corner 2.9e-5 from its
# command, within 1e-6 when read again).
REREADS = 3
SETTLE = 0.3


def check(failures, what, got, want, tol=TOL):
    """Appends a failure when some |got - want| > tol; prints the comparison. `got` may be a
    function that reads the values: it is then read again (REREADS, SETTLE) while they differ."""
    read = got if callable(got) else None
    got = read() if read else got
    err = max(abs(g - w) for g, w in zip(got, want))
    for _ in range(REREADS if read else 0):
        if err <= tol:
            break
        time.sleep(SETTLE)
        got = read()
        err = max(abs(g - w) for g, w in zip(got, want))
        print(f"{what}: read again after {SETTLE} s")
    print(f"{what}: max difference {err:.2e}")
    if err > tol or len(got) != len(want):
        failures.append(f"{what}: LinuxCNC {got}, pkm {want}: differs by {err:.3g} > {tol}")
    return err


def joint_pins(cnc, joints):
    """The joint positions at full precision (HAL joint.N.pos-fb)."""
    values = cnc.pins([f"joint.{j}.pos-fb" for j in range(joints)])
    return [float(values[f"joint.{j}.pos-fb"]) for j in range(joints)]


def run_program(cnc, path, count, at_stop, timeout=120, feed_override=500):
    """Runs `path` in auto mode; at each of its `count` M0 stops calls at_stop(index), then
    resumes. Raises RuntimeError when the stops do not come or the program does not end."""
    for c in ["set mode auto", f"set feed_override {feed_override}", f"set open {path}",
              "set run"]:
        reply = cnc.ask(c)
        if "NAK" in reply:
            raise RuntimeError(f"'{c}' refused: {reply}")
    deadline = time.time() + timeout
    stops, running, started, last_line = 0, True, False, None
    while time.time() < deadline:
        status = cnc.ask("get program_status").split()[-1]
        line = cnc.ask("get program_line").split()[-1]
        started = started or status != "IDLE"  # `set run` returns before the program starts
        if status == "PAUSED" and line != last_line:  # a new stop (not the last one, resuming)
            if stops >= count:
                raise RuntimeError(f"{path}: more than {count} stops")
            at_stop(stops)
            stops, last_line = stops + 1, line
            cnc.ask("set resume")
        elif status == "IDLE" and started:
            running = False
            break
        time.sleep(0.05)
    if running:
        raise RuntimeError(f"{path} did not end in {timeout} s")
    if stops != count:
        raise RuntimeError(f"{path}: {stops} stops, expected {count}")
    cnc.ask("set mode mdi")


def error_text(cnc):
    """LinuxCNC's last error message (linuxcncrsh `get error`)."""
    return cnc.ask("get error")
