"""A headless LinuxCNC for pkm's in-the-loop tests (tests/linuxcnc/*_test.py, docs/linuxcnc.md).

One LinuxCNC runs per machine (its lock file /tmp/linuxcnc.lock, linuxcncrsh's port 5007, HAL's
shared memory), so every test that starts one goes through this module. It starts LinuxCNC on a
configuration with this build's kinematics modules, talks to it, and always cleans up.

API (everything a test needs; the rest of the module is private):

    import lcnc_harness as lh

    lh.require(modules=[so, ...], deadline=150)
        Exit 77 (CTest's SKIP_RETURN_CODE) unless LinuxCNC is installed, every module file was
        built, and the modules can be loaded: as root, through a private mount namespace
        (`unshare --mount`) with LinuxCNC run as the unprivileged user USER (scripts/setup.sh
        creates it: rtapi_app refuses root); not as root, only if the installed modules are these
        files. Also arms the test's deadline: after `deadline` seconds, or on SIGTERM/SIGINT, an
        exception unwinds the test, so that every cleanup still runs (CTest's own TIMEOUT kills
        without warning: keep `deadline` below it).

    work = lh.workdir("pkm-foo-")              a temporary folder the LinuxCNC user can read
    cfg = lh.copy_config(src, work, "cfg")     a copy of a configuration folder, writable by USER
    work, cfg, ini = lh.hexapod_sample("pkm-foo-")
                                               LinuxCNC's hexapod-sim (genhexkins), copied and
                                               headless, with a tool table (skips without it)
    lh.make_headless(ini)                      DISPLAY = linuxcncrsh, GUI panels and the manual
                                               tool-change dialog removed
    lh.set_ini(ini, section, key, value)       sets (or adds) one INI entry in place

    with lh.LinuxCNC(ini, modules=[so, ...], name="calibrated", work=work) as cnc:
        cnc.home()                             estop off, machine on, home all, wait until the
                                               INI's [KINS] JOINTS joints are homed
        cnc.mdi("G0 X1 Y1 Z21")                one MDI line, waits until the motion is done
        cnc.joints(), cnc.world()              joint positions / world position (linuxcncrsh's
                                               `get joint_pos` / `get abs_act_pos`: 6 decimals)
        cnc.pins(["joint.0.motor-pos-cmd", "pkmhexkins.geometry-ok"])
                                               HAL pins and parameters read with full precision
                                               (float, bool or int), through python3's `hal`
        cnc.pin(name)                          one of them
        cnc.setp(name, value)                  sets a HAL pin or parameter (python3's `hal`)
        cnc.ask("get program_status")          one raw linuxcncrsh command; its reply line
    cnc.log                                    LinuxCNC's whole output (after the `with`)
    cnc.leftovers                              what cleanup could not remove (should be [])
    cnc.seconds                                how long LinuxCNC ran

    failures, log = lh.session(ini, modules, name, work, body)
        Runs body(cnc, failures) in a `with LinuxCNC(...)`; an error raised by LinuxCNC or the
        body (RuntimeError, OSError) and anything left behind become entries of `failures`.
        Prints how long LinuxCNC ran. Returns the failures and LinuxCNC's log.

    r = lh.halrun(["loadrt pkmexechonkins params=FILE", "show pin"], modules=[...],
                  name="hal", work=work)
        Runs halcmd lines with `halrun -f` (no LinuxCNC: realtime, the lines, unload all) with
        the modules loadable: r.returncode is halcmd's (non-zero when a loadrt failed), r.log the
        output, r.leftovers and r.seconds as below.

    r = lh.start_fails(ini, modules=[...], name="bad", work=work, timeout=60)
        Starts LinuxCNC on a configuration that must not start (a kinematics module that fails
        its `loadrt`): r.started is True if linuxcncrsh answered (it should not), r.returncode
        is the `linuxcnc` script's exit status, r.log its output, r.leftovers as above.

Guaranteed cleanup and one LinuxCNC at a time (lcnc_process.py, described at its top): whatever
LinuxCNC leaves is removed after the `with` block, start_fails and halrun, also after an exception,
a failed check or the deadline; a second test's LinuxCNC waits for the first.
"""
import json
import os
import pwd
import re
import shutil
import signal
import socket
import subprocess
import sys
import time

# The process side (one LinuxCNC at a time, start, stop, cleanup) is lcnc_process.py; its public
# names are the harness's too (lh.USER, lh.workdir(), lh.leftovers(), ...).
from lcnc_process import (HARNESS_LOCK, LOCK, MODULES, USER, WAIT, LinuxCNCProcess, as_root,
                          leftovers, user_prefix, workdir)

__all__ = ["USER", "PORT", "MODULES", "LOCK", "HARNESS_LOCK", "WAIT", "Timeout", "skip", "require",
           "workdir", "copy_config", "HEXAPOD_SAMPLE", "hexapod_sample", "make_headless", "set_ini",
           "leftovers", "LinuxCNC", "StartResult", "start_fails", "session", "halrun"]

PORT = 5007  # linuxcncrsh's port


class Timeout(Exception):
    """The test's deadline (require(deadline=...)) passed, or the test was asked to stop."""


def skip(why):
    """Ends the test as skipped (exit 77)."""
    print(f"SKIP: {why}")
    sys.stdout.flush()
    sys.exit(77)


def _raise(signum, frame):
    raise Timeout(f"stopped by signal {signum} (deadline or SIGTERM): cleaning up")


def require(modules=(), deadline=150):
    """Exit 77 unless LinuxCNC can run here with `modules`; arms the deadline (see the top)."""
    if shutil.which("linuxcnc") is None or not os.path.isdir(MODULES):
        skip("LinuxCNC is not installed (scripts/setup.sh installs linuxcnc-uspace)")
    for module in modules:
        if not os.path.exists(module):
            skip(f"{module} was not built (no halcompile or LinuxCNC headers)")
    if as_root():
        try:
            pwd.getpwnam(USER)
        except KeyError:
            skip(f"running as root and user {USER} does not exist (scripts/setup.sh creates it)")
        if shutil.which("unshare") is None or shutil.which("runuser") is None:
            skip("unshare or runuser (util-linux) is missing")
        probe = subprocess.run(["unshare", "--mount", "--propagation", "private", "true"],
                               capture_output=True, text=True)
        if probe.returncode != 0:
            skip(f"cannot make a private mount namespace here: {probe.stderr.strip()}")
    else:
        import filecmp
        for module in modules:
            installed = os.path.join(MODULES, os.path.basename(module))
            if not os.path.exists(installed) or not filecmp.cmp(installed, module, shallow=False):
                skip(f"not root: install {module} into {MODULES} to run this test")
    signal.signal(signal.SIGALRM, _raise)
    signal.signal(signal.SIGTERM, _raise)
    signal.alarm(int(deadline))


def _open_up(path):
    os.chmod(path, 0o777)
    for root, dirs, files in os.walk(path):
        for entry in dirs + files:
            os.chmod(os.path.join(root, entry), 0o777)


def copy_config(src, work, name="cfg"):
    """A copy of the configuration folder `src` in `work`, which USER may write (.var files)."""
    cfg = os.path.join(work, name)
    shutil.copytree(src, cfg)
    _open_up(cfg)
    return cfg


HEXAPOD_SAMPLE = "/usr/share/doc/linuxcnc/examples/sample-configs/sim/axis/vismach/hexapod-sim"


def hexapod_sample(prefix):
    """LinuxCNC's own hexapod-sim (genhexkins, inch) ready to run headless: (work, cfg, ini). A
    new work folder, the sample copied into work/cfg, linuxcncrsh as display and a one-tool table.
    Exit 77 (skipped) when the sample is not installed."""
    if not os.path.isdir(HEXAPOD_SAMPLE):
        skip(f"LinuxCNC's sample configuration {HEXAPOD_SAMPLE} is not installed")
    work = workdir(prefix)
    cfg = copy_config(HEXAPOD_SAMPLE, work, "cfg")
    ini = os.path.join(cfg, "hexapod.ini")
    make_headless(ini)
    with open(os.path.join(cfg, "hexapod.tbl"), "w") as f:
        f.write("T1 P1 D0.125 Z+0.5 ;test tool\n")
    return work, cfg, ini


def make_headless(ini):
    """The configuration as a headless test configuration: linuxcncrsh, no GUI panels."""
    with open(ini) as f:
        s = f.read()
    s = re.sub(r"(?m)^DISPLAY\s*=.*$", "DISPLAY = linuxcncrsh", s)
    s = re.sub(r"(?m)^(PYVCP|INTRO_GRAPHIC|INTRO_TIME|POSTGUI_HALFILE)\s*=.*\n", "", s)
    s = re.sub(r"(?m)^HALCMD\s*=\s*loadusr -W hexagui\s*\n", "", s)
    s = re.sub(r"(?m)^(HALFILE\s*=\s*LIB:basic_sim\.tcl)\s*$", r"\1 -no_use_hal_manualtoolchange",
               s)
    with open(ini, "w") as f:
        f.write(s)


def set_ini(ini, section, key, value):
    """Sets `key = value` in [section] of `ini` (the first such key; added if absent)."""
    with open(ini) as f:
        s = f.read()
    head = re.search(rf"(?m)^\[{re.escape(section)}\]\s*$", s)
    if head is None:
        s = s.rstrip("\n") + f"\n\n[{section}]\n{key} = {value}\n"
    else:
        end = re.search(r"(?m)^\[", s[head.end():])
        stop = head.end() + (end.start() if end else len(s) - head.end())
        body = s[head.end():stop]
        line = re.search(rf"(?m)^{re.escape(key)}\s*=.*$", body)
        if line:
            body = body[:line.start()] + f"{key} = {value}" + body[line.end():]
        else:
            body = body.rstrip("\n") + f"\n{key} = {value}\n\n"
        s = s[:head.end()] + body + s[stop:]
    with open(ini, "w") as f:
        f.write(s)


class LinuxCNC(LinuxCNCProcess):
    """One headless LinuxCNC session (see the top of the module): the process (LinuxCNCProcess)
    and linuxcncrsh and HAL to talk to it."""

    # -- start and stop (the rest is LinuxCNCProcess's) --

    def connect(self, timeout=90):
        """Waits for linuxcncrsh and opens a session; False if LinuxCNC ended first."""
        deadline = time.time() + timeout
        while True:
            try:
                self.sock = socket.create_connection(("127.0.0.1", PORT), timeout=10)
                break
            except OSError:
                if self.proc.poll() is not None:
                    return False
                if time.time() > deadline:
                    raise RuntimeError(f"linuxcncrsh did not answer on port {PORT} in {timeout} s")
                time.sleep(0.2)
        self.buf = b""
        for c in ["hello EMC pkm 1", "set enable EMCTOO", "set echo off", "set verbose on"]:
            self.ask(c)
        return True

    def __enter__(self):
        try:
            self.launch()
            if not self.connect():
                raise RuntimeError("LinuxCNC ended before linuxcncrsh answered")
        except BaseException:
            self.stop()
            raise
        return self

    def __exit__(self, *exc):
        self.stop()
        return False

    # -- linuxcncrsh --

    def ask(self, command):
        """Sends one linuxcncrsh command; returns its reply line."""
        self.sock.sendall(command.encode() + b"\r\n")
        while b"\n" not in self.buf:
            data = self.sock.recv(4096)
            if not data:
                raise RuntimeError(f"connection closed after '{command}'")
            self.buf += data
        line, self.buf = self.buf.split(b"\n", 1)
        return line.decode().strip()

    def joint_count(self):
        """[KINS] JOINTS of the INI (linuxcncrsh reports more joints than the machine has)."""
        with open(self.ini) as f:
            m = re.search(r"(?ms)^\[KINS\].*?^JOINTS\s*=\s*(\d+)", f.read())
        return int(m.group(1)) if m else None

    def home(self, timeout=90):
        """Estop off, machine on, homes all joints and waits until the INI's [KINS] JOINTS
        joints are homed."""
        for c in ["set estop off", "set machine on", "set mode manual", "set home -1"]:
            self.ask(c)
        joints = self.joint_count()
        deadline = time.time() + timeout
        while time.time() < deadline:
            reply = self.ask("get joint_homed").split()
            flags = reply[1:1 + joints] if joints else reply[1:]
            if reply[:1] == ["JOINT_HOMED"] and flags and all(f == "YES" for f in flags):
                self.ask("set mode mdi")
                return
            time.sleep(0.1)
        raise RuntimeError("homing did not finish")

    def mdi(self, command, timeout=60):
        """Runs one MDI line (switching to MDI mode) and waits until it is done."""
        if not self.ask("get mode").endswith("MDI"):
            self.ask("set mode mdi")
        reply = self.ask(f"set mdi {command}")
        if "NAK" in reply:
            raise RuntimeError(f"MDI '{command}' refused: {reply}")
        self.ask("set wait done")
        deadline = time.time() + timeout
        while time.time() < deadline:
            if self.ask("get program_status").endswith("IDLE"):
                return
            time.sleep(0.05)
        raise RuntimeError(f"'{command}' did not finish in {timeout} s")

    def numbers(self, what, count=6):
        """The first `count` numbers of `get <what>`."""
        return [float(v) for v in self.ask(f"get {what}").split()[1:1 + count]]

    def joints(self, count=6):
        """Joint positions (linuxcncrsh, 6 decimals)."""
        return self.numbers("joint_pos", count)

    def world(self, count=6):
        """World position, LinuxCNC's forward kinematics of the joints (6 decimals)."""
        return self.numbers("abs_act_pos", count)

    # -- HAL --

    def pins(self, names):
        """{name: value} of HAL pins or parameters, at full precision (python3's hal module)."""
        code = ("import hal, json, os, sys\n"
                "c = hal.component('pkm-read-%d' % os.getpid())\n"
                "out = {}\n"
                "for n in sys.argv[1:]:\n"
                "    try: out[n] = hal.get_value(n)\n"
                "    except Exception as e: out[n] = 'error: ' + str(e)\n"
                "c.exit()\n"
                "print(json.dumps(out))\n")
        r = subprocess.run(user_prefix() + ["/usr/bin/python3", "-c", code, *names],
                           capture_output=True, text=True, timeout=20)
        if r.returncode != 0:
            raise RuntimeError(f"reading HAL pins failed: {r.stderr.strip()}")
        return json.loads(r.stdout.strip().splitlines()[-1])

    def pin(self, name):
        return self.pins([name])[name]

    def setp(self, name, value):
        """Sets the HAL pin or parameter `name` (an unconnected input pin, or a parameter) to
        `value`, as `halcmd setp` does (python3's `hal` module)."""
        code = ("import hal, os, sys\n"
                "c = hal.component('pkm-set-%d' % os.getpid())\n"
                "try: hal.set_p(sys.argv[1], sys.argv[2])\n"
                "finally: c.exit()\n")
        r = subprocess.run(user_prefix() + ["/usr/bin/python3", "-c", code, name, str(value)],
                           capture_output=True, text=True, timeout=20)
        if r.returncode != 0:
            raise RuntimeError(f"setting HAL pin {name} failed: {r.stderr.strip()}")


class StartResult:
    """What start_fails() saw: started, returncode, log, leftovers, seconds."""

    def __init__(self, started, returncode, log, left, seconds):
        self.started, self.returncode, self.log = started, returncode, log
        self.leftovers, self.seconds = left, seconds


def start_fails(ini, modules=(), name="refused", work=None, timeout=60):
    """Starts LinuxCNC expecting it not to come up; see the top of the module."""
    cnc = LinuxCNC(ini, modules, name, work)
    started = False
    try:
        cnc.launch()
        deadline = time.time() + timeout
        while cnc.proc.poll() is None and time.time() < deadline:
            try:
                socket.create_connection(("127.0.0.1", PORT), timeout=1).close()
                started = True
                break
            except OSError:
                time.sleep(0.2)
        returncode = cnc.proc.poll()
    finally:
        cnc.stop()
    return StartResult(started, returncode, cnc.log, cnc.leftovers, cnc.seconds)


def session(ini, modules, name, work, body):
    """Runs body(cnc, failures) on a LinuxCNC; returns (failures, log). See the top."""
    failures = []
    cnc = LinuxCNC(ini, modules, name, work)
    try:
        with cnc:
            body(cnc, failures)
    except (RuntimeError, OSError) as e:
        failures.append(f"{type(e).__name__}: {e}")
    if cnc.leftovers:
        failures.append(f"left behind after LinuxCNC stopped: {cnc.leftovers}")
    print(f"{name}: LinuxCNC ran {cnc.seconds:.1f} s")
    return failures, cnc.log


def halrun(commands, modules=(), name="halrun", work=None, timeout=60):
    """Runs halcmd `commands` (a list of lines) with `halrun -f` (realtime started, the commands,
    then everything unloaded) as LinuxCNC would, with `modules` loadable; no LinuxCNC. Returns a
    StartResult: returncode (halcmd's; non-zero when a loadrt failed), log (the output),
    leftovers, seconds; started is False."""
    work = work or workdir()
    hal = os.path.join(work, f"{name}.hal")
    with open(hal, "w") as f:
        f.write("\n".join(commands) + "\n")
    os.chmod(hal, 0o644)
    cnc = LinuxCNC(hal, modules, name, work, command=["halrun", "-f", hal])
    returncode = None
    try:
        cnc.launch()
        try:
            returncode = cnc.proc.wait(timeout=timeout)
        except subprocess.TimeoutExpired:
            pass
    finally:
        cnc.stop()
    return StartResult(False, returncode, cnc.log, cnc.leftovers, cnc.seconds)
