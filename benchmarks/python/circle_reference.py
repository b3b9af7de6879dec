"""The reference of the circle benchmarks: the least-squares circle by scipy.optimize.least_squares
(method "lm", analytic Jacobian, started from the centroid and the mean distance), as a user would
fit it. As a program it is the whole-process reference of benchmarks/circle_vs_scipy_whole_process.sh:
np.loadtxt of an x,y CSV, the fit, "cx cy r evaluations" printed.

Usage: /usr/bin/python3 benchmarks/python/circle_reference.py POINTS.csv
"""

import sys

import numpy as np
from scipy.optimize import least_squares


def scipy_circle(xy):
    """The fit of an (N, 2) array: scipy's OptimizeResult (x = cx, cy, r; nfev)."""
    x, y = xy[:, 0], xy[:, 1]

    def residual(p):
        return np.hypot(x - p[0], y - p[1]) - p[2]

    def jacobian(p):
        d = np.hypot(x - p[0], y - p[1])
        return np.column_stack(((p[0] - x) / d, (p[1] - y) / d, -np.ones_like(d)))

    start = [x.mean(), y.mean(), np.hypot(x - x.mean(), y - y.mean()).mean()]
    return least_squares(residual, start, jac=jacobian, method="lm")


if __name__ == "__main__":
    fit = scipy_circle(np.loadtxt(sys.argv[1], delimiter=",", skiprows=1))
    print(f"{fit.x[0]:.12f} {fit.x[1]:.12f} {fit.x[2]:.12f} {fit.nfev}")
