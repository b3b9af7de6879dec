#!/usr/bin/python3
"""`pkm serve --linuxcnc` following a running LinuxCNC (docs/linuxcnc.md, "The live machine").

LinuxCNC's own hexapod-sim configuration is started headless and homed; `pkm serve --linuxcnc`
is started beside it (port 0). Then, through GET /api/live:
  - after an MDI move, the commanded pose LinuxCNC reports and its joints, at full precision, agree
    with `pkm hexapod ik` of that pose within JOINT_TOL, and pkm's check of the pose is "ok";
  - while a program runs, the state is "running" and its executing line goes through every line
    of the program that moves;
  - E-stop is shown as "estop" within a second;
  - with LinuxCNC stopped, following again reports it not running.
  - the page (web/app/test/live_browser_test.mjs in headless Chromium) follows a program one of
    whose moves takes strut 3 below the limit this test sets half-way (not at its ends, where
    LinuxCNC checks when it queues the move): the drawn machine's joints equal
    LinuxCNC's within 1e-6 in, the machine moves, the executing line is highlighted and the
    violation is flagged ahead of it before LinuxCNC gets there; E-stop turns the header red.
The server sends LinuxCNC no command of its own: it has no MDI or run route (404), and its one
motion routine, the calibration, is refused without the launch's token (401; its routes and the
routine: tests/server/api_live_calibration_test.cpp, live_calibration_test.py).
Exit 77 (skipped) when LinuxCNC, its sample or the harness's user is missing; the page's part is
left out (with a note) without node, Chromium or web/app/node_modules.

Usage: live_view_test.py PKM_BINARY [SCREENSHOT_DIR]
"""
import json
import os
import shutil
import subprocess
import sys
import time
import urllib.error
import urllib.request

import lcnc_harness as lh

POSE = (1.5, -1, 21, 2, -3, 4)
# The link reads LinuxCNC's status in doubles; the joints are genhexkins' inverse kinematics of the
# commanded pose, computed in double precision by both programs.
JOINT_TOL = 1e-6  # inch
PROGRAM = """G20 G90
G0 X0 Y0 Z20
G1 X1 Y0 Z20 F20
G1 X1 Y1 Z20.5
G1 X0 Y1 Z21
G1 X-1 Y0 Z20.5
G1 X0 Y-1 Z20
G0 X0 Y0 Z20
M2
"""


# The page's part: strut 3 may not shorten below MIN_LIMIT (28.5 in here). A straight move of the
# platform from x = -4.459 to -14.459 (y 0, z 20) keeps it at 28.64 in at both ends, which LinuxCNC
# checks when it queues the move, but takes it to 28.20 in half-way, which LinuxCNC finds only when
# the machine gets there; pkm checks the whole path and flags line 7 while lines 2-6 run.
STRUT3_MIN = 28.5
VIOLATING = """G20 G90
G0 X0 Y0 Z20 A0 B0 C0
G1 X-1 Y0 Z20 F30
G1 X-2 Y0.5
G1 X-3 Y0
G1 X-4.459 Y0
G1 X-14.459 Y0
G1 X0 Y0
M2
"""
HERE = os.path.dirname(os.path.abspath(__file__))
BROWSER_TEST = os.path.join(HERE, "..", "..", "web", "app", "test", "live_browser_test.mjs")


def get(port, path="/api/live"):
    req = urllib.request.Request(f"http://127.0.0.1:{port}{path}")
    with urllib.request.urlopen(req, timeout=5) as r:
        return json.loads(r.read())


def wait_for(port, what, predicate, timeout=20):
    deadline = time.time() + timeout
    last = None
    while time.time() < deadline:
        last = get(port)
        if predicate(last):
            return last
        time.sleep(0.05)
    raise RuntimeError(f"{what}: not seen in {timeout} s; last answer {json.dumps(last)[:2000]}")


def start_server(pkm, ini):
    p = subprocess.Popen([pkm, "serve", "--port", "0", "--linuxcnc", ini],
                         stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    line = p.stdout.readline()
    if "serving http://127.0.0.1:" not in line:
        p.kill()
        raise RuntimeError(f"pkm serve printed {line!r}; stderr {p.stderr.read()}")
    # "pkm: serving http://127.0.0.1:PORT/?token=…" (the token: docs/web.md, "Security")
    return p, int(line.split("127.0.0.1:", 1)[1].split("/", 1)[0])


def pkm_ik(pkm, cfg, ini, pose, work):
    path = os.path.join(work, "pose.csv")
    with open(path, "w") as f:
        f.write("x,y,z,a,b,c\n" + ",".join(repr(v) for v in pose) + "\n")
    out = subprocess.run([pkm, "hexapod", "ik", "--machine", os.path.join(cfg, "kinematics.hal"),
                          "--ini", ini, "--poses", path], capture_output=True, text=True,
                         check=True).stdout
    return [float(v) for v in out.strip().splitlines()[1].split(",")[:6]]


def page_follows(cnc, port, work, shots, failures):
    """The page's part (live_browser_test.mjs); False when it cannot run here."""
    node = shutil.which("node")
    if not node or not os.path.exists("/usr/bin/chromium"):
        print("note: no node or chromium here: the page's part is left out")
        return False
    program = os.path.join(work, "violating.ngc")
    with open(program, "w") as f:
        f.write(VIOLATING)
    os.chmod(program, 0o644)
    page = subprocess.Popen([node, BROWSER_TEST, f"http://127.0.0.1:{port}/", shots],
                            stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True)
    try:
        first = page.stdout.readline().strip()
        if first.startswith("SKIP"):
            print(f"note: {first}: the page's part is left out")
            page.wait(timeout=10)
            return False
        if first != "ready":
            raise RuntimeError(f"the page test said {first!r}, expected ready")
        for c in ["set mode auto", f"set open {program}", "set run"]:
            if "NAK" in cnc.ask(c):
                raise RuntimeError(f"'{c}' refused")
        page.stdin.write("running\n")
        page.stdin.flush()
        said = page.stdout.readline().strip()
        cnc.ask("set abort")
        cnc.ask("set estop on")
        page.stdin.write("estop\n")
        page.stdin.flush()
        result = page.stdout.read().strip()
        code = page.wait(timeout=30)
        print(f"page test: {said}, {result}, exit {code}")
        if said != "seen" or code != 0:
            failures.append(f"the page did not follow LinuxCNC: {said}, {result}, exit {code}")
    finally:
        if page.poll() is None:
            page.kill()
    return True


def body(pkm, cfg, ini, work, port, shots):
    def check(cnc, failures):
        cnc.home()
        cnc.mdi("G0 X{} Y{} Z{} A{} B{} C{}".format(*POSE))
        j = wait_for(port, "the MDI pose", lambda j: j.get("connected") and all(
            abs(a - b) < 1e-9 for a, b in zip(j["status"]["pose_commanded"], POSE)))
        want = pkm_ik(pkm, cfg, ini, j["status"]["pose_commanded"], work)
        got = j["status"]["joints_commanded"]
        err = max(abs(a - b) for a, b in zip(got, want))
        print(f"MDI pose {POSE}: LinuxCNC joints {got}; pkm ik {want}; max difference {err:.2e}")
        if err > JOINT_TOL:
            failures.append(f"joints differ from pkm hexapod ik by {err:.3g} in > {JOINT_TOL}")
        if j["check"]["status"] != "ok" or j["state"] != "idle":
            failures.append(f"check {j['check']['status']}, state {j['state']}")
        if not (j["joint_disagreement"] <= JOINT_TOL):
            failures.append(f"joint_disagreement {j['joint_disagreement']}")
        if j["machine"]["units"] != "inch" or not j["machine"]["hal"].endswith("kinematics.hal"):
            failures.append(f"machine {j['machine']}")

        program = os.path.join(work, "square.ngc")
        with open(program, "w") as f:
            f.write(PROGRAM)
        os.chmod(program, 0o644)
        for c in ["set mode auto", f"set open {program}", "set run"]:
            if "NAK" in cnc.ask(c):
                raise RuntimeError(f"'{c}' refused")
        lines, running, t0 = set(), False, time.time()
        while time.time() - t0 < 60:
            s = get(port)
            if s["state"] == "running":
                running = True
                lines.add(s["status"]["executing_line"])
            elif running and s["state"] == "idle":
                break
            time.sleep(0.02)
        print(f"while the program ran the page saw lines {sorted(lines)}")
        if not running or not {2, 3, 4, 5, 6, 7} <= lines:
            failures.append(f"program run not followed: running {running}, lines {sorted(lines)}")
        cnc.ask("set mode mdi")

        if not page_follows(cnc, port, work, shots, failures):
            cnc.ask("set estop on")
        wait_for(port, "E-stop", lambda j: j["state"] == "estop", timeout=5)
        for path, code in [("/api/live/run", 404), ("/api/mdi", 404),
                           ("/api/live/calibration", 401)]:
            try:
                urllib.request.urlopen(urllib.request.Request(
                    f"http://127.0.0.1:{port}{path}", data=b"{}", method="POST"), timeout=5)
                failures.append(f"POST {path} was answered: the server must not command")
            except urllib.error.HTTPError as e:
                if e.code != code:
                    failures.append(f"POST {path}: {e.code}, expected {code}")
        # The server lets go of LinuxCNC's shared memory before LinuxCNC stops (the harness
        # checks that nothing is left behind); following again afterwards must say it is gone.
        urllib.request.urlopen(urllib.request.Request(
            f"http://127.0.0.1:{port}/api/live/disconnect", data=b"{}", method="POST"), timeout=5)
    return check


def main():
    pkm = os.path.abspath(sys.argv[1])
    lh.require()
    work, cfg, ini = lh.hexapod_sample("pkm-live-")
    lh.set_ini(ini, "JOINT_3", "MIN_LIMIT", str(STRUT3_MIN))
    shots = sys.argv[2] if len(sys.argv) > 2 else os.path.join(work, "screenshots")
    server, port = start_server(pkm, ini)
    try:
        first = get(port)
        if first["following"] is not True:
            sys.exit(f"FAIL: --linuxcnc did not start following: {first}")
        failures, log = lh.session(ini, [], "live", work, body(pkm, cfg, ini, work, port, shots))
        if not failures:
            urllib.request.urlopen(urllib.request.Request(
                f"http://127.0.0.1:{port}/api/live/connect", data=b"{}", method="POST"),
                timeout=5)
            gone = wait_for(port, "the disconnection",
                            lambda j: not j["connected"] and "not running" in j["reason"],
                            timeout=10)
            print(f"after LinuxCNC stopped: state {gone['state']}, reason {gone['reason']!r}")
            if gone["state"] != "disconnected" or not gone["reason"]:
                failures.append(f"after LinuxCNC stopped: {gone}")
    finally:
        server.terminate()
        server.wait(timeout=10)
    if failures:
        sys.exit("FAIL:\n" + "\n".join(failures) + "\n--- linuxcnc log ---\n" + log)
    print("ok: pkm serve --linuxcnc follows LinuxCNC's pose, joints, program line and E-stop")


if __name__ == "__main__":
    main()
