"""Fit a circle to the points of a CSV file (header x,y) with pkm.metrology.circle.

Prints the least-squares centre and radius and both roundness values, and, when matplotlib is
installed, plots the points and the fitted circle to OUT_DIR/circle.png.

Usage: PYTHONPATH=build/python /usr/bin/python3 examples/python/fit_circle.py POINTS.csv [OUT_DIR]
(`pkm simulate seed003-probe-offset --out s3` writes s3/probe_circle_compensated.csv.)
"""

import sys

import numpy as np

import pkm


def main(csv_path, out_dir=None):
    with open(csv_path) as f:  # pkm's files start with '# key: value' lines
        lines = [line for line in f if not line.startswith("#")]
    table = np.genfromtxt(lines, delimiter=",", names=True)
    xy = np.column_stack([table["x"], table["y"]])
    fit = pkm.metrology.circle(xy)
    print(f"centre {fit.center}, radius {fit.radius:.6f}")
    print(f"roundness: least squares {fit.roundness_lsc * 1e3:.3f} um, "
          f"minimum zone {fit.roundness_mzc * 1e3:.3f} um")
    if out_dir is not None:
        try:
            import matplotlib
        except ImportError:
            print("matplotlib is not installed: no plot")
            return fit
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt

        t = np.linspace(0, 2 * np.pi, 361)
        fig, ax = plt.subplots()
        ax.plot(xy[:, 0], xy[:, 1], ".", label="points")
        ax.plot(fit.center[0] + fit.radius * np.cos(t), fit.center[1] + fit.radius * np.sin(t),
                label="least-squares circle")
        ax.set_aspect("equal")
        ax.set_xlabel("x (mm)")
        ax.set_ylabel("y (mm)")
        ax.set_title(f"roundness {fit.roundness_lsc * 1e3:.2f} um (least squares)")
        ax.legend()
        fig.savefig(f"{out_dir}/circle.png")
        print(f"plot: {out_dir}/circle.png")
    return fit


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2] if len(sys.argv) > 2 else None)
