# pkm's reader of a running LinuxCNC (docs/linuxcnc.md, "The live machine"), embedded into
# pkm::live and run by LinuxcncLink as `/usr/bin/python3 -u -c <this file> PERIOD`.
#
# It polls LinuxCNC's status channel (the `linuxcnc` Python module of linuxcnc-uspace, which reads
# the task's status buffer in shared memory: no daemon, full double precision) every PERIOD
# seconds and writes one JSON object per line to standard output. It never sends a command.
# It exits when its standard input closes (the pkm process that started it has ended).
#
# Lines written:
#   {"fatal": TEXT}                        the module cannot be imported (then exit 3)
#   {"error": TEXT}                        LinuxCNC is not running, or stopped (polling goes on)
#   {"seq": N, "t": SECONDS, ...status}    a status record; keys as LinuxcncStatus documents
import json
import select
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


def main():
    period = float(sys.argv[1]) if len(sys.argv) > 1 else 0.04
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


try:
    main()
except (BrokenPipeError, KeyboardInterrupt):
    pass
