#!/usr/bin/python3
"""Cutter radius compensation against LinuxCNC's rs274, on programs no one wrote by hand: seeded
random contours (lines, R and IJK arcs, full circles, Z moves, G0 corners, G41/G42 with the
spindle tool) and tangent contours (rounded rectangles in G17 and G18, G41.1/G42.1 diameters,
both senses). Each program runs through rs274 and `pkm gcode moves` as
benchmarks/gcode_corpus_vs_rs274.py runs them; every program must give the same motions, or be
refused by both on the same line. Skipped (exit 77) without rs274 (scripts/fetch-linuxcnc.sh).

Usage: /usr/bin/python3 tests/cnc/cutter_comp_vs_rs274.py PKM [--seed S] [--programs N]
"""
import argparse
import importlib.util
import math
import os
import random
import re
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
LCNC = os.path.join(ROOT, ".cache/linuxcnc/usr")
RS274 = os.path.join(LCNC, "bin/rs274")
TOOLS = os.path.join(LCNC, "share/doc/linuxcnc/examples/sample-configs/common/tool.tbl")


def load_corpus_module():
    spec = importlib.util.spec_from_file_location(
        "corpus", os.path.join(ROOT, "benchmarks/gcode_corpus_vs_rs274.py"))
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def random_contour(rng):
    """Lines, arcs, Z moves and full circles anywhere: many are refused (gouging, radii)."""
    out = ["G21 G17 G90 G40 F500", "T%d M6" % rng.choice([1, 2, 3]), "G0 X-30 Y-30 Z1",
           "%s G1 X0 Y0" % rng.choice(["G41", "G42"])]
    x = y = 0.0
    for _ in range(rng.randint(2, 8)):
        k = rng.random()
        nx, ny = round(rng.uniform(-20, 40), 3), round(rng.uniform(-20, 40), 3)
        if k < 0.5:
            z = " Z%g" % round(rng.uniform(-2, 1), 2) if rng.random() < 0.2 else ""
            out.append("G%d X%g Y%g%s" % (rng.choice([0, 1, 1, 1]), nx, ny, z))
        elif k < 0.8:
            d = math.hypot(nx - x, ny - y)
            if d < 1e-3:
                continue
            r = round(d / 2 * rng.uniform(1.0, 3.0), 3) * (-1 if rng.random() < 0.3 else 1)
            out.append("G%d X%g Y%g R%g" % (rng.choice([2, 3]), nx, ny, r))
        elif k < 0.9:
            out.append("G1 Z%g" % round(rng.uniform(-2, 1), 2))
            nx, ny = x, y
        else:
            out.append("G%d I%g J%g" % (rng.choice([2, 3]), round(rng.uniform(-10, 10), 3),
                                        round(rng.uniform(-10, 10), 3)))
            nx, ny = x, y
        x, y = nx, ny
    out.append("G40 G1 X%g Y%g" % (round(rng.uniform(-30, 50), 2), round(rng.uniform(-30, 50), 2)))
    return "\n".join(out + ["M2"]) + "\n"


def tangent_contour(rng):
    """A rounded rectangle: tangent line-arc and arc-line joints, convex or concave for the tool."""
    r = round(rng.uniform(0.5, 8), 3)
    w, h = round(rng.uniform(2 * r + 0.1, 40), 3), round(rng.uniform(2 * r + 0.1, 30), 3)
    side = rng.choice(["G41", "G42", "G41.1 D%g" % round(rng.uniform(0.2, 6), 3),
                       "G42.1 D%g" % round(rng.uniform(0.2, 6), 3)])
    plane = rng.choice(["G17", "G17", "G18"])
    a, b, pa, pb = ("X", "Y", "I", "J") if plane == "G17" else ("Z", "X", "K", "I")
    ccw = rng.random() < 0.5
    pts = [(r, 0), (w - r, 0), (w, r), (w, h - r), (w - r, h), (r, h), (0, h - r), (0, r), (r, 0)]
    centres = [None, (w - r, r), None, (w - r, h - r), None, (r, h - r), None, (r, r)]
    if not ccw:
        pts = [(p, -q) for p, q in pts]
        centres = [None if c is None else (c[0], -c[1]) for c in centres]
    out = ["G21 G90 G40 F500 " + plane, "T%d M6" % rng.choice([1, 2, 3]), "G0 X-30 Y-30 Z-30",
           "%s G1 %s0 %s%g" % (side, a, b, -r if rng.random() < 0.5 else 0),
           "G1 %s%g %s%g" % (a, pts[0][0], b, pts[0][1])]
    for i in range(1, len(pts)):
        c, (px, py), (qx, qy) = centres[i - 1], pts[i - 1], pts[i]
        if c is None:
            out.append("G1 %s%g %s%g" % (a, qx, b, qy))
            continue
        g = "G3" if ccw == (plane == "G17") else "G2"  # G18's sense is seen from +Y
        if rng.random() < 0.5:
            out.append("%s %s%g %s%g R%g" % (g, a, qx, b, qy, r))
        else:
            out.append("%s %s%g %s%g %s%g %s%g" % (g, a, qx, b, qy, pa, round(c[0] - px, 6), pb,
                                                   round(c[1] - py, 6)))
    out.append("G40 G1 %s-20 %s-20" % (a, b))
    return "\n".join(out + ["M2"]) + "\n"


def refused_lines(path, work):
    """The line rs274 refuses (it echoes the block after its message) and the one pkm names."""
    r = subprocess.run([RS274, "-t", TOOLS, "-g", path, os.path.join(work, "x.txt")],
                       cwd=os.path.dirname(path), capture_output=True, text=True,
                       stdin=subprocess.DEVNULL, env=dict(os.environ, HOME=work))
    lines = [l for l in (r.stdout + r.stderr).splitlines() if l.strip() and l.strip() != "executing"]
    echo = lines[1].strip() if len(lines) > 1 else None
    source = open(path).read().splitlines()
    rs = [i + 1 for i, l in enumerate(source) if l.strip() == echo]
    return rs


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("pkm")
    ap.add_argument("--seed", type=int, default=39)
    ap.add_argument("--programs", type=int, default=80)
    args = ap.parse_args()
    if not (os.path.exists(RS274) and os.path.exists(TOOLS)):
        print("rs274 not installed (scripts/fetch-linuxcnc.sh): skipped")
        return 77
    corpus = load_corpus_module()
    opts = argparse.Namespace(pkm=os.path.abspath(args.pkm), rs274=RS274, tool_table=TOOLS,
                              tool_units="inch", pkm_ini=False)
    os.environ["LD_LIBRARY_PATH"] = os.path.join(LCNC, "lib")
    rng = random.Random(args.seed)
    counts, bad = {}, []
    with tempfile.TemporaryDirectory() as work:
        for k in range(args.programs):
            text = tangent_contour(rng) if rng.random() < 0.5 else random_contour(rng)
            path = os.path.join(work, "p%03d.ngc" % k)
            with open(path, "w") as f:
                f.write(text)
            outcome, why = corpus.run_one(path, opts, work)
            if outcome == "refused by both":
                p = subprocess.run([opts.pkm, "gcode", "moves", path, "--tool-table", TOOLS,
                                    "--tool-units", "inch"], capture_output=True, text=True)
                m = re.search(r":(\d+): ", p.stderr)
                if not m or int(m.group(1)) not in refused_lines(path, work):
                    outcome, why = "refused on another line", p.stderr.strip()
            counts[outcome] = counts.get(outcome, 0) + 1
            if outcome not in ("same", "refused by both"):
                bad.append("%s: %s\n%s%s" % (outcome, why, text, "-" * 40))
    print("cutter compensation vs rs274, seed %d: %s" % (args.seed, counts))
    for b in bad:
        print(b)
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
