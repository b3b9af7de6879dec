#!/usr/bin/python3
"""`pkm linuxcnc install` proven in a running LinuxCNC (docs/linuxcnc.md).

A copy of LinuxCNC's own hexapod-sim configuration is patched with a calibration whose joints
differ from the sample's, LinuxCNC is started on it headless (linuxcncrsh, POSIX non-realtime),
homed, and sent to three poses by MDI; the joint positions it reports must be pkm's inverse
kinematics of the *calibrated* machine (and not of the nominal one). Exit 77 (skipped) when
LinuxCNC is not installed or, as root, the unprivileged user scripts/setup.sh creates is missing.

Usage: install_runs_test.py PKM_BINARY
"""
import json
import os
import pwd
import re
import shutil
import socket
import subprocess
import sys
import tempfile
import time

SAMPLE = "/usr/share/doc/linuxcnc/examples/sample-configs/sim/axis/vismach/hexapod-sim"
USER = "pkm-linuxcnc"  # the unprivileged user rtapi_app needs when the tests run as root
PORT = 5007  # linuxcncrsh's default port: one LinuxCNC at a time (CTest RESOURCE_LOCK linuxcnc)
POSES = [(1, 1, 21, 0, 0, 0), (-2, 1.5, 19, 3, -2, 5), (0.5, -2, 22.5, -4, 1, -3)]
# Joint positions agree to what linuxcncrsh prints (6 decimals) plus genhexkins' own forward
# kinematics tolerance on the commanded pose (its default convergence criterion 1e-9 in).
JOINT_TOL = 2e-6  # inch
# The calibration moves joints by 0.05 in: a nominal configuration would miss by far more.
CHANGE_MIN = 1e-3  # inch


def skip(why):
    print(f"SKIP: {why}")
    sys.exit(77)


def run(cmd, **kw):
    r = subprocess.run(cmd, capture_output=True, text=True, **kw)
    if r.returncode != 0:
        sys.exit(f"FAIL: {' '.join(cmd)} exited {r.returncode}\n{r.stdout}\n{r.stderr}")
    return r.stdout


def make_headless(ini_path):
    """The sample as a headless test configuration: linuxcncrsh, no GUI panels, a tool table."""
    with open(ini_path) as f:
        s = f.read()
    s = re.sub(r"(?m)^DISPLAY\s*=.*$", "DISPLAY = linuxcncrsh", s)
    s = re.sub(r"(?m)^(PYVCP|INTRO_GRAPHIC|INTRO_TIME|POSTGUI_HALFILE)\s*=.*\n", "", s)
    s = re.sub(r"(?m)^HALCMD\s*=\s*loadusr -W hexagui\s*\n", "", s)
    s = s.replace("LIB:basic_sim.tcl\n", "LIB:basic_sim.tcl -no_use_hal_manualtoolchange\n")
    with open(ini_path, "w") as f:
        f.write(s)
    with open(os.path.join(os.path.dirname(ini_path), "hexapod.tbl"), "w") as f:
        f.write("T1 P1 D0.125 Z+0.5 ;test tool\n")


class Rsh:
    """A linuxcncrsh session (the EMC telnet protocol)."""

    def __init__(self):
        deadline = time.time() + 30
        while True:
            try:
                self.sock = socket.create_connection(("127.0.0.1", PORT), timeout=5)
                break
            except OSError:
                if time.time() > deadline:
                    raise
                time.sleep(0.2)
        self.buf = b""
        for c in ["hello EMC pkm 1", "set enable EMCTOO", "set echo off", "set verbose on"]:
            self.ask(c)

    def ask(self, command):
        self.sock.sendall(command.encode() + b"\r\n")
        while b"\n" not in self.buf:
            data = self.sock.recv(4096)
            if not data:
                raise RuntimeError(f"connection closed after '{command}'")
            self.buf += data
        line, self.buf = self.buf.split(b"\n", 1)
        return line.decode().strip()

    def wait_idle(self, timeout=30):
        deadline = time.time() + timeout
        self.ask("set wait done")
        while time.time() < deadline:
            if self.ask("get program_status").endswith("IDLE"):
                return
            time.sleep(0.1)
        raise RuntimeError("motion did not finish")


def main():
    pkm = os.path.abspath(sys.argv[1])
    if shutil.which("linuxcnc") is None or not os.path.isdir(SAMPLE):
        skip("LinuxCNC is not installed (scripts/setup.sh installs linuxcnc-uspace)")
    as_user = []
    if os.geteuid() == 0:
        try:
            pwd.getpwnam(USER)
        except KeyError:
            skip(f"running as root and user {USER} does not exist (scripts/setup.sh creates it)")
        as_user = ["runuser", "-u", USER, "--"]
    work = tempfile.mkdtemp(prefix="pkm-linuxcnc-")
    os.chmod(work, 0o755)
    cfg = os.path.join(work, "cfg")
    shutil.copytree(SAMPLE, cfg)
    ini = os.path.join(cfg, "hexapod.ini")
    make_headless(ini)

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

    for path in (work, cfg):
        for root, dirs, files in os.walk(path):
            for name in dirs + files:
                os.chmod(os.path.join(root, name), 0o777)
    env = dict(os.environ, RUNTESTS="1")  # keeps LinuxCNC's log on its standard output
    log = open(os.path.join(work, "linuxcnc.log"), "w")
    proc = subprocess.Popen(as_user + ["env", "RUNTESTS=1", "linuxcnc", ini], cwd=cfg,
                            stdout=log, stderr=subprocess.STDOUT, env=env,
                            start_new_session=True)
    failures = []
    try:
        rsh = Rsh()
        for c in ["set estop off", "set machine on", "set mode manual", "set home -1"]:
            rsh.ask(c)
        time.sleep(0.5)
        rsh.ask("set mode mdi")
        for pose, want, nom in zip(POSES, expected, nominal):
            rsh.ask("set mdi G0 X{} Y{} Z{} A{} B{} C{}".format(*pose))
            rsh.wait_idle()
            got = [float(v) for v in rsh.ask("get joint_pos").split()[1:7]]
            err = max(abs(g - w) for g, w in zip(got, want))
            off = max(abs(g - n) for g, n in zip(got, nom))
            print(f"pose {pose}: LinuxCNC {got}; pkm calibrated IK {want}; "
                  f"max difference {err:.2e} in (nominal IK differs by {off:.2e} in)")
            if err > JOINT_TOL:
                failures.append(f"pose {pose}: joints differ from pkm's by {err} in")
            if off < CHANGE_MIN:
                failures.append(f"pose {pose}: the calibration did not change the joints")
        rsh.sock.sendall(b"shutdown\r\n")  # LinuxCNC closes the connection as it stops
    finally:
        try:
            proc.wait(timeout=30)
        except subprocess.TimeoutExpired:
            os.killpg(proc.pid, 9)
        log.close()
    if failures:
        with open(os.path.join(work, "linuxcnc.log")) as f:
            sys.exit("FAIL:\n" + "\n".join(failures) + "\n--- linuxcnc log ---\n" + f.read())
    shutil.rmtree(work, ignore_errors=True)
    print("ok: the patched configuration runs in LinuxCNC with pkm's calibrated joints")


if __name__ == "__main__":
    main()
