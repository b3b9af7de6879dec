"""Benchmarks of the Python bindings (docs/python.md, "Performance").

1. Hexapod.ik on 1,000,000 poses against a straightforward vectorised numpy implementation
   (rotation matrices by broadcasting, np.linalg.norm), same results checked.
2. Hexapod.fk on a 100,000-row path against `pkm hexapod fk` on the same readings (whole
   process, CSV in and out) when PKM_BINARY is set.

Runs alternate (A, B, A, B, ...) and the median of each is reported, for a loaded machine.

Usage: PYTHONPATH=build/python [PKM_BINARY=build/bin/pkm] /usr/bin/python3 benchmarks/python/bench_hexapod.py [RUNS]
"""

import os
import subprocess
import sys
import tempfile
import time

import numpy as np

import pkm


def numpy_ik(machine, poses):
    """Strut readings |p + R a_i - b_i| - offset_i with R = Rz(c) Ry(b) Rx(a), in numpy."""
    a, b, c = np.radians(poses[:, 3]), np.radians(poses[:, 4]), np.radians(poses[:, 5])
    ca, sa, cb, sb, cc, sc = np.cos(a), np.sin(a), np.cos(b), np.sin(b), np.cos(c), np.sin(c)
    R = np.empty((len(poses), 3, 3))
    R[:, 0, 0] = cc * cb
    R[:, 0, 1] = cc * sb * sa - sc * ca
    R[:, 0, 2] = cc * sb * ca + sc * sa
    R[:, 1, 0] = sc * cb
    R[:, 1, 1] = sc * sb * sa + cc * ca
    R[:, 1, 2] = sc * sb * ca - cc * sa
    R[:, 2, 0] = -sb
    R[:, 2, 1] = cb * sa
    R[:, 2, 2] = cb * ca
    platform = machine.platform_joints - machine.tool_offset  # (6, 3), no spindle offset
    legs = poses[:, None, :3] + np.einsum("nij,kj->nki", R, platform) - machine.base_joints
    return np.linalg.norm(legs, axis=2) - machine.length_offsets


def timed(f):
    t = time.perf_counter()
    out = f()
    return time.perf_counter() - t, out


def path(machine, n):
    t = np.linspace(0, 1, n)[:, None]
    amplitude = np.array([40, 40, 30, 5, 5, 10.0])
    return machine.home + amplitude * np.sin(2 * np.pi * (3 * t + np.arange(6) / 6))


def main(runs):
    machine = pkm.load_machine("hexapod-default")
    rng = np.random.default_rng(1)
    poses = machine.home + rng.uniform(-1, 1, (1_000_000, 6)) * [50, 50, 30, 8, 8, 15]
    np.testing.assert_allclose(machine.ik(poses[:1000]), numpy_ik(machine, poses[:1000]), atol=1e-9)
    ik_pkm, ik_np = [], []
    for _ in range(runs):
        ik_pkm.append(timed(lambda: machine.ik(poses))[0])
        ik_np.append(timed(lambda: numpy_ik(machine, poses))[0])
    a, b = np.median(ik_pkm), np.median(ik_np)
    print(f"ik 1,000,000 poses: pkm {a * 1e3:.1f} ms ({a * 1e3:.0f} ns/pose), "
          f"numpy {b * 1e3:.1f} ms, speed-up {b / a:.1f}x (medians of {runs})")

    lengths = machine.ik(path(machine, 100_000))
    binary = os.environ.get("PKM_BINARY")
    fk_pkm, fk_cli = [], []
    with tempfile.TemporaryDirectory() as tmp:
        csv = os.path.join(tmp, "l.csv")
        if binary:
            np.savetxt(csv, lengths, delimiter=",", header="l0,l1,l2,l3,l4,l5", comments="",
                       fmt="%.17g")
        for _ in range(runs):
            fk_pkm.append(timed(lambda: machine.fk(lengths))[0])
            if binary:
                fk_cli.append(timed(lambda: subprocess.run(
                    [binary, "hexapod", "fk", "-l", csv], stdout=subprocess.DEVNULL, check=True))[0])
    poses, status, _ = machine.fk(lengths)
    assert (status == "ok").all()
    a = np.median(fk_pkm)
    line = f"fk 100,000-row path: Python {a * 1e3:.1f} ms ({a * 1e9 / 1e5:.0f} ns/row)"
    if fk_cli:
        b = np.median(fk_cli)
        line += f", pkm hexapod fk (whole process) {b * 1e3:.1f} ms, ratio {a / b:.2f}"
    print(line + f" (medians of {runs})")


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 5)
