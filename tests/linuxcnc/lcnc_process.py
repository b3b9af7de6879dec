"""The process side of lcnc_harness.py (tests import lcnc_harness only; it re-exports this
module's public names): one LinuxCNC at a time on this machine, started with this build's modules
loadable (as the unprivileged user USER when run as root), stopped, and everything it leaves
removed. LinuxCNCProcess starts and stops it; lcnc_harness.LinuxCNC adds linuxcncrsh and HAL.

Guaranteed cleanup (the `with` block's exit, start_fails, and an atexit hook; also after an
exception, a failed check or the deadline): `shutdown` through linuxcncrsh, then SIGTERM to the
`linuxcnc` script (its own cleanup), SIGKILL after a grace period; as root, every process of USER
is ended (the user exists for these tests only), and USER's System V shared memory, semaphores and
message queues, /dev/shm files, /tmp/linuxcnc.lock, the script's /tmp/linuxcnc.{debug,print}.*
files and the rtapi FIFO (RTAPI_FIFO_PATH, in the session's HOME in the work folder) are
removed. The module folder copy lives only in the mount namespace, which ends with its last
process. The test process is the subreaper of LinuxCNC's daemons, so none is left as a zombie
either.

Serialisation: a session holds an flock on /tmp/pkm-linuxcnc-harness.lock, so two test programs
(also from different ctest runs or build trees) wait for each other, up to WAIT seconds; a
LinuxCNC not started by this harness (a live rtapi_app or /tmp/linuxcnc.lock) is also waited for.
A lock file of USER with no process of USER left (a test killed outright) is stale and removed.
"""
import atexit
import fcntl
import glob
import os
import pwd
import shutil
import signal
import subprocess
import tempfile
import time

USER = "pkm-linuxcnc"  # the unprivileged user LinuxCNC runs as when the tests run as root
MODULES = "/usr/lib/linuxcnc/modules"  # where LinuxCNC loads modules from (only there)
LOCK = "/tmp/linuxcnc.lock"  # the `linuxcnc` script's (its path is fixed in the script)
HARNESS_LOCK = "/tmp/pkm-linuxcnc-harness.lock"
WAIT = 120  # seconds to wait for another LinuxCNC to finish


def as_root():
    return os.geteuid() == 0


def _uid():
    return pwd.getpwnam(USER).pw_uid if as_root() else os.geteuid()


def user_prefix():
    """The command prefix that runs a program as the LinuxCNC user."""
    return ["runuser", "-u", USER, "--"] if as_root() else []


def workdir(prefix="pkm-linuxcnc-"):
    """A new temporary folder readable by the LinuxCNC user."""
    work = tempfile.mkdtemp(prefix=prefix)
    os.chmod(work, 0o755)
    return work


# ---- processes and leftovers -------------------------------------------------------------------

def _procs():
    """(pid, uid, name, state) of every process."""
    out = []
    for pid in filter(str.isdigit, os.listdir("/proc")):
        try:
            uid = os.stat(f"/proc/{pid}").st_uid
            with open(f"/proc/{pid}/stat") as f:
                stat = f.read()
        except OSError:
            continue
        name = stat[stat.find("(") + 1:stat.rfind(")")]
        out.append((int(pid), uid, name, stat[stat.rfind(")") + 2]))
    return out


def _rtapi_running():
    return any(name == "rtapi_app" and state != "Z" for _, _, name, state in _procs())


def _user_pids(uid):
    return [pid for pid, u, _, state in _procs() if u == uid and state != "Z"]


def _ipc(uid):
    """(flag, id, owner) of USER's System V IPC objects (shared memory, semaphores, queues)."""
    found = []
    names = (USER, USER[:10], str(uid))
    for flag in ("-m", "-s", "-q"):
        r = subprocess.run(["ipcs", flag], capture_output=True, text=True)
        for line in r.stdout.splitlines():
            f = line.split()
            if len(f) >= 3 and f[0].startswith("0x") and f[2] in names:
                found.append((flag, f[1], f[2]))
    return found


def _tmp_files(uid):
    files = [LOCK] if os.path.exists(LOCK) else []
    files += glob.glob("/tmp/linuxcnc.debug.*") + glob.glob("/tmp/linuxcnc.print.*")
    files += [os.path.join("/dev/shm", f) for f in os.listdir("/dev/shm")]
    mine = []
    for path in files:
        try:
            if os.stat(path).st_uid == uid:
                mine.append(path)
        except OSError:
            pass
    return mine


def leftovers(fifo=None):
    """What a LinuxCNC of this harness could have left: processes, IPC objects, files."""
    uid = _uid()
    left = []
    if as_root():
        left += [f"process {pid}" for pid in _user_pids(uid)]
        left += [f"ipc {flag} {ident}" for flag, ident, _ in _ipc(uid)]
    elif _rtapi_running():
        left.append("rtapi_app")
    left += [f"file {p}" for p in _tmp_files(uid)]
    if fifo and os.path.exists(fifo):
        left.append(f"file {fifo}")
    return left


def _sweep(fifo=None):
    """Ends every process of USER and removes its IPC objects and files (root only)."""
    if not as_root():
        if _rtapi_running():
            subprocess.run(["halrun", "-U"], capture_output=True, timeout=30)
        for path in _tmp_files(_uid()):
            if os.path.basename(path).startswith("linuxcnc.") and path.startswith("/tmp/"):
                os.remove(path)
        return
    uid = _uid()
    for sig in (signal.SIGTERM, signal.SIGKILL):
        for pid in _user_pids(uid):
            try:
                os.kill(pid, sig)
            except OSError:
                pass
        for _ in range(20):
            if not _user_pids(uid):
                break
            time.sleep(0.1)
    remove = {"-m": "-m", "-s": "-s", "-q": "-q"}
    for flag, ident, _ in _ipc(uid):
        subprocess.run(["ipcrm", remove[flag], ident], capture_output=True)
    for path in _tmp_files(uid) + ([fifo] if fifo and os.path.exists(fifo) else []):
        try:
            os.remove(path)
        except OSError:
            pass


# ---- one LinuxCNC at a time --------------------------------------------------------------------

class _Slot:
    """The right to run LinuxCNC: the harness flock, and no other LinuxCNC around."""

    def __init__(self):
        self.fd = None

    def acquire(self):
        deadline = time.time() + WAIT
        old = os.umask(0)
        try:
            self.fd = os.open(HARNESS_LOCK, os.O_RDWR | os.O_CREAT, 0o666)
        finally:
            os.umask(old)
        while True:
            try:
                fcntl.flock(self.fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
                break
            except BlockingIOError:
                if time.time() > deadline:
                    raise RuntimeError(f"another test's LinuxCNC still runs after {WAIT} s")
                time.sleep(0.5)
        # A LinuxCNC this harness did not start, or the remains of a test killed outright.
        while _rtapi_running() or os.path.exists(LOCK):
            if as_root() and not _user_pids(_uid()) and not _rtapi_running():
                try:
                    if os.stat(LOCK).st_uid == _uid():
                        print(f"note: removing a stale {LOCK} (no process of {USER} left)")
                        _sweep()
                        continue
                except OSError:
                    continue
            if time.time() > deadline:
                self.release()
                raise RuntimeError(f"another LinuxCNC (rtapi_app or {LOCK}) still runs after "
                                   f"{WAIT} s")
            time.sleep(1)

    def release(self):
        if self.fd is not None:
            fcntl.flock(self.fd, fcntl.LOCK_UN)
            os.close(self.fd)
            self.fd = None


_active = []


def _become_subreaper():
    """Makes this process the reaper of LinuxCNC's orphans (prctl PR_SET_CHILD_SUBREAPER), so
    that the daemons the `linuxcnc` script leaves behind when it is killed are reaped here rather
    than left as zombies under a PID 1 that does not reap (as in some containers)."""
    try:
        import ctypes
        libc = ctypes.CDLL(None, use_errno=True)
        libc.prctl(36, 1, 0, 0, 0)  # PR_SET_CHILD_SUBREAPER
    except (OSError, AttributeError):
        pass


def _reap():
    """Reaps every finished child (the orphans this process adopted as subreaper)."""
    while True:
        try:
            pid, _ = os.waitpid(-1, os.WNOHANG)
        except ChildProcessError:
            return
        if pid == 0:
            return


@atexit.register
def _cleanup_all():
    for cnc in list(_active):
        cnc.stop()


class LinuxCNCProcess:
    """The `linuxcnc` script (or `command`) started and stopped; lcnc_harness.LinuxCNC talks to
    it."""

    def __init__(self, ini, modules=(), name="linuxcnc", work=None, env=None, command=None):
        self.ini = os.path.abspath(ini)
        self.command = command or ["linuxcnc", self.ini]  # halrun() runs halrun instead
        self.modules = [os.path.abspath(m) for m in modules]
        self.name = name
        self.work = work or workdir()
        self.env = dict(env or {})
        self.log_path = os.path.join(self.work, f"{name}.log")
        self.home_dir = os.path.join(self.work, f"{name}.home")  # HOME: written by USER
        self.fifo = os.path.join(self.home_dir, "rtapi_fifo")
        self.proc = None
        self.sock = None
        self.buf = b""
        self.log = ""
        self.leftovers = []
        self.seconds = 0.0
        self._slot = _Slot()
        self._logfile = None
        self._started = 0.0

    # -- start and stop --

    def launch(self):
        """Starts the `linuxcnc` script (in its own process group); does not wait for it."""
        self._slot.acquire()
        _active.append(self)
        _become_subreaper()
        cfg = os.path.dirname(self.ini)
        os.makedirs(self.home_dir, exist_ok=True)
        os.chmod(self.home_dir, 0o777)
        env = {"RUNTESTS": "1", "HOME": self.home_dir, "RTAPI_FIFO_PATH": self.fifo, **self.env}
        start = user_prefix() + ["env"] + [f"{k}={v}" for k, v in env.items()]
        start += self.command
        if as_root():
            copy = os.path.join(self.work, f"{self.name}.modules")
            shutil.copytree(MODULES, copy, symlinks=True)
            for module in self.modules:
                shutil.copy(module, copy)
            os.chmod(copy, 0o755)
            script = 'mount --bind "$1" "$2" && shift 2 && exec "$@"'
            start = ["unshare", "--mount", "--propagation", "private", "sh", "-c", script, "sh",
                     copy, MODULES] + start
        self._logfile = open(self.log_path, "w")
        self._started = time.time()
        self.proc = subprocess.Popen(start, cwd=cfg, stdout=self._logfile,
                                     stderr=subprocess.STDOUT, start_new_session=True)

    def stop(self):
        """Stops LinuxCNC and removes everything it left (idempotent). The deadline's and
        SIGTERM's signals wait until it is done."""
        signals = {signal.SIGALRM, signal.SIGTERM, signal.SIGINT}
        old = signal.pthread_sigmask(signal.SIG_BLOCK, signals)
        try:
            self._stop()
        finally:
            signal.pthread_sigmask(signal.SIG_SETMASK, old)

    def _stop(self):
        if self.proc is None:
            if self in _active:
                _active.remove(self)
            self._slot.release()
            return
        if self.sock is not None:
            try:
                self.sock.sendall(b"shutdown\r\n")  # LinuxCNC closes the connection as it stops
            except OSError:
                pass
        for sig, grace in ((None, 20), (signal.SIGTERM, 10), (signal.SIGKILL, 5)):
            if sig is not None:
                try:
                    os.killpg(self.proc.pid, sig)
                except OSError:
                    pass
            try:
                self.proc.wait(timeout=grace)
                break
            except subprocess.TimeoutExpired:
                continue
        if self.sock is not None:
            self.sock.close()
            self.sock = None
        _sweep(self.fifo)
        _reap()
        self.leftovers = leftovers(self.fifo)
        self.seconds = time.time() - self._started
        self._logfile.close()
        with open(self.log_path, errors="replace") as f:
            self.log = f.read()
        self.proc = None
        if self in _active:
            _active.remove(self)
        self._slot.release()

