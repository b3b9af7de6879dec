#!/usr/bin/python3
"""Runs every G-code program under the given folders through LinuxCNC's rs274 and `pkm gcode
moves` and sorts them by outcome: same motions, different motions, refused by pkm only, accepted
by pkm only (rs274 refuses), refused by both. The motion comparison is the one of
tests/cnc/rs274_compare_test.cpp: rs274's canonical calls rebuilt in machine coordinates (printed
position + G5x + G92 + tool offset, the XY rotation applied, in mm), kind, end point, arc centre,
turns and feed within rs274's printing precision.

With --pkm-ini, an INI's RS274NGC_STARTUP_CODE is put before the program for rs274 (LinuxCNC's
task runs it before every program; the standalone rs274 ignores it); pkm runs it from the INI.

A corpus is any folder of .ngc files, e.g. LinuxCNC's own tests/interp and nc_files (a git
checkout of LinuxCNC, not part of pkm) or /usr/share/linuxcnc/ncfiles. Each program runs in its
own folder (so that subroutine files there are found), with a fresh parameter file; a test.ini
or *.tbl beside it is passed to both programs.

Usage: /usr/bin/python3 benchmarks/gcode_corpus_vs_rs274.py [--pkm build/bin/pkm]
           [--rs274 rs274] [--tool-table T.tbl] [--list] [--json OUT] DIR...
"""
import argparse
import json
import math
import os
import re
import subprocess
import sys
import tempfile

CALL = re.compile(r"^\s*\d+ N\S*\s+(\w+)\((.*)\)\s*$")
HALF_UNIT = 0.5e-4  # rs274 prints 4 decimals
ARC_AXES = {0: (0, 1, 2), 1: (2, 0, 1), 2: (1, 2, 0)}  # plane -> first, second, normal axis


def numbers(args):
    out = []
    for s in args.replace(",", " ").split():
        try:
            out.append(float(s))
        except ValueError:
            pass
    return out


def rs274_moves(text):
    """Motions of rs274's printout in machine coordinates: (kind, end[6], centre[3], turns, feed,
    tol)."""
    scale, plane, rot, feed = 1.0, 0, 0.0, 0.0
    g5x, g92, tlo = [0.0] * 6, [0.0] * 6, [0.0] * 6
    per_rev, spindle, sync = False, 0.0, 0.0  # G95, S, G33/G33.1's K (mm/rev)
    moves = []

    def rate():  # a feed move's rate in mm/min as pkm reports it: F, F*S (G95), K*S (G33)
        return sync * spindle if sync else feed * spindle if per_rev else feed

    for line in text.splitlines():
        m = CALL.match(line)
        if not m:
            continue
        name, args = m.group(1), m.group(2)
        v = numbers(args)
        if name == "USE_LENGTH_UNITS":
            scale = 25.4 if "INCHES" in args else 1.0
        elif name == "SELECT_PLANE":
            plane = 1 if "XZ" in args else 2 if "YZ" in args else 0
        elif name == "SET_XY_ROTATION" and v:
            rot = math.radians(v[0])
        elif name == "SET_G5X_OFFSET" and len(v) >= 7:
            g5x = [v[1 + i] * (scale if i < 3 else 1.0) for i in range(6)]
        elif name == "SET_G92_OFFSET" and len(v) >= 6:
            g92 = [v[i] * (scale if i < 3 else 1.0) for i in range(6)]
        elif name == "USE_TOOL_LENGTH_OFFSET" and len(v) >= 6:
            tlo = [v[i] * (scale if i < 3 else 1.0) for i in range(6)]
        elif name == "SET_FEED_RATE" and v:
            feed = v[0] * scale
        elif name == "SET_FEED_MODE" and len(v) >= 2:
            per_rev = v[1] == 1
        elif name == "SET_SPINDLE_SPEED" and len(v) >= 2:
            spindle = v[1]
        elif name == "START_SPEED_FEED_SYNC" and v:
            sync = abs(v[0]) * scale
        elif name == "STOP_SPEED_FEED_SYNCH":
            sync = 0.0
        elif name == "RIGID_TAP" and len(v) >= 3:  # in to the point, back out to the start
            start = moves[-1][1] if moves else [0.0] * 6
            end = machine(list(v[:3]) + [0.0] * 3, scale, rot, g5x, g92, tlo)
            end[3:6] = start[3:6]
            moves.append(("linear", end, [None] * 3, 0, rate()))
            moves.append(("linear", list(start), [None] * 3, 0, rate()))
        elif name in ("STRAIGHT_TRAVERSE", "STRAIGHT_FEED", "ARC_FEED", "STRAIGHT_PROBE"):
            prog = [0.0] * 6
            centre = [None] * 3
            turns = 0
            if name == "ARC_FEED":
                a = ARC_AXES[plane]
                prog[a[0]], prog[a[1]] = v[0], v[1]
                centre[a[0]], centre[a[1]] = v[2], v[3]
                turns = int(v[4])
                prog[a[2]] = v[5]
                prog[3:6] = v[6:9]
                kind = "arc"
            else:
                prog = v[:6]
                kind = "rapid" if name == "STRAIGHT_TRAVERSE" else "linear"
            moves.append((kind, machine(prog, scale, rot, g5x, g92, tlo),
                          machine_centre(centre, scale, rot, g5x, g92, tlo), turns,
                          None if kind == "rapid" else rate()))
    return moves


def rotate(x, y, rot):
    c, s = math.cos(rot), math.sin(rot)
    return x * c - y * s, x * s + y * c


def machine(prog, scale, rot, g5x, g92, tlo):
    p = [prog[i] * (scale if i < 3 else 1.0) for i in range(6)]
    p = [p[i] + g92[i] for i in range(6)]
    p[0], p[1] = rotate(p[0], p[1], rot)
    return [p[i] + g5x[i] + tlo[i] for i in range(6)]


def machine_centre(centre, scale, rot, g5x, g92, tlo):
    """The arc centre in machine coordinates; axes without a centre stay None."""
    if all(c is None for c in centre):
        return centre
    full = [c if c is not None else 0.0 for c in centre] + [0.0] * 3
    m = machine(full, scale, rot, g5x, g92, tlo)
    return [m[i] if centre[i] is not None else None for i in range(3)]


def pkm_moves(csv_text):
    rows = csv_text.splitlines()[1:]
    out = []
    for r in rows:
        f = r.split(",")
        num = lambda s: None if s in ("", "nan") else float(s)
        out.append((f[1], [float(x) for x in f[2:8]], [num(x) for x in f[8:11]], int(f[11] or 0),
                    num(f[13])))
    return out


def compare(ref, got, inch):
    tol = HALF_UNIT * (25.4 if inch else 1.0) * 4 + 1e-9
    if len(ref) != len(got):
        return "rs274 %d motions, pkm %d" % (len(ref), len(got))
    for k, (r, g) in enumerate(zip(ref, got)):
        if r[0] != g[0]:
            return "motion %d: rs274 %s, pkm %s" % (k + 1, r[0], g[0])
        for i in range(6):
            if abs(r[1][i] - g[1][i]) > tol:
                return "motion %d axis %d: rs274 %.4f, pkm %.4f" % (k + 1, i, r[1][i], g[1][i])
        if r[0] == "arc":
            if r[3] != g[3]:
                return "motion %d: turns %d vs %d" % (k + 1, r[3], g[3])
            for i in range(3):
                if r[2][i] is not None and g[2][i] is not None and abs(r[2][i] - g[2][i]) > tol:
                    return "motion %d centre %d: %.4f vs %.4f" % (k + 1, i, r[2][i], g[2][i])
        if r[4] is not None and g[4] is not None and abs(r[4] - g[4]) > tol * 10:
            return "motion %d feed %.4f vs %.4f" % (k + 1, r[4], g[4])
    return None


def beside(folder, suffix):
    for f in sorted(os.listdir(folder)):
        if f.endswith(suffix):
            return os.path.join(folder, f)
    return None


def startup_code(ini):
    """The INI's RS274NGC_STARTUP_CODE ([RS274NGC], or [EMC] in old files), or None."""
    section = None
    found = {}
    for raw in open(ini, errors="replace"):
        line = raw.strip()
        if line.startswith("[") and line.endswith("]"):
            section = line[1:-1].strip().upper()
        elif "=" in line and not line.startswith("#"):
            key, value = line.split("=", 1)
            if key.strip() == "RS274NGC_STARTUP_CODE" and section in ("RS274NGC", "EMC"):
                found.setdefault(section, value.strip())
    return found.get("RS274NGC", found.get("EMC"))


def with_startup(path, code, work):
    """A copy of program `path` with `code` as its first block (after a leading %): LinuxCNC's
    task runs the INI's start-up code before a program, the standalone rs274 does not."""
    lines = open(path, errors="replace").read().split("\n")
    at = 1 if lines and lines[0].strip().startswith("%") else 0
    out = os.path.join(work, "with_startup.ngc")
    with open(out, "w") as f:
        f.write("\n".join(lines[:at] + [code] + lines[at:]))
    return out


def run_one(path, opts, work):
    folder = os.path.dirname(os.path.abspath(path))
    tbl = opts.tool_table or beside(folder, ".tbl")
    ini = beside(folder, ".ini")
    var = os.path.join(work, "rs274.var")
    open(var, "w").close()
    out = os.path.join(work, "rs274.txt")
    if os.path.exists(out):
        os.remove(out)
    cmd = [opts.rs274, "-v", var]
    if tbl:
        cmd += ["-t", tbl]
    if ini:
        cmd += ["-i", ini]
    program = os.path.abspath(path)
    code = startup_code(ini) if ini and opts.pkm_ini else None
    if code:
        program = with_startup(program, code, work)
    cmd += ["-g", program, out]
    try:
        # rs274 keeps its tool data in $HOME/.tool.mmap: a HOME of our own, so that runs in
        # parallel (ctest -j) do not clobber each other's tool table.
        r = subprocess.run(cmd, cwd=folder, stdin=subprocess.DEVNULL, capture_output=True,
                           text=True, errors="replace", timeout=30, env=dict(os.environ, HOME=work))
        ref_ok = r.returncode == 0
        ref_text = open(out, errors="replace").read() if os.path.exists(out) else ""
        ref_err = (r.stdout + r.stderr).strip().replace("executing", "").strip()
    except subprocess.TimeoutExpired:
        ref_ok, ref_text, ref_err = False, "", "timeout"
    csv = os.path.join(work, "pkm.csv")
    pcmd = [opts.pkm, "gcode", "moves", os.path.abspath(path), "--out", csv, "--force"]
    if tbl:
        pcmd += ["--tool-table", tbl, "--tool-units", opts.tool_units]
    if ini and opts.pkm_ini:
        pcmd += ["--ini", ini]
    try:
        p = subprocess.run(pcmd, cwd=folder, stdin=subprocess.DEVNULL, capture_output=True,
                           text=True, errors="replace", timeout=30)
        got_ok, got_err = p.returncode == 0, p.stderr.strip()
        if p.returncode not in (0, 2):
            got_err = "CRASH (exit %d) %s" % (p.returncode, got_err)
    except subprocess.TimeoutExpired:
        got_ok, got_err = False, "HANG (timeout)"
    if ref_ok and got_ok:
        inch = "CANON_UNITS_INCHES" in ref_text
        diff = compare(rs274_moves(ref_text), pkm_moves(open(csv).read()), inch)
        return ("same", "") if diff is None else ("differ", diff)
    if ref_ok:
        return "refused by pkm", got_err.splitlines()[-1] if got_err else ""
    if got_ok:
        return "accepted by pkm only", ref_err.splitlines()[0] if ref_err else ""
    return "refused by both", ""


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("dirs", nargs="+")
    ap.add_argument("--pkm", default="build/bin/pkm")
    ap.add_argument("--rs274", default="rs274")
    ap.add_argument("--tool-table", default=None)
    ap.add_argument("--tool-units", default="inch", help="units of the tool tables (rs274: inch)")
    ap.add_argument("--pkm-ini", action="store_true", help="pass a folder's .ini to pkm too")
    ap.add_argument("--list", action="store_true", help="print every program's outcome")
    ap.add_argument("--json", default=None)
    opts = ap.parse_args()
    opts.pkm = os.path.abspath(opts.pkm)
    if opts.tool_table:
        opts.tool_table = os.path.abspath(opts.tool_table)
    files = sorted(os.path.join(d, f) for top in opts.dirs for d, _, fs in os.walk(top)
                   for f in fs if f.endswith(".ngc"))
    results = {}
    with tempfile.TemporaryDirectory() as work:
        for f in files:
            results[f] = run_one(f, opts, work)
    counts = {}
    for outcome, _ in results.values():
        counts[outcome] = counts.get(outcome, 0) + 1
    if opts.list:
        for f, (outcome, why) in results.items():
            print("%-22s %s  %s" % (outcome, f, why[:160]))
    ran = sum(counts.get(k, 0) for k in ("same", "differ", "refused by pkm"))
    print("programs: %d; rs274 runs %d of them" % (len(files), ran))
    for k in ("same", "differ", "refused by pkm", "accepted by pkm only", "refused by both"):
        print("  %-22s %d" % (k, counts.get(k, 0)))
    if ran:
        print("  same motions on %.1f %% of the programs rs274 runs" % (100.0 * counts.get("same", 0) / ran))
    if opts.json:
        with open(opts.json, "w") as out:
            json.dump({"counts": counts, "programs": results}, out, indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main())
