#!/usr/bin/python3
"""Bad kinematics parameters stop LinuxCNC at load, with the reason in its log (docs/linuxcnc.md).

pkm's kinematics modules read their parameter file at `loadrt` (`[KINS] KINEMATICS = pkmhexkins
params=FILE`, `pkmexechonkins params=FILE`) and refuse it there: a missing parameter, an unknown
name, or a geometry that does not assemble fails the loadrt, so LinuxCNC does not start (instead
of failing at the first move). For each module:
  - a good file: LinuxCNC starts and homes; pkmhexkins (a copy of
    data/linuxcnc/hexapod-linuxcnc-sim, the geometry moved away from the module's defaults and
    written by `pkm hexapod linuxcnc-params`): the world position after homing is the file's home, the pins
    hold the file's values, and at two MDI poses the joints are pkm's IK of the file's machine;
    pkmexechonkins (a copy of data/linuxcnc/exechon-mxt700s): the world position after homing is
    [TRAJ] HOME;
  - a missing parameter, an unknown name, a geometry that does not assemble (pkmhexkins: one strut
    twice, platform joints on one line; pkmexechonkins: dB = 0, singular at home (h = 0)):
    LinuxCNC does not start, its log has `<module>: FILE: <reason>` and no misleading
    "Operation not permitted" after it, and nothing is left behind.
LinuxCNC is run by lcnc_harness.py (exit 77 when it cannot run here).

Usage: load_failures_test.py PKM_BINARY HEXKINS_SO EXECHON_SO SOURCE_DIR
"""
import json
import os
import re
import shutil
import subprocess
import sys

import lcnc_harness as lh

TOL = 1e-6  # inch (linuxcncrsh prints 6 decimals)


def run(cmd):
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit(f"FAIL: {' '.join(cmd)} exited {r.returncode}\n{r.stdout}\n{r.stderr}")
    return r.stdout


def replace_lines(text, values):
    """The parameter file `text` with the lines of the names in `values` (name -> numbers)
    replaced."""
    out = []
    for line in text.splitlines(keepends=True):
        name = line.split(" ", 1)[0]
        out.append(f"{name} {' '.join(map(repr, values[name]))}\n" if name in values else line)
    return "".join(out)


def numbers(text, name):
    """The numbers of the line `name ...` of a parameter file."""
    line = next(l for l in text.splitlines() if l.split(" ", 1)[0] == name)
    return [float(v) for v in line.split()[1:]]


def make_config(sample, work, name, kinematics, text):
    """A copy of the sample, its KINEMATICS line set and the parameter file written."""
    cfg = lh.copy_config(sample, work, name)
    params = os.path.join(cfg, "kinematics.params")
    with open(params, "w") as f:
        f.write(text)
    os.chmod(params, 0o644)
    hal = os.path.join(cfg, "kinematics.hal")
    with open(hal) as f:
        kept = [l for l in f if not l.startswith("setp pkmhexkins.")]
    with open(hal, "w") as f:
        f.writelines(kept if kinematics == "pkmhexkins" else
                     [l for l in kept if "pkmhexkins" not in l])
    ini = os.path.join(cfg, "hexapod-linuxcnc-sim.ini")
    lh.set_ini(ini, "KINS", "KINEMATICS", f"{kinematics} params={params}")
    lh.make_headless(ini)
    return ini, params


def refused(failures, what, ini, module, work, name, want):
    """LinuxCNC on `ini` must not start; its log must have the line `want`."""
    r = lh.start_fails(ini, [module], name, work)
    print(f"{what}: started {r.started}, linuxcnc exit {r.returncode}, {r.seconds:.1f} s, "
          f"message {'found' if want in r.log else 'MISSING'}: '{want}'")
    if r.started:
        failures.append(f"{what}: LinuxCNC started")
    if want not in r.log:
        failures.append(f"{what}: the log does not say '{want}':\n{r.log}")
    # The module's reason is the last word: no misleading EPERM from rtapi_app after it.
    if "Operation not permitted" in r.log:
        failures.append(f"{what}: the log says 'Operation not permitted':\n{r.log}")
    if r.leftovers:
        failures.append(f"{what}: left behind: {r.leftovers}")


def hexapod_cases(pkm, module, sample, work, failures):
    machine = json.loads(run([pkm, "hexapod", "describe", "--json", "--machine",
                              "hexapod-linuxcnc-sim"]))
    machine["struts"][2]["base"][0] += 0.04  # not the module's defaults: the file must count
    machine["struts"][5]["length_offset"] = 0.03
    mpath = os.path.join(work, "machine.json")
    with open(mpath, "w") as f:
        json.dump(machine, f)
    good = run([pkm, "hexapod", "linuxcnc-params", "--machine", mpath])
    ini, _ = make_config(sample, work, "hex-good", "pkmhexkins", good)
    home = [machine["home"][k] for k in "xyzabc"]
    csv = os.path.join(work, "poses.csv")
    poses = [home, [0.5, -1.0, 21.0, 2.0, -3.0, 4.0], [-1.5, 0.5, 19.0, -4.0, 1.0, -2.0]]
    with open(csv, "w") as f:
        f.write("x,y,z,a,b,c\n" + "".join(",".join(map(repr, p)) + "\n" for p in poses))
    rows = run([pkm, "hexapod", "ik", "--machine", mpath, "--poses", csv]).strip().splitlines()
    q, *moves = [[float(v) for v in r.split(",")[:6]] for r in rows[1:]]
    for i, v in enumerate(q):  # joint homes: the IK at home of this machine
        for key in ("HOME", "HOME_OFFSET"):
            lh.set_ini(ini, f"JOINT_{i}", key, repr(v))

    def body(cnc, fails):
        cnc.home()
        world = cnc.world()
        err = max(abs(a - b) for a, b in zip(world, home))
        print(f"pkmhexkins, good file: world after homing {world}, home {home}: {err:.1e}")
        if err > TOL:
            fails.append(f"world after homing {world} is not the file's home {home}")
        pins = cnc.pins(["pkmhexkins.base.2.x", "pkmhexkins.length-offset.5",
                         "pkmhexkins.geometry-ok"])
        if (pins["pkmhexkins.base.2.x"] != machine["struts"][2]["base"][0]
                or pins["pkmhexkins.length-offset.5"] != 0.03
                or pins["pkmhexkins.geometry-ok"] is not True):
            fails.append(f"the pins do not hold the file's values: {pins}")
        for pose, want in zip(poses[1:], moves):
            cnc.mdi("G0 X{} Y{} Z{} A{} B{} C{}".format(*pose))
            got = cnc.joints()
            err = max(abs(a - b) for a, b in zip(got, want))
            print(f"pkmhexkins, good file: joints at {pose} {got}, pkm IK {want}: {err:.1e}")
            if err > TOL:
                fails.append(f"joints at {pose} differ from pkm's IK by {err}")

    fails, log = lh.session(ini, [module], "hex-good", work, body)
    failures += [f"pkmhexkins, good file: {f}" for f in fails]
    if "pkmhexkins:" in log and "parameters from" not in log:
        failures.append(f"pkmhexkins, good file: the module complained:\n{log}")

    lines = good.splitlines(keepends=True)
    missing = "".join(l for l in lines if not l.startswith("tool "))
    unknown = good.replace("spindle-offset", "spindel-offset")
    number = 1 + next(i for i, l in enumerate(lines) if l.startswith("spindle-offset"))
    # Geometries pkm itself would not load, made from its file: strut 4 a second copy of strut 3;
    # the platform joints on one line (turns about it are free).
    twice = replace_lines(good, {"base.4": numbers(good, "base.3"),
                                 "platform.4": numbers(good, "platform.3")})
    line = replace_lines(good, {f"platform.{i}": [2.0 * i - 5.0, 0.0, 0.0] for i in range(6)})
    cases = [("missing parameter", missing, "missing tool"),
             ("unknown name", unknown, f"line {number}: unknown parameter 'spindel-offset'"),
             ("one strut twice", twice, "struts 3 and 4 join the same joints"),
             ("collinear platform joints", line, "the geometry is singular at the home pose")]
    for what, text, reason in cases:
        name = "hex-" + what.replace(" ", "-")
        ini, params = make_config(sample, work, name, "pkmhexkins", text)
        refused(failures, f"pkmhexkins, {what}", ini, module, work, name,
                f"pkmhexkins: {params}: {reason}")


def exechon_cases(module, sample, work, failures):
    """The Exechon sample (its KINEMATICS line: pkmexechonkins params=mxt700s-like.params)."""
    with open(os.path.join(sample, "mxt700s-like.params")) as f:
        good = f.read()
    cfg = lh.copy_config(sample, work, "exechon-good")
    ini = os.path.join(cfg, "mxt700s-like.ini")
    lh.make_headless(ini)
    with open(ini) as f:
        home = [float(v) for v in re.search(r"(?m)^HOME = (.*)$", f.read()).group(1).split()]

    def body(cnc, fails):
        cnc.home()
        world = cnc.world()
        err = max(abs(a - b) for a, b in zip(world, home))
        print(f"pkmexechonkins, good file: world after homing {world}, home {home}: {err:.1e}")
        if err > 1e-5:  # mm
            fails.append(f"world after homing {world} is not [TRAJ] HOME {home}")
        if cnc.pin("pkmexechonkins.fwd-kins-fail") is not False:
            fails.append("forward kinematics failed after homing")

    fails, log = lh.session(ini, [module], "exechon-good", work, body)
    failures += [f"pkmexechonkins, good file: {f}" for f in fails]

    lines = good.splitlines(keepends=True)
    number = 1 + next(i for i, l in enumerate(lines) if l.startswith("hz "))
    cases = [("missing parameter", "".join(l for l in lines if not l.startswith("tool_length")),
              "missing tool_length"),
             ("unknown name", good.replace("\nhz ", "\nhzz "),
              f"line {number}: unknown parameter 'hzz'"),
             ("dB = 0", re.sub(r"(?m)^dB .*$", "dB 0", good), "tripod: dB must be != 0"),
             ("home h = 0", re.sub(r"(?m)^home_h .*$", "home_h 0", good),
              "the tripod is singular at home")]
    for what, text, reason in cases:
        name = "exechon-" + re.sub(r"[^a-zA-Z0-9]+", "-", what)
        cfg = lh.copy_config(sample, work, name)
        with open(os.path.join(cfg, "mxt700s-like.params"), "w") as f:
            f.write(text)
        ini = os.path.join(cfg, "mxt700s-like.ini")
        lh.make_headless(ini)
        refused(failures, f"pkmexechonkins, {what}", ini, module, work, name,
                f"pkmexechonkins: mxt700s-like.params: {reason}")


def main():
    pkm, hexkins, exechon, source_dir = (os.path.abspath(a) for a in sys.argv[1:5])
    lh.require([hexkins, exechon])
    work = lh.workdir("pkm-load-failures-")
    failures = []
    hexapod_cases(pkm, hexkins, os.path.join(source_dir, "data/linuxcnc/hexapod-linuxcnc-sim"), work,
                  failures)
    exechon_cases(exechon, os.path.join(source_dir, "data/linuxcnc/exechon-mxt700s"), work,
                  failures)
    if failures:
        sys.exit("FAIL:\n" + "\n".join(failures))
    shutil.rmtree(work, ignore_errors=True)
    print("ok: bad kinematics parameters stop LinuxCNC at load with the reason in its log")


if __name__ == "__main__":
    main()
