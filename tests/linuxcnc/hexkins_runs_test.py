#!/usr/bin/python3
"""The pkmhexkins kinematics module in a running LinuxCNC (docs/linuxcnc.md).

The sample configuration data/linuxcnc/hexapod-sim-pkm is given a calibrated geometry (all 42
parameters of the hexapod-sim machine moved, the platform's tool point too), written as the
module's HAL pins from a pkm machine file. LinuxCNC is started on it headless (linuxcncrsh, POSIX
non-realtime) with the module built by this build tree, homed, and moved by MDI. Checked:
  - after homing, LinuxCNC's world position (its forward kinematics) is [TRAJ] HOME;
  - at each pose, the joint positions equal pkm's inverse kinematics of the calibrated machine,
    and the world position LinuxCNC reports equals the commanded pose (forward kinematics in the
    loop);
  - with a G43 tool length offset, the joints equal pkm's IK of the machine with the tool length
    added to its spindle offset (genhexkins' tool-offset convention).
All to 1e-6 in (linuxcncrsh prints 6 decimals).

LinuxCNC loads modules from /usr/lib/linuxcnc/modules only. As root, the test runs LinuxCNC in a
private mount namespace where a copy of that folder with this build's module is mounted over it
(nothing on the system changes); otherwise the installed module must be this build's. LinuxCNC
runs as the unprivileged user scripts/setup.sh creates (rtapi_app refuses root). Exit 77 (skipped)
without LinuxCNC, the module, the user, or a way to load the module.

Usage: hexkins_runs_test.py PKM_BINARY MODULE_SO SOURCE_DIR
"""
import filecmp
import json
import os
import pwd
import random
import re
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import time

USER = "pkm-linuxcnc"
PORT = 5007  # linuxcncrsh's port: one LinuxCNC at a time (CTest RESOURCE_LOCK linuxcnc)
MODULES = "/usr/lib/linuxcnc/modules"
HOME = (0.0, 0.0, 20.0, 0.0, 0.0, 0.0)
POSES = [(1, 1, 21, 0, 0, 0), (-2, 1.5, 19, 3, -2, 5), (0.5, -2, 22.5, -4, 1, -3),
         (2.5, 0.5, 20.5, 6, 4, -8)]
TOOL_POSES = [(0.5, -0.5, 20, 0, 0, 0), (-1, 1, 21, 5, -4, 2)]
TOOL_LENGTH = 0.5  # T1 in the sample's tool table
TOL = 1e-6  # inch: 6 printed decimals (5e-7) plus the FK tolerance (1e-9)


def skip(why):
    print(f"SKIP: {why}")
    sys.exit(77)


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


def pkm_ik(pkm, machine, poses, work):
    path = os.path.join(work, "machine.json")
    with open(path, "w") as f:
        json.dump(machine, f)
    csv = os.path.join(work, "poses.csv")
    with open(csv, "w") as f:
        f.write("x,y,z,a,b,c\n" + "".join(",".join(map(repr, p)) + "\n" for p in poses))
    rows = run([pkm, "hexapod", "ik", "--machine", path, "--poses", csv]).strip().splitlines()
    return [[float(v) for v in r.split(",")[:6]] for r in rows[1:]]


def write_config(cfg, machine, home_joints):
    """The sample made headless, with the machine's pins and joint homes."""
    hal = []
    for i, s in enumerate(machine["struts"]):
        for k, c in enumerate("xyz"):
            hal.append(f"setp pkmhexkins.base.{i}.{c} {s['base'][k]!r}\n")
            hal.append(f"setp pkmhexkins.platform.{i}.{c} {s['platform'][k]!r}\n")
        hal.append(f"setp pkmhexkins.length-offset.{i} {s['length_offset']!r}\n")
    for k, c in enumerate("xyz"):
        hal.append(f"setp pkmhexkins.tool.{c} {machine['tool_offset'][k]!r}\n")
    path = os.path.join(cfg, "kinematics.hal")
    with open(path) as f:
        kept = [l for l in f if not re.match(r"setp pkmhexkins\.(base|platform|length-offset)", l)]
    with open(path, "w") as f:
        f.writelines(hal + kept)
    ini = os.path.join(cfg, "hexapod.ini")
    with open(ini) as f:
        s = f.read()
    s = re.sub(r"(?m)^DISPLAY\s*=.*$", "DISPLAY = linuxcncrsh", s)
    s = s.replace("LIB:basic_sim.tcl\n", "LIB:basic_sim.tcl -no_use_hal_manualtoolchange\n")
    for i, q in enumerate(home_joints):  # each joint's HOME and HOME_OFFSET: the IK at home
        for key in ("HOME", "HOME_OFFSET"):
            s = re.sub(rf"(\[JOINT_{i}\][^\[]*?^{key} = )[^\n]*", rf"\g<1>{q!r}", s,
                       flags=re.M | re.S)
    with open(ini, "w") as f:
        f.write(s)
    return ini


class Rsh:
    """A linuxcncrsh session (the EMC telnet protocol)."""

    def __init__(self, proc):
        deadline = time.time() + 30
        while True:
            try:
                self.sock = socket.create_connection(("127.0.0.1", PORT), timeout=10)
                break
            except OSError:
                if time.time() > deadline or proc.poll() is not None:
                    raise RuntimeError("linuxcncrsh did not answer on port 5007")
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

    def mdi(self, command):
        reply = self.ask(f"set mdi {command}")
        if "NAK" in reply:
            raise RuntimeError(f"MDI '{command}' refused: {reply}")
        self.ask("set wait done")
        deadline = time.time() + 30
        while time.time() < deadline:
            if self.ask("get program_status").endswith("IDLE"):
                return
            time.sleep(0.05)
        raise RuntimeError(f"'{command}' did not finish")

    def wait_homed(self, timeout=30):
        deadline = time.time() + timeout
        while time.time() < deadline:
            reply = self.ask("get joint_homed")
            if reply.startswith("JOINT_HOMED") and "NO" not in reply.split():
                return
            time.sleep(0.1)
        raise RuntimeError("homing did not finish")

    def numbers(self, what):
        return [float(v) for v in self.ask(f"get {what}").split()[1:7]]


def launch(ini, cfg, module, work, log):
    """LinuxCNC on `ini`, with `module` loadable; the command as a process group leader."""
    user = ["runuser", "-u", USER, "--"] if os.geteuid() == 0 else []
    start = user + ["env", "RUNTESTS=1", "linuxcnc", ini]
    if os.geteuid() == 0:
        modules = work + "-modules"
        shutil.copytree(MODULES, modules, symlinks=True)
        shutil.copy(module, modules)
        os.chmod(modules, 0o755)
        script = 'mount --bind "$1" "$2" && shift 2 && exec "$@"'
        start = ["unshare", "--mount", "--propagation", "private", "sh", "-c", script, "sh",
                 modules, MODULES] + start
    return subprocess.Popen(start, cwd=cfg, stdout=log, stderr=subprocess.STDOUT,
                            start_new_session=True)


def hal_pins(names):
    """The values of pkmhexkins.<name> in the running HAL (halcmd getp, as the LinuxCNC user)."""
    user = ["runuser", "-u", USER, "--"] if os.geteuid() == 0 else []
    values = {}
    for name in names:
        r = subprocess.run(user + ["halcmd", "getp", f"pkmhexkins.{name}"], capture_output=True,
                           text=True, timeout=10)
        values[name] = r.stdout.strip() if r.returncode == 0 else f"error: {r.stderr.strip()}"
    return values


def rtapi_running():
    """True when a live (not zombie) rtapi_app process exists."""
    for pid in filter(str.isdigit, os.listdir("/proc")):
        try:
            with open(f"/proc/{pid}/stat") as f:
                stat = f.read()
        except OSError:
            continue
        name, state = stat[stat.find("(") + 1:stat.rfind(")")], stat[stat.rfind(")") + 2]
        if name == "rtapi_app" and state != "Z":
            return True
    return False


def user_processes(uid):
    """Pids of the live processes of `uid` (the dedicated test user: all started by this test)."""
    pids = []
    for pid in filter(str.isdigit, os.listdir("/proc")):
        try:
            if os.stat(f"/proc/{pid}").st_uid == uid:
                pids.append(int(pid))
        except OSError:
            pass
    return pids


def cleanup(proc, rsh):
    """No LinuxCNC process, HAL shared memory or lock left, also after a failure."""
    if rsh is not None:
        try:
            rsh.sock.sendall(b"shutdown\r\n")  # LinuxCNC closes the connection as it stops
        except OSError:
            pass
    try:
        proc.wait(timeout=20)
    except subprocess.TimeoutExpired:
        os.killpg(proc.pid, signal.SIGTERM)
        try:
            proc.wait(timeout=5)
        except subprocess.TimeoutExpired:
            os.killpg(proc.pid, signal.SIGKILL)
            proc.wait()
    if os.geteuid() != 0:
        if rtapi_running():
            subprocess.run(["halrun", "-U"], capture_output=True, timeout=30)
        return  # halrun -U freed what LinuxCNC left; the user's other segments are not ours
    uid = pwd.getpwnam(USER).pw_uid
    for sig in (signal.SIGTERM, signal.SIGKILL):
        for pid in user_processes(uid):
            try:
                os.kill(pid, sig)
            except OSError:
                pass
        time.sleep(0.5)
    for line in subprocess.run(["ipcs", "-m"], capture_output=True, text=True).stdout.splitlines():
        f = line.split()  # key shmid owner perms bytes nattch
        if len(f) >= 6 and f[2] in (USER, USER[:10], str(uid)) and f[5] == "0":
            subprocess.run(["ipcrm", "-m", f[1]], capture_output=True)
    lock = os.path.join(tempfile.gettempdir(), "linuxcnc.lock")
    if os.path.exists(lock) and os.stat(lock).st_uid == uid:
        os.remove(lock)


def check(failures, what, got, want):
    err = max(abs(g - w) for g, w in zip(got, want))
    print(f"{what}: LinuxCNC {got}; pkm {want}; max difference {err:.1e}")
    if err > TOL:
        failures.append(f"{what}: differs from pkm by {err}")


def check_requirements(module):
    """Skips (exit 77) when LinuxCNC, the module, the user or a way to load the module is missing."""
    if shutil.which("linuxcnc") is None or not os.path.isdir(MODULES):
        skip("LinuxCNC is not installed (scripts/setup.sh installs linuxcnc-uspace)")
    if not os.path.exists(module):
        skip(f"{module} was not built (no halcompile or LinuxCNC headers)")
    if os.geteuid() == 0:
        try:
            pwd.getpwnam(USER)
        except KeyError:
            skip(f"running as root and user {USER} does not exist (scripts/setup.sh creates it)")
        if shutil.which("unshare") is None:
            skip("unshare (util-linux) is missing")
        probe = subprocess.run(["unshare", "--mount", "--propagation", "private", "true"],
                               capture_output=True, text=True)
        if probe.returncode != 0:
            skip(f"cannot make a private mount namespace here: {probe.stderr.strip()}")
    else:
        installed = os.path.join(MODULES, os.path.basename(module))
        if not os.path.exists(installed) or not filecmp.cmp(installed, module, shallow=False):
            skip(f"not root: install {module} into {MODULES} to run this test")
    deadline = time.time() + 90  # another test program's LinuxCNC (outside this ctest's lock)
    while rtapi_running() or os.path.exists(os.path.join(tempfile.gettempdir(), "linuxcnc.lock")):
        if time.time() > deadline:
            sys.exit("FAIL: another LinuxCNC (rtapi_app or its lock) is still there after 90 s")
        time.sleep(1)


def session(ini, cfg, module, work, name, body):
    """Runs body(rsh, failures) on a LinuxCNC started on `ini`; returns (failures, log text)."""
    for root, dirs, files in os.walk(cfg):
        for entry in dirs + files:
            os.chmod(os.path.join(root, entry), 0o777)
    os.chmod(cfg, 0o777)
    log_path = os.path.join(work, f"{name}.log")
    log = open(log_path, "w")
    started = time.time()
    proc = launch(ini, cfg, module, os.path.join(work, name), log)
    failures = []
    rsh = None
    try:
        rsh = Rsh(proc)
        body(rsh, failures)
    except (RuntimeError, OSError) as e:
        failures.append(str(e))
    finally:
        cleanup(proc, rsh)
        log.close()
    print(f"{name}: LinuxCNC ran {time.time() - started:.1f} s")
    with open(log_path) as f:
        return failures, f.read()


def moves(expected, expected_tool):
    """Home, the MDI poses and the tool poses, each checked against pkm."""

    def body(rsh, failures):
        for c in ["set estop off", "set machine on", "set mode manual", "set home -1"]:
            rsh.ask(c)
        rsh.wait_homed()
        check(failures, "world after homing", rsh.numbers("abs_act_pos"), HOME)
        rsh.ask("set mode mdi")
        for pose, want in zip(POSES, expected[1:]):
            rsh.mdi("G0 X{} Y{} Z{} A{} B{} C{}".format(*pose))
            check(failures, f"joints at {pose}", rsh.numbers("joint_pos"), want)
            check(failures, f"world at {pose}", rsh.numbers("abs_act_pos"), pose)
        pins = hal_pins(["fwd-kins-fail", "geometry-ok", "max-iterations", "last-iterations",
                         "fwd-kins-failures"])
        print(f"pkmhexkins pins: {pins}")
        if pins.get("fwd-kins-fail") != "FALSE" or pins.get("geometry-ok") != "TRUE":
            failures.append(f"forward kinematics reports a failure: {pins}")
        if int(pins.get("max-iterations", "0")) < 1:
            failures.append("LinuxCNC never ran the module's forward kinematics")
        rsh.mdi("T1 M6")
        rsh.mdi("G43")
        for pose, want in zip(TOOL_POSES, expected_tool):
            rsh.mdi("G0 X{} Y{} Z{} A{} B{} C{}".format(*pose))
            check(failures, f"joints at {pose} with G43 (tool {TOOL_LENGTH} in)",
                  rsh.numbers("joint_pos"), want)

    return body


def refused(rsh, failures):
    """A geometry the module refuses: no motion, geometry-ok false."""
    for c in ["set estop off", "set machine on", "set mode manual", "set home -1"]:
        rsh.ask(c)
    time.sleep(1.0)
    pins = hal_pins(["geometry-ok"])
    if pins.get("geometry-ok") != "FALSE":
        failures.append(f"a bad geometry was accepted: {pins}")
    rsh.ask("set mode mdi")
    if "NAK" not in rsh.ask("set mdi G0 X1 Y1 Z21"):
        rsh.ask("set wait done")
        if any(abs(v) > 1e-9 for v in rsh.numbers("joint_pos")[:3]) and "NO" in rsh.ask(
                "get joint_homed").split():
            failures.append("a bad geometry moved the machine")


def main():
    pkm, module, source_dir = (os.path.abspath(a) for a in sys.argv[1:4])
    check_requirements(module)
    work = tempfile.mkdtemp(prefix="pkm-hexkins-")
    os.chmod(work, 0o755)
    machine = calibrated_machine(source_dir)
    expected = pkm_ik(pkm, machine, [HOME] + POSES, work)
    tooled = dict(machine, spindle_offset=TOOL_LENGTH)
    tool_poses = [(x, y, z + TOOL_LENGTH, a, b, c) for x, y, z, a, b, c in TOOL_POSES]
    expected_tool = pkm_ik(pkm, tooled, tool_poses, work)
    sample = os.path.join(source_dir, "data/linuxcnc/hexapod-sim-pkm")

    cfg = os.path.join(work, "cfg")
    shutil.copytree(sample, cfg)
    ini = write_config(cfg, machine, expected[0])
    failures, text = session(ini, cfg, module, work, "calibrated", moves(expected, expected_tool))
    if "pkmhexkins:" in text:
        failures.append("the module reported an error")
    if failures:
        sys.exit("FAIL:\n" + "\n".join(failures) + "\n--- linuxcnc log ---\n" + text)

    # A geometry that does not assemble: strut 4 given as a second copy of strut 3.
    bad = json.loads(json.dumps(machine))
    bad["struts"][4]["base"] = bad["struts"][3]["base"]
    bad["struts"][4]["platform"] = bad["struts"][3]["platform"]
    bad_cfg = os.path.join(work, "bad")
    shutil.copytree(sample, bad_cfg)
    bad_ini = write_config(bad_cfg, bad, expected[0])
    failures, text = session(bad_ini, bad_cfg, module, work, "bad-geometry", refused)
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
