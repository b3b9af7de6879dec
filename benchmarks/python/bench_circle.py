"""pkm.metrology.circle on 1,000,000 noisy points from memory against scipy (docs/python.md,
"Performance"): the same ring as benchmarks/circle_vs_scipy_whole_process.sh (50 mm radius, 3- and
5-lobe form, 1 µm noise), held in a numpy array. The reference is scipy.optimize.least_squares
(method "lm", analytic Jacobian); pkm with fit="lsc", budget=False does the same work, and the
default (both circles, budgets) is timed too. Runs alternate (scipy, pkm lsc, pkm both, ...); the
medians and the ratio are printed, and the centres and radii compared (within 1e-9 of the
radius). Target: pkm lsc >= 3x scipy.

Usage: PYTHONPATH=build/python /usr/bin/python3 benchmarks/python/bench_circle.py [RUNS]
"""

import os
import statistics
import sys
import time

import numpy as np
from circle_reference import scipy_circle
from make_ring import ring

import pkm


def timed(f):
    start = time.perf_counter()
    out = f()
    return time.perf_counter() - start, out


def main():
    runs = int(sys.argv[1]) if len(sys.argv) > 1 else 7
    xy = ring(1_000_000)
    ref, lsc, both = [], [], []
    for _ in range(runs):
        t, s = timed(lambda: scipy_circle(xy).x)
        ref.append(t)
        t, p = timed(lambda: pkm.metrology.circle(xy, fit="lsc", budget=False))
        lsc.append(t)
        t, _ = timed(lambda: pkm.metrology.circle(xy))
        both.append(t)
    d = max(abs(p.center[0] - s[0]), abs(p.center[1] - s[1]), abs(p.radius - s[2]))
    print(f"machine: {os.cpu_count()} cores; 1,000,000 points in memory, medians of {runs} runs")
    print(f"  scipy least_squares (lm): {statistics.median(ref):.3f} s")
    print(f"  pkm.metrology.circle(fit='lsc', budget=False): {statistics.median(lsc):.3f} s "
          f"-> {statistics.median(ref) / statistics.median(lsc):.1f}x scipy")
    print(f"  pkm.metrology.circle() (both circles, budgets): {statistics.median(both):.3f} s")
    print(f"  centre and radius agree within {d:.2g} mm" + (" (ok)" if d <= 1e-9 * 50 else " (DIFFER)"))
    # For benchmarks/summary.sh: job | pkm s | reference | reference s | target ratio.
    print(f"bench-row|pkm.metrology.circle in Python, 1M points in memory|{statistics.median(lsc)}"
          f"|scipy least_squares|{statistics.median(ref)}|3")
    if d > 1e-9 * 50:
        sys.exit(1)


if __name__ == "__main__":
    main()
