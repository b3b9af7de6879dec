#!/usr/bin/python3
"""`pkm calibrate hexapod --live` end to end in a running LinuxCNC (docs/linuxcnc.md, "Automated
calibration by constrained motion"), without a person.

`pkm simulate seed004-hexapod-calibration` gives the truth of Lee et al.'s machine ("Development of
a Parallel-Typed CNC Machine": joint centres off by up to 33 mm, strut offsets up to 18 mm, struts
with 1 um encoders, 2 um repeatability and 5 um backlash). `pkm linuxcnc config --machine
hexapod-default --simulate-truth` writes the NOMINAL machine's configuration with that true machine
in LinuxCNC's loop (pkm-truth: its three dial gauges and a laser along x on HAL pins). The axis
limits are widened to what the paper's 540 mm x move needs (pkm checks every planned pose itself).
LinuxCNC is started headless and homed; then, as LinuxCNC's user, `pkm calibrate hexapod --live
--install` plans the stations, drives LinuxCNC through them by MDI with the constrained motion at
each, calibrates, installs the result into the configuration (pkmhexkins' parameter file, with a
backup), applies it to the running LinuxCNC and re-measures the x move on the simulated laser.

Before that, the page (web/app/test/calibration_browser_test.mjs in headless Chromium, on `pkm
serve --linuxcnc` run as LinuxCNC's user): a routine of PAGE_STATIONS stations started with the
mouse, confirmed, its installation declined (the parameter file stays as it was); one stopped with
Stop; one whose page is closed mid-way (the server stops LinuxCNC within 2 s). Left out, with a
note, without node, Chromium or web/app/node_modules.

Checked: the laser's error over 540 mm before (about 12 mm, the paper's figure) and after
(the paper: below 0.5 mm; here 0.42 ... 0.53 mm, the test allows 0.6 mm, see AFTER); the held-out stations' gauge residuals fall; the parameter file was
replaced and backed up; every command sent is in commands.log; the routine's wall time is printed.

Usage: live_calibration_test.py PKM_BINARY PKMHEXKINS_SO SOURCE_DIR
"""
import os
import re
import shutil
import signal
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import config_helpers as ch  # noqa: E402
import lcnc_harness as lh  # noqa: E402

BEFORE = (8.0, 16.0)  # mm: "about 12 mm" over 540 mm before calibration (Lee et al.)
# mm after calibration. Lee et al. report below 0.5 mm; this routine gives 0.42 ... 0.53 mm here
# (14 runs): gauges on a table barely see the x scale (a move parallel to the table reads nothing
# when only its length is wrong), so what is left of it varies with micrometres of data. 0.6 mm
# keeps the test from failing by chance; docs/linuxcnc.md gives the figures.
AFTER = 0.6
PAGE_STATIONS = ("14", "2")  # fit and held-out stations of the page's routines (a short run)
HERE = os.path.dirname(os.path.abspath(__file__))
BROWSER_TEST = os.path.join(HERE, "..", "..", "web", "app", "test", "calibration_browser_test.mjs")
LIMITS = {"AXIS_X": (-280, 280), "AXIS_Y": (-210, 210), "AXIS_C": (-21, 21)}


def page_calibrates(pkm, ini, home, work, failures):
    """The page's part: `pkm serve --linuxcnc` as LinuxCNC's user, the browser test on it."""
    if not os.path.exists(os.path.join(os.path.dirname(pkm), "pkm-serve")):
        print("note: pkm-serve was not built (PKM_BUILD_SERVER off): the page's part is left out")
        return
    node = shutil.which("node")
    if not node or not os.path.exists("/usr/bin/chromium"):
        print("note: no node or chromium here: the page's part is left out")
        return
    server = subprocess.Popen(lh.user_prefix() + ["env", f"HOME={home}", pkm, "serve", "--port",
                                                  "0", "--linuxcnc", ini],
                              stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                              start_new_session=True)
    try:
        line = server.stdout.readline()
        url = re.search(r"serving (http://127\.0\.0\.1:\d+/\?token=[0-9a-f]+)", line)
        if not url:
            failures.append(f"pkm serve printed {line!r}")
            return
        shots = os.environ.get("PKM_SCREENSHOTS") or os.path.join(work, "screenshots")
        started = time.monotonic()
        r = subprocess.run([node, BROWSER_TEST, url.group(1), shots, *PAGE_STATIONS],
                           capture_output=True, text=True, timeout=600)
        print(r.stderr.strip())
        print(f"page: {r.stdout.strip()} in {time.monotonic() - started:.1f} s; screenshots {shots}")
        if r.stdout.startswith("SKIP"):
            print(f"note: {r.stdout.strip()}: the page's part is left out")
        elif r.returncode != 0:
            failures.append(f"the page's calibration failed: {r.stdout.strip()}\n{r.stderr}")
    finally:
        os.killpg(server.pid, signal.SIGTERM)
        try:
            server.wait(timeout=15)
        except subprocess.TimeoutExpired:
            os.killpg(server.pid, signal.SIGKILL)
            server.wait()


def main():
    pkm, hexkins, source_dir = (os.path.abspath(a) for a in sys.argv[1:4])
    lh.require(modules=[hexkins], deadline=400)
    if not os.path.exists(os.path.join(os.path.dirname(pkm), "pkm-truth")):
        lh.skip("pkm-truth was not built (no LinuxCNC HAL headers)")
    work = lh.workdir("pkm-live-cal-")
    sim = os.path.join(work, "sim")
    ch.run([pkm, "simulate", "seed004-hexapod-calibration", "--out", sim])
    ini = ch.config(pkm, "hexapod-default", work, "cfg",
                    ["--simulate-truth", os.path.join(sim, "truth.json")])
    for section, (lo, hi) in LIMITS.items():
        lh.set_ini(ini, section, "MIN_LIMIT", str(lo))
        lh.set_ini(ini, section, "MAX_LIMIT", str(hi))
    # A simulated machine may travel faster than the written limits (the routine's moves are rapids).
    for section in ["AXIS_X", "AXIS_Y", "AXIS_Z"] + [f"JOINT_{i}" for i in range(6)]:
        lh.set_ini(ini, section, "MAX_VELOCITY", "600")
        lh.set_ini(ini, section, "MAX_ACCELERATION", "6000")
    lh.set_ini(ini, "TRAJ", "MAX_LINEAR_VELOCITY", "600")
    lh.set_ini(ini, "TRAJ", "MAX_LINEAR_ACCELERATION", "6000")
    cfg = os.path.dirname(ini)
    params = os.path.join(cfg, "pkm-hx1200.params")
    with open(params) as f:
        params_before = f.read()
    out = os.path.join(work, "out")
    os.makedirs(out)
    lh._open_up(out)
    lh._open_up(cfg)
    run = {}

    def body(cnc, failures):
        cnc.home()
        page_calibrates(pkm, ini, cnc.home_dir, work, failures)
        with open(params) as f:
            if f.read() != params_before:
                failures.append("the page's routine changed the parameter file (install declined)")
        # As LinuxCNC's user, with its HOME: LinuxCNC shares its tool table in $HOME/.tool.mmap.
        cmd = lh.user_prefix() + ["env", f"HOME={cnc.home_dir}", 
            pkm, "calibrate", "hexapod", "--live", "--ini", ini, "--out", out,
            "--gauges", "pkmtruth.gauge-0,pkmtruth.gauge-1,pkmtruth.gauge-2",
            "--laser", "pkmtruth.laser-x", "--install", "--settle", "0.02", "--tolerance", "0.01"]
        started = time.monotonic()
        r = subprocess.run(cmd, capture_output=True, text=True, timeout=900)
        run.update(rc=r.returncode, out=r.stdout, err=r.stderr, seconds=time.monotonic() - started)
        if r.returncode != 0:
            failures.append(f"pkm calibrate hexapod --live exited {r.returncode}:\n{r.stdout}\n{r.stderr}")

    failures, log = lh.session(ini, [hexkins], "live-calibration", work, body)
    if failures:
        sys.exit("FAIL:\n" + "\n".join(failures) + "\n--- linuxcnc log ---\n" + log)
    text = run["out"]
    print(text)
    errors = [float(v) for v in re.findall(r"error ([-+][0-9.]+) mm (?:before|after) calibration", text)]
    if len(errors) != 2:
        sys.exit("FAIL: the report does not give the x move's error before and after")
    before, after = errors
    if not BEFORE[0] <= abs(before) <= BEFORE[1]:
        failures.append(f"error before calibration {before} mm, expected about 12 mm")
    if not abs(after) < AFTER:
        failures.append(f"error after calibration {after} mm, expected below {AFTER} mm")
    rms = re.search(r"residuals RMS ([0-9.]+) mm with the configuration's machine, ([0-9.]+) mm", text)
    if not rms or not float(rms.group(2)) < float(rms.group(1)) / 10:
        failures.append("the held-out gauge residuals did not fall tenfold")
    with open(params) as f:
        if f.read() == params_before:
            failures.append("the parameter file was not replaced")
    with open(params + ".pkm-backup") as f:
        if f.read() != params_before:
            failures.append("the backup is not the parameter file as it was")
    with open(os.path.join(out, "commands.log")) as f:
        sent = f.read().splitlines()
    mdi = [line for line in sent if '"mdi"' in line]
    if len(mdi) < 50 or not all("G53 G0" in line for line in mdi):
        failures.append(f"commands.log has {len(mdi)} MDI lines")
    print(f"x move over 540 mm: {before:+.4f} mm -> {after:+.4f} mm; routine {run['seconds']:.1f} s, "
          f"{len(sent)} commands")
    if failures:
        sys.exit("FAIL:\n" + "\n".join(failures) + "\n--- linuxcnc log ---\n" + log)
    shutil.rmtree(work, ignore_errors=True)
    print("ok: pkm calibrate hexapod --live calibrated, installed and re-measured LinuxCNC")


if __name__ == "__main__":
    main()
