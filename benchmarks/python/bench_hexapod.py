"""Benchmarks of the Python bindings (docs/python.md, "Performance").

1. Hexapod.ik on 1,000,000 poses against a straightforward vectorised numpy implementation
   (rotation matrices by broadcasting, np.linalg.norm), same results checked. Target: >= 5x.
2. Hexapod.ik per pose against the C++ benchmark BM_HexapodIk of bench_kinematics (Google
   Benchmark, one pose per call; a build with -DPKM_BUILD_BENCHMARKS=ON) when PKM_BENCH_KINEMATICS
   names it, and against the whole `pkm hexapod ik` process on the same poses (CSV in and out)
   when PKM_BINARY is set. Target: within 1.5x of the C++ benchmark.
3. Hexapod.fk on a 100,000-row path against `pkm hexapod fk` on the same readings (whole
   process, CSV in and out) when PKM_BINARY is set. Target: within 1.5x.

Runs alternate (A, B, A, B, ...) and the median of each is reported with its spread (min..max),
for a machine that other jobs load; ratios are taken within a run (measurements made back to
back) and their median reported. Within a run, each binding call, numpy's IK, the C++ benchmark
and the FK process are timed 3 times and the shortest taken (timeit's rule: the least disturbed;
the same rule for pkm and numpy); the IK process once. The C++ benchmark cycles through 10,000 poses of a smooth path that stay in
the cache, so Python is also timed on those very poses (100 calls of 10,000): that ratio is the
binding's cost alone, without the memory traffic of 1,000,000 poses (48 MB in, 48 MB out) and
the larger angles of the random poses (dearer sin and cos).

Usage: PYTHONPATH=build/python [PKM_BINARY=build/bin/pkm] \
           [PKM_BENCH_KINEMATICS=build/bin/bench_kinematics] \
           /usr/bin/python3 benchmarks/python/bench_hexapod.py [RUNS]
"""

import json
import os
import subprocess
import sys
import tempfile
import time

import numpy as np

import pkm

IK_POSES = 1_000_000
CACHED_POSES, CACHED_CALLS = 10_000, 100  # the C++ benchmark's poses fit in the cache too
FK_ROWS = 100_000
BEST_OF = 3  # per run, the shortest of 3 timings of each binding call and C++ repetition


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
    f()
    return time.perf_counter() - t


def stats(times, scale=1.0):
    """'median (min..max)' of `times` x scale."""
    t = np.asarray(times) * scale
    return f"{np.median(t):.1f} ({t.min():.1f}..{t.max():.1f})"


def path(machine, n):
    t = np.linspace(0, 1, n)[:, None]
    amplitude = np.array([40, 40, 30, 5, 5, 10.0])
    return machine.home + amplitude * np.sin(2 * np.pi * (3 * t + np.arange(6) / 6))


def best(f, k=BEST_OF):
    """The shortest of `k` timings of f (the least disturbed by other jobs)."""
    return min(timed(f) for _ in range(k))


def benchmark_path():
    """BM_HexapodIk's poses (benchmarks/bench_kinematics.cpp, PathFixture): 10,000 poses of a
    smooth path about home of LinuxCNC's sim hexapod (the built-in hexapod-linuxcnc-sim, the
    same geometry as the benchmark's linuxcncSimModel), angles in degrees. The IK's cost depends
    on the angles (glibc's sin and cos are cheaper below 0.126 rad), so the per-pose comparison
    uses the very same poses."""
    machine = pkm.load_machine("hexapod-linuxcnc-sim")
    t = 2 * np.pi * np.arange(CACHED_POSES) / CACHED_POSES
    poses = np.tile(machine.home, (CACHED_POSES, 1))
    poses[:, 0] += 3 * np.sin(t)
    poses[:, 1] += 3 * (1 - np.cos(t))
    poses[:, 2] += np.sin(2 * t)
    poses[:, 3] += np.degrees(0.15 * np.sin(t))
    poses[:, 4] += np.degrees(0.12 * np.sin(3 * t))
    poses[:, 5] += np.degrees(0.2 * np.sin(t))
    return machine, poses


def cxx_ik_ns(bench):
    """BM_HexapodIk's time per call, ns (one pose): the shortest of BEST_OF repetitions of
    bench_kinematics (each the mean over its iterations), from its JSON output."""
    p = subprocess.run([bench, "--benchmark_filter=BM_HexapodIk$", "--benchmark_format=json",
                        "--benchmark_min_time=0.2", f"--benchmark_repetitions={BEST_OF}"],
                       capture_output=True, text=True, check=True)
    runs = [b for b in json.loads(p.stdout)["benchmarks"] if b.get("run_type") == "iteration"]
    assert runs and all(b["time_unit"] == "ns" for b in runs)
    return min(b["real_time"] for b in runs)


def write_csv(path, header, rows):
    np.savetxt(path, rows, delimiter=",", header=header, comments="", fmt="%.17g")


def bench_ik(machine, runs, binary, bench):
    rng = np.random.default_rng(1)
    poses = machine.home + rng.uniform(-1, 1, (IK_POSES, 6)) * [50, 50, 30, 8, 8, 15]
    np.testing.assert_allclose(machine.ik(poses[:1000]), numpy_ik(machine, poses[:1000]),
                               atol=1e-9)
    sim, cached = benchmark_path()
    py_t, np_t, cached_t, cxx_t, cli_t = [], [], [], [], []
    with tempfile.TemporaryDirectory() as tmp:
        csv = os.path.join(tmp, "poses.csv")
        if binary:
            write_csv(csv, "x,y,z,a,b,c", poses)
        for _ in range(runs):  # each run measures all, back to back, so the load is alike
            py_t.append(best(lambda: machine.ik(poses)))
            np_t.append(best(lambda: numpy_ik(machine, poses)))
            cached_t.append(best(lambda: [sim.ik(cached) for _ in range(CACHED_CALLS)]))
            if bench:
                cxx_t.append(cxx_ik_ns(bench))
            if binary:
                cli_t.append(timed(lambda: subprocess.run(
                    [binary, "hexapod", "ik", "-p", csv], stdout=subprocess.DEVNULL, check=True)))
    py_ns = np.array(py_t) * 1e9 / IK_POSES
    cached_ns = np.array(cached_t) * 1e9 / (CACHED_POSES * CACHED_CALLS)
    speed_up = np.array(np_t) / np.array(py_t)
    print(f"ik {IK_POSES:,} poses: pkm {stats(py_t, 1e3)} ms, numpy {stats(np_t, 1e3)} ms, "
          f"speed-up {np.median(speed_up):.1f}x ({speed_up.min():.1f}..{speed_up.max():.1f}; "
          f"medians (min..max) of {runs} runs)")
    # For benchmarks/summary.sh: job | pkm s | reference | reference s | target ratio.
    print(f"bench-row|Hexapod.ik in Python, {IK_POSES:,} poses|{np.median(py_t)}|numpy (vectorised)"
          f"|{np.median(np_t)}|10")
    line = (f"ik per pose: Python {stats(py_ns)} ns on {IK_POSES:,} poses, {stats(cached_ns)} ns "
            f"on the C++ benchmark's {CACHED_POSES:,} ({CACHED_CALLS} calls)")
    if cxx_t:
        ratio, cached_ratio = py_ns / np.array(cxx_t), cached_ns / np.array(cxx_t)
        line += (f"; C++ BM_HexapodIk {stats(cxx_t)} ns; ratio (same run) {np.median(ratio):.2f} "
                 f"({ratio.min():.2f}..{ratio.max():.2f}), same poses {np.median(cached_ratio):.2f} "
                 f"({cached_ratio.min():.2f}..{cached_ratio.max():.2f})")
    if cli_t:
        line += (f"; whole `pkm hexapod ik` process {np.median(cli_t) * 1e9 / IK_POSES:.0f} ns "
                 f"({stats(cli_t, 1e3)} ms)")
    print(line)


def bench_fk(machine, runs, binary):
    lengths = machine.ik(path(machine, FK_ROWS))
    fk_py, fk_cli = [], []
    with tempfile.TemporaryDirectory() as tmp:
        csv = os.path.join(tmp, "l.csv")
        if binary:
            write_csv(csv, "l0,l1,l2,l3,l4,l5", lengths)
        for _ in range(runs):
            fk_py.append(best(lambda: machine.fk(lengths)))
            if binary:
                fk_cli.append(best(lambda: subprocess.run(
                    [binary, "hexapod", "fk", "-l", csv], stdout=subprocess.DEVNULL, check=True)))
    _, status, _ = machine.fk(lengths)
    assert (status == "ok").all()
    a = np.median(fk_py)
    line = (f"fk {FK_ROWS:,}-row path: Python {stats(fk_py, 1e3)} ms "
            f"({a * 1e9 / FK_ROWS:.0f} ns/row)")
    if fk_cli:
        ratio = np.array(fk_py) / np.array(fk_cli)
        line += (f", pkm hexapod fk (whole process) {stats(fk_cli, 1e3)} ms, ratio (same run) "
                 f"{np.median(ratio):.2f} ({ratio.min():.2f}..{ratio.max():.2f})")
    print(line + f" (medians (min..max) of {runs})")


def main(runs):
    machine = pkm.load_machine("hexapod-default")
    binary = os.environ.get("PKM_BINARY")
    bench = os.environ.get("PKM_BENCH_KINEMATICS")
    bench_ik(machine, runs, binary, bench)
    bench_fk(machine, runs, binary)


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 5)
