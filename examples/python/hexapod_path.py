"""A hexapod path: inverse kinematics of a helix, limit checks, forward kinematics back, and the
strut lengths plotted (when matplotlib is installed) to OUT_DIR/struts.png.

Usage: PYTHONPATH=build/python /usr/bin/python3 examples/python/hexapod_path.py [OUT_DIR]
"""

import sys

import numpy as np

import pkm


def main(out_dir=None):
    machine = pkm.load_machine("hexapod-default")
    t = np.linspace(0, 4 * np.pi, 2000)
    poses = np.tile(machine.home, (len(t), 1))
    poses[:, 0] += 60 * np.cos(t)
    poses[:, 1] += 60 * np.sin(t)
    poses[:, 2] += 5 * t
    poses[:, 5] += 10 * np.sin(t / 2)
    lengths, status = machine.ik(poses, status=True)
    check = machine.check(poses)
    back, fk_status, iterations = machine.fk(lengths)
    print(f"{len(poses)} poses, {np.count_nonzero(status != 'ok')} outside a limit; "
          f"smallest stroke margin {check['stroke_margin'].min():.3f} {machine.unit}; "
          f"FK round trip {np.abs(back - poses).max():.2e}, {iterations.mean():.1f} iterations/row")
    if out_dir is not None:
        try:
            import matplotlib
        except ImportError:
            print("matplotlib is not installed: no plot")
            return lengths
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt

        fig, ax = plt.subplots()
        for i in range(6):
            ax.plot(np.degrees(t), lengths[:, i], label=f"l{i}")
        ax.set_xlabel("helix angle (deg)")
        ax.set_ylabel(f"strut reading ({machine.unit})")
        ax.legend()
        fig.savefig(f"{out_dir}/struts.png")
        print(f"plot: {out_dir}/struts.png")
    return lengths


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else None)
