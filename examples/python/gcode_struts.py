"""A G-code program run through a hexapod: the strut lengths over time plotted (when matplotlib is
installed) to OUT_DIR/gcode_struts.png, and the check report printed.

Usage: PYTHONPATH=build/python /usr/bin/python3 examples/python/gcode_struts.py [OUT_DIR [PROGRAM]]

PROGRAM defaults to examples/gcode/hexapod_contour.ngc (a rounded square, a helix and a tilted
pass on the built-in hexapod). The same run on the command line:
``pkm gcode run examples/gcode/hexapod_contour.ngc --machine hexapod-default``.
"""

import os
import sys

import pkm

HERE = os.path.dirname(os.path.abspath(__file__))
DEFAULT_PROGRAM = os.path.join(HERE, "..", "gcode", "hexapod_contour.ngc")


def main(out_dir=None, program=DEFAULT_PROGRAM):
    machine = pkm.load_machine("hexapod-default")
    run = pkm.gcode.run(machine, program)
    # Strut readings are lengths minus each strut's length offset (docs/conventions.md).
    lengths = run.joints + machine.length_offsets
    print(run.text, end="")
    print(f"{run.total_points} points over {run.t[-1]:.2f} s; strut lengths "
          f"{lengths.min():.1f} .. {lengths.max():.1f} {machine.unit}")
    if out_dir is not None:
        try:
            import matplotlib
        except ImportError:
            print("matplotlib is not installed: no plot")
            return run
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt

        fig, ax = plt.subplots()
        for i, name in enumerate(run.joint_names):
            ax.plot(run.t, lengths[:, i], label=name)
        ax.set_xlabel("time (s)")
        ax.set_ylabel(f"strut length ({machine.unit})")
        ax.set_title(os.path.basename(program))
        ax.legend()
        fig.savefig(os.path.join(out_dir, "gcode_struts.png"))
        print(f"plot: {os.path.join(out_dir, 'gcode_struts.png')}")
    return run


if __name__ == "__main__":
    main(*sys.argv[1:3])
