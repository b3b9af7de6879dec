# pkm's link to a running LinuxCNC (docs/linuxcnc.md, "The live machine"), embedded into
# pkm::live. Two programs in one file, so that both report the same status record:
#   `/usr/bin/python3 -u -c <this file> PERIOD`   the reader (LinuxcncLink), below;
#   `/usr/bin/python3 -u -c <this file> command`  the commander (LinuxcncCommander), at the end.
#
# The reader polls LinuxCNC's status channel (the `linuxcnc` Python module of linuxcnc-uspace, which reads
# the task's status buffer in shared memory: no daemon, full double precision) every PERIOD
# seconds and writes one JSON object per line to standard output. It never sends a command.
# It exits when its standard input closes (the pkm process that started it has ended).
#
# Lines written:
#   {"fatal": TEXT}                        the module cannot be imported (then exit 3)
#   {"error": TEXT}                        LinuxCNC is not running, or stopped (polling goes on)
#   {"seq": N, "t": SECONDS, ...status}    a status record; keys as LinuxcncStatus documents
import json
import os
import select
import signal
import sys
import time

try:
    import linuxcnc
except ImportError as exc:  # linuxcnc-uspace is not installed for this python3
    print(json.dumps({"fatal": "python3 cannot import the linuxcnc module (%s): install "
                      "linuxcnc-uspace" % exc}), flush=True)
    sys.exit(3)


def finite(values):
    """A list of floats with non-finite entries as None (JSON has no NaN)."""
    return [v if v == v and abs(v) != float("inf") else None for v in values]


def record(stat, seq):
    """The fields pkm's live view reads, from one poll of the status channel."""
    joints = int(stat.joints)
    return {
        "seq": seq,
        "t": time.monotonic(),
        "ini": stat.ini_filename,
        "kinematics_type": int(stat.kinematics_type),
        "linear_units": float(stat.linear_units),
        "joints": joints,
        "joint_actual": finite(stat.joint_actual_position[:joints]),
        "joint_commanded": finite(stat.joint_position[:joints]),
        "pose_commanded": finite(stat.position[:6]),
        "pose_actual": finite(stat.actual_position[:6]),
        "estop": bool(stat.estop),
        "enabled": bool(stat.enabled),
        "homed": [bool(h) for h in stat.homed[:joints]],
        "task_mode": int(stat.task_mode),
        "task_state": int(stat.task_state),
        "exec_state": int(stat.exec_state),
        "interp_state": int(stat.interp_state),
        "paused": bool(stat.paused),
        "inpos": bool(stat.inpos),
        "file": stat.file,
        "current_line": int(stat.current_line),
        "motion_line": int(stat.motion_line),
        "read_line": int(stat.read_line),
        "tool": int(stat.tool_in_spindle),
        "tool_offset": finite(stat.tool_offset[:3]),
        "g5x_index": int(stat.g5x_index),
        "g5x_offset": finite(stat.g5x_offset[:6]),
        "g92_offset": finite(stat.g92_offset[:6]),
        "velocity": float(stat.current_vel),
    }


# A status channel stays attached to LinuxCNC's shared memory after LinuxCNC has ended (and keeps
# that memory from being freed), reading its last state: the channel is opened anew this often, s,
# so that an ended LinuxCNC is reported, a restarted one is followed, and the memory is let go.
REOPEN_EVERY = 1.0


def reader(period):
    stat = None
    opened = 0.0
    seq = 0
    while True:
        started = time.monotonic()
        try:
            if stat is not None and started - opened >= REOPEN_EVERY:
                stat = None
            if stat is None:
                stat = linuxcnc.stat()
                opened = started
            stat.poll()
            seq += 1
            line = record(stat, seq)
        except linuxcnc.error as exc:
            stat = None
            line = {"error": "LinuxCNC is not running on this host (%s)" % exc}
        print(json.dumps(line), flush=True)
        wait = max(0.0, period - (time.monotonic() - started))
        readable, _, _ = select.select([sys.stdin], [], [], wait)
        if readable and not sys.stdin.readline():
            return


# ---- the commander --------------------------------------------------------------------------
# It reads one JSON request per line on standard input and answers each with one JSON line:
#   {"id": N, "ok": true, "status": RECORD, "values": [...]}   or   {"id": N, "ok": false,
#   "error": TEXT}. Requests ("op"):
#   "status"                          the status record
#   "mdi", "line", "timeout"          one MDI line, refused unless LinuxCNC is out of E-stop, on,
#                                     homed and idle; answered when the motion has ended
#   "hal_get", "pins"[, "samples", "interval"]  HAL pin values (this process is a HAL component),
#                                     the mean of `samples` reads `interval` s apart
#   "hal_set", "pin", "value"         sets an unconnected input pin or a parameter
#   "machine", "on"                   machine on (true) or off (false); off needs no motion
#   "abort"                           stops any motion (LinuxCNC's abort)
# Safety: when its standard input ends (the pkm process ended or dropped the connection), on
# SIGTERM or Ctrl-C, it aborts whatever motion it started and exits. An "abort" line that arrives
# while an MDI line executes stops it at once.

def motion_refusal(stat):
    """Why LinuxCNC must not be sent motion now ("" when it may)."""
    if stat.estop:
        return "LinuxCNC is in E-stop"
    if not stat.enabled or stat.task_state != linuxcnc.STATE_ON:
        return "the machine is off"
    if not all(stat.homed[:int(stat.joints)]):
        return "not every joint is homed"
    if stat.interp_state != linuxcnc.INTERP_IDLE or stat.task_mode == linuxcnc.MODE_AUTO and \
            stat.exec_state not in (linuxcnc.EXEC_DONE, linuxcnc.EXEC_ERROR):
        return "LinuxCNC is running a program or command"
    return ""


class Aborted(Exception):
    pass


class Commander:
    def __init__(self):
        self.stat = linuxcnc.stat()
        self.cmd = linuxcnc.command()
        self.errors = linuxcnc.error_channel()
        self.hal = None
        self.moved = False
        # Unbuffered, so that select() sees every line not yet read (an "abort" during a move).
        self.input = open(0, "rb", buffering=0, closefd=False)

    def poll(self):
        self.stat.poll()
        return self.stat

    def status(self):
        return record(self.poll(), 0)

    def lcnc_error(self):
        """LinuxCNC's next error message ("" when none)."""
        e = self.errors.poll()
        if e and e[0] in (linuxcnc.NML_ERROR, linuxcnc.OPERATOR_ERROR):
            return e[1]
        return ""

    def check_input(self):
        """An "abort" line or the end of input while a motion runs: abort it."""
        readable, _, _ = select.select([self.input], [], [], 0)
        if not readable:
            return
        line = self.input.readline()
        if not line or json.loads(line).get("op") == "abort":
            self.abort()
            raise Aborted("aborted" if line else "pkm's connection ended: aborted")

    def mdi(self, line, timeout):
        while self.lcnc_error():
            pass  # old messages are not this command's
        why = motion_refusal(self.poll())
        if why:
            raise RuntimeError("refused: " + why)
        if self.stat.task_mode != linuxcnc.MODE_MDI:
            self.cmd.mode(linuxcnc.MODE_MDI)
            self.cmd.wait_complete(5)
        self.moved = True
        self.cmd.mdi(line)
        self.cmd.wait_complete(5)
        until = time.monotonic() + timeout
        while True:
            time.sleep(0.01)
            self.check_input()
            stat = self.poll()
            err = self.lcnc_error()
            if err:
                self.abort()
                raise RuntimeError("LinuxCNC: " + err)
            if stat.estop or not stat.enabled:
                raise RuntimeError("LinuxCNC left the on state during the move")
            if stat.interp_state == linuxcnc.INTERP_IDLE and stat.queue == 0 and stat.inpos:
                return record(stat, 0)
            if time.monotonic() > until:
                self.abort()
                raise RuntimeError("the move did not end within %g s: aborted" % timeout)

    def abort(self):
        if self.moved:
            self.cmd.abort()
            self.cmd.wait_complete(5)

    def component(self):
        if self.hal is None:
            import hal
            self.hal = (hal, hal.component("pkm-command-%d" % os.getpid()))
        return self.hal[0]

    def machine(self, on):
        if on:
            self.cmd.state(linuxcnc.STATE_ON)
        else:
            if self.poll().interp_state != linuxcnc.INTERP_IDLE or not self.stat.inpos:
                raise RuntimeError("refused: the machine is moving")
            self.cmd.state(linuxcnc.STATE_OFF)
        self.cmd.wait_complete(5)
        until = time.monotonic() + 5
        while bool(self.poll().enabled) != on:
            if time.monotonic() > until:
                raise RuntimeError("LinuxCNC did not turn the machine %s" % ("on" if on else "off"))
            time.sleep(0.01)
        return record(self.stat, 0)

    def serve(self, request):
        op = request.get("op")
        if op == "status":
            return {"status": self.status()}
        if op == "mdi":
            return {"status": self.mdi(str(request["line"]), float(request.get("timeout", 120)))}
        if op == "hal_get":
            h = self.component()
            pins = [str(p) for p in request["pins"]]
            samples = max(1, int(request.get("samples", 1)))
            sums = [0.0] * len(pins)
            for k in range(samples):
                if k:
                    time.sleep(float(request.get("interval", 0.002)))
                for i, p in enumerate(pins):
                    sums[i] += float(h.get_value(p))
            return {"values": [v / samples for v in sums]}
        if op == "hal_set":
            self.component().set_p(str(request["pin"]), str(request["value"]))
            return {}
        if op == "machine":
            return {"status": self.machine(bool(request["on"]))}
        if op == "abort":
            self.abort()
            return {}
        raise RuntimeError("unknown request %r" % op)

    def close(self):
        self.abort()
        if self.hal is not None:
            self.hal[1].exit()


def commander():
    signal.signal(signal.SIGTERM, lambda *_: sys.exit(0))
    try:
        c = Commander()
    except linuxcnc.error as exc:
        print(json.dumps({"fatal": "LinuxCNC is not running on this host (%s)" % exc}), flush=True)
        sys.exit(3)
    try:
        for line in iter(c.input.readline, b""):
            request = {}
            try:
                request = json.loads(line)
                reply = c.serve(request)
                reply.update({"id": request.get("id"), "ok": True})
            except Aborted as exc:
                reply = {"id": request.get("id"), "ok": False, "error": str(exc)}
                print(json.dumps(reply), flush=True)
                if "ended" in str(exc):
                    return
                continue
            except linuxcnc.error as exc:
                reply = {"id": request.get("id"), "ok": False,
                         "error": "LinuxCNC is not running on this host (%s)" % exc}
            except Exception as exc:  # every failure is answered, never a crash
                reply = {"id": request.get("id"), "ok": False, "error": str(exc)}
            print(json.dumps(reply), flush=True)
    finally:
        c.close()


try:
    if len(sys.argv) > 1 and sys.argv[1] == "command":
        commander()
    else:
        reader(float(sys.argv[1]) if len(sys.argv) > 1 else 0.04)
except (BrokenPipeError, KeyboardInterrupt):
    pass
