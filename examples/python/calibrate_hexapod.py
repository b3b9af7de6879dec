"""Seed 004 end to end: calibrate the simulated hexapod of `seed004-hexapod-calibration` (the
hexapod-default machine with 9-33 mm joint errors and 6-18 mm strut offsets) from laser-tracker
full poses, compare the errors on held-out poses before and after, and check the paper's figure:
a 540 mm move along x is off by about 12 mm with the nominal controller, < 0.5 mm calibrated.

Usage:
    pkm simulate seed004-hexapod-calibration --out s4
    PYTHONPATH=build/python /usr/bin/python3 examples/python/calibrate_hexapod.py OUT_DIR --data s4

Without --data the measurements are simulated in Python (pkm.simulate, when the module has it).
Writes OUT_DIR/seed004-calibrated.json (and its .hal, .pkmhexkins.hal, .summary.json), and with
matplotlib installed OUT_DIR/holdout.png and OUT_DIR/x_move.png.
"""

import argparse
import csv
import json
import os

import numpy as np

import pkm

POSE = ["l0", "l1", "l2", "l3", "l4", "l5", "x", "y", "z", "a", "b", "c"]


def read_tracker_file(path):
    """A tracker file as (metadata dict, (N, 12) array of l0..l5, x, y, z, a, b, c)."""
    meta, lines = {}, []
    with open(path) as f:
        for line in f:
            if line.startswith("#"):
                key, _, value = line[1:].partition(":")
                meta[key.strip()] = value.strip()
            elif line.strip():
                lines.append(line)
    rows = list(csv.DictReader(lines))
    return meta, np.array([[float(r[c]) for c in POSE] for r in rows])


def load_measurements(data_dir):
    """The fit poses, the held-out poses, the tracker target (tool frame), and the truth."""
    if data_dir is not None:
        meta, poses = read_tracker_file(os.path.join(data_dir, "tracker-pose.csv"))
        _, held = read_tracker_file(os.path.join(data_dir, "tracker-holdout.csv"))
        with open(os.path.join(data_dir, "truth.json")) as f:
            truth = json.load(f)
    elif hasattr(pkm, "simulate"):
        sim = pkm.simulate("seed004-hexapod-calibration")
        meta = sim.metadata["tracker-pose"]
        poses = np.column_stack([sim.tables["tracker-pose"][c] for c in POSE])
        held = np.column_stack([sim.tables["tracker-holdout"][c] for c in POSE])
        truth = sim.truth
    else:
        raise SystemExit("give --data DIR (pkm simulate seed004-hexapod-calibration --out DIR)")
    target = np.array([float(v) for v in meta["smr offset mm"].strip("()").split(",")])
    return poses, held, target, truth


def x_move_error(controller, true_machine, home):
    """Seed 004's positioning test: a 540 mm move along x (10 targets). The controller commands
    its IK, the true machine goes where those strut lengths take it, and an interferometer aligned
    with the travel reads the distance from the start: its error against the commanded distance.
    (A distance, because a calibration from tracker data fixes the machine's world frame only up
    to the rigid motion the data cannot see.)"""
    commands = np.tile(home, (10, 1))
    commands[:, 0] = np.linspace(-270, 270, 10)
    actual, _, _ = true_machine.fk(controller.ik(commands), seed=commands[0])
    travelled = np.linalg.norm(actual[:, :3] - actual[0, :3], axis=1)
    commanded = np.linalg.norm(commands[:, :3] - commands[0, :3], axis=1)
    return commands[:, 0], travelled - commanded


def plot(out_dir, result, x, before, after):
    try:
        import matplotlib
    except ImportError:
        print("matplotlib is not installed: no plots")
        return
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots()
    ax.semilogy(result.holdout_errors_before, "o", label="nominal machine")
    ax.semilogy(result.holdout_errors_after, "s", label="calibrated machine")
    ax.set_xlabel("held-out pose")
    ax.set_ylabel("TCP error (mm)")
    ax.legend()
    fig.savefig(os.path.join(out_dir, "holdout.png"))
    fig, ax = plt.subplots()
    ax.plot(x, before, "o-", label="nominal controller")
    ax.plot(x, after, "s-", label="calibrated controller")
    ax.set_xlabel("x command (mm)")
    ax.set_ylabel("distance error from the start (mm)")
    ax.legend()
    fig.savefig(os.path.join(out_dir, "x_move.png"))
    print(f"plots: {out_dir}/holdout.png, {out_dir}/x_move.png")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("out_dir")
    parser.add_argument("--data", help="the folder `pkm simulate seed004-hexapod-calibration` wrote")
    args = parser.parse_args()
    os.makedirs(args.out_dir, exist_ok=True)
    nominal = pkm.load_machine("hexapod-default")

    # How good could 30 poses be? The planner's choice against a random one.
    plan = pkm.calibration.plan_poses("hexapod-default", count=30, candidates=300)
    print(f"pose planning: {plan.summary}")

    poses, held, target, truth = load_measurements(args.data)
    result = pkm.calibration.hexapod(nominal, poses=poses, holdout=held, frame="tracker",
                                     target_offset=target, raise_on_failure=True)
    print(f"{result.observations['poses']} tracker poses: {result.rank} of "
          f"{result.identifiability['parameters']} unknowns identifiable (condition number "
          f"{result.condition_number:.4g}); {len(result.identifiability['unidentifiable'])} "
          f"directions unseen (the base frame's rigid motion against the tracker's placement)")
    print(f"fitted residual RMS {result.residuals_before['rms']:.4g} -> "
          f"{result.residuals_after['rms']:.4g} mm in {result.iterations} iterations")
    h = result.holdout
    print(f"held-out TCP error ({h['after']['poses']} poses): RMS {h['before']['rms']:.4g} -> "
          f"{h['after']['rms']:.4g} mm, max {h['before']['max']:.4g} -> {h['after']['max']:.4g} mm")
    largest = np.argsort(-np.abs(result.change))[:3]
    for k in largest:
        print(f"  {result.parameter_names[k]}: moved {result.change[k]:+.3f} mm "
              f"(sigma {result.standard_deviation[k]:.2g} mm)")

    # The paper's figure: the 540 mm move along x on the true machine.
    g = truth["true_geometry"]
    true_machine = nominal.with_geometry(base_joints=np.array(g["base"]),
                                         platform_joints=np.array(g["platform"]),
                                         length_offsets=np.array(g["length_offset"]))
    x, before = x_move_error(nominal, true_machine, nominal.home)
    _, after = x_move_error(result.machine, true_machine, nominal.home)
    print(f"540 mm move along x: positioning error {np.abs(before).max():.3g} mm with the nominal "
          f"controller, {np.abs(after).max():.3g} mm calibrated (seed 004: 12 mm before, "
          f"< 0.5 mm after)")

    written = result.save(os.path.join(args.out_dir, "seed004-calibrated.json"), force=True)
    print(f"calibrated machine written: {', '.join(written)}")
    plot(args.out_dir, result, x, before, after)


if __name__ == "__main__":
    main()
