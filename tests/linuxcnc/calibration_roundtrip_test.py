#!/usr/bin/python3
"""The calibration round trip through LinuxCNC (docs/linuxcnc.md, "From `pkm linuxcnc config` to
a running machine", calibrated hexapod).

1. `pkm simulate`: the default hexapod with seed 004's assembly errors (joint centres off by up
   to 33 mm, strut length offsets up to 18 mm) measured by a laser tracker with a 6-DOF probe at
   200 random poses and 50 held-out ones. The tracker is placed at the machine's origin (the
   scenario without its tracker placement), so the readings are in the machine's world frame
   and the calibration fixes that frame too (`--frame world`): all 42 parameters identifiable.
2. `pkm calibrate hexapod` → CAL.json.
3. `pkm linuxcnc config --machine CAL.json` → a configuration with pkmhexkins.
4. LinuxCNC runs examples/gcode/hexapod_contour.ngc, stopped (M0) at the end of each motion.
   There the joints LinuxCNC commands are read (HAL, full precision) and the TRUE machine's
   forward kinematics of them (`pkm hexapod fk` on the simulated machine's geometry, truth.json)
   must be the program's pose to the calibration's held-out residual (its largest TCP error,
   rotations taken at the machine's characteristic length), while the nominal machine's joints
   would miss by more than 100 times that. The joints must also equal `pkm gcode run`'s on the
   calibrated machine to 1e-6 mm.

With --tracker-route, the README's tracker-frame route instead: the scenario as built in (the
tracker 1.7 m from the machine, readings in its own frame), `pkm calibrate hexapod --frame tracker
--registration tracker-pose-registration.csv` (the tracker's readings of six fiducial nests on the
table), then the same LinuxCNC run; the tolerance is the held-out residual and at most 10 um. The
same calibration without --registration must be refused by `pkm linuxcnc config` (exit 2).

Usage: calibration_roundtrip_test.py PKM_BINARY PKMHEXKINS_SO SOURCE_DIR [--tracker-route]
"""
import json
import math
import os
import shutil
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import config_helpers as ch  # noqa: E402
import lcnc_harness as lh  # noqa: E402

SCENARIO = "seed004-hexapod-calibration"
SENSITIVITY = 100  # the nominal machine must miss by this many times the tolerance
TRACKER_ROUTE_LIMIT = 0.010  # mm: the tracker-frame route must end this close to the program


def refuses_unregistered(pkm, sim, work):
    """The tracker-frame calibration without a registration: marked, and refused by config."""
    cal = os.path.join(work, "unregistered", "cal.json")
    os.makedirs(os.path.dirname(cal))
    ch.run([pkm, "calibrate", "hexapod", "--machine", "hexapod-default", "--data",
            os.path.join(sim, "tracker-pose.csv"), "--frame", "tracker", "--out", cal])
    r = subprocess.run([pkm, "linuxcnc", "config", "--machine", cal, "--out",
                        os.path.join(work, "refused")], capture_output=True, text=True)
    if r.returncode != 2 or "--registration" not in r.stderr or os.path.exists(
            os.path.join(work, "refused")):
        sys.exit(f"FAIL: linuxcnc config of an unregistered calibration: exit {r.returncode}\n"
                 f"{r.stderr}")
    print("an unregistered tracker-frame calibration is refused by pkm linuxcnc config")


def simulate_and_calibrate(pkm, source_dir, work, tracker_route=False):
    """(CAL.json, the true machine's JSON, the held-out max TCP error in mm)."""
    ch.run([pkm, "simulate", SCENARIO, "--out", os.path.join(work, "scenario")])
    with open(os.path.join(work, "scenario", "scenario.json")) as f:
        scenario = json.load(f)
    scenario["name"] = "roundtrip"
    scenario["measurements"] = [m for m in scenario["measurements"]
                                if m["name"] in ("tracker-pose", "tracker-holdout")]
    for m in scenario["measurements"]:
        if not tracker_route:
            m.pop("tracker_frame", None)  # the tracker at the machine's origin
    path = os.path.join(work, "roundtrip.json")
    with open(path, "w") as f:
        json.dump(scenario, f)
    sim = os.path.join(work, "sim")
    ch.run([pkm, "simulate", path, "--out", sim])
    cal = os.path.join(work, "cal.json")
    frame = ["--frame", "world"]
    if tracker_route:
        refuses_unregistered(pkm, sim, work)
        frame = ["--frame", "tracker", "--registration",
                 os.path.join(sim, "tracker-pose-registration.csv")]
    ch.run([pkm, "calibrate", "hexapod", "--machine", "hexapod-default", "--data",
            os.path.join(sim, "tracker-pose.csv"), "--holdout",
            os.path.join(sim, "tracker-holdout.csv"), *frame, "--out", cal])
    with open(os.path.join(work, "cal.summary.json")) as f:
        summary = json.load(f)
    residual = summary["holdout"]["after"]["max"]
    with open(os.path.join(source_dir, "data/machines/hexapod-default.json")) as f:
        true = json.load(f)
    with open(os.path.join(sim, "truth.json")) as f:
        geometry = json.load(f)["true_geometry"]
    for i, s in enumerate(true["struts"]):
        s["base"], s["platform"] = geometry["base"][i], geometry["platform"][i]
        s["length_offset"] = geometry["length_offset"][i]
    true["name"] = "true-machine"
    true_path = os.path.join(work, "true.json")
    with open(true_path, "w") as f:
        json.dump(true, f)
    return cal, true_path, residual


def pose_error(got, want, length):
    """Largest position error and rotation error (degrees, as a length at `length`)."""
    position = max(abs(g - w) for g, w in zip(got[:3], want[:3]))
    rotation = max(abs(g - w) for g, w in zip(got[3:], want[3:]))
    return max(position, math.radians(rotation) * length)


def main():
    pkm, hexkins, source_dir = (os.path.abspath(a) for a in sys.argv[1:4])
    tracker_route = "--tracker-route" in sys.argv[4:]
    lh.require(modules=[hexkins], deadline=170)
    work = lh.workdir("pkm-roundtrip-")
    cal, true_machine, residual = simulate_and_calibrate(pkm, source_dir, work, tracker_route)
    if tracker_route:
        residual = min(residual, TRACKER_ROUTE_LIMIT)
    with open(cal) as f:  # the characteristic length: the platform joints' mean distance
        platform = [s["platform"] for s in json.load(f)["struts"]]
    length = sum(math.sqrt(sum(v * v for v in p)) for p in platform) / len(platform)
    print(f"calibration: held-out TCP error max {residual:.4g} mm (the tolerance)")

    ini = ch.config(pkm, cal, work, "cfg")
    program = os.path.join(source_dir, "examples/gcode/hexapod_contour.ngc")
    ends = ch.joint_ends(pkm, cal, program, work)
    stopped = ch.with_stops(program, ends, os.path.join(os.path.dirname(ini), "program.ngc"))
    nominal = ch.hexapod_ik(pkm, "hexapod-default", [pose for _, pose, _ in ends], work)
    nominal_errors = [pose_error(got, pose, length) for got, (_, pose, _) in
                      zip(ch.hexapod_fk(pkm, true_machine, nominal, work), ends)]
    print(f"the nominal machine's joints would miss by {min(nominal_errors):.4g} to "
          f"{max(nominal_errors):.4g} mm")
    commanded = []

    def body(cnc, failures):
        cnc.home()

        def at_stop(k):
            line, _, want = ends[k]
            q = ch.joint_pins(cnc, 6)
            ch.check(failures, f"joints at the end of line {line} (calibrated IK)", q, want)
            commanded.append(q)

        ch.run_program(cnc, stopped, len(ends), at_stop)

    failures, log = lh.session(ini, [hexkins], "calibrated", work, body)
    reached = ch.hexapod_fk(pkm, true_machine, commanded, work) if commanded else []
    worst = 0.0
    for got, (line, pose, _) in zip(reached, ends):
        err = pose_error(got, pose, length)
        worst = max(worst, err)
        if err > residual:
            failures.append(f"line {line}: the true machine reaches {got}, programmed {pose}: "
                            f"{err:.4g} mm > {residual:.4g} mm")
    print(f"the true machine at LinuxCNC's joints: largest error {worst:.4g} mm over "
          f"{len(reached)} end points (tolerance {residual:.4g} mm)")
    if len(reached) != len(ends):
        failures.append(f"{len(reached)} of {len(ends)} end points reached")
    if min(nominal_errors) < SENSITIVITY * residual:
        failures.append("the nominal machine is too close to the true one for this test")
    if "pkmhexkins:" in log:
        failures.append("the kinematics reported an error")
    if failures:
        sys.exit("FAIL:\n" + "\n".join(failures) + "\n--- linuxcnc log ---\n" + log)
    shutil.rmtree(work, ignore_errors=True)
    print("ok: LinuxCNC with the calibrated configuration drives the true machine to the "
          "programmed poses")


if __name__ == "__main__":
    main()
