"""Writes the measured-like ring of the circle benchmarks: N points (default 1,000,000) of a 50 mm
ring about (12.3, -4.56) with a 3- and 5-lobe form of 10 um and 1 um noise, 6 decimals as a CMM
writes them, header x,y, seeded (20261126) so every run reads the same file.

Usage: /usr/bin/python3 benchmarks/python/make_ring.py OUT.csv [N]
"""

import sys

import numpy as np


def ring(n):
    """The ring's points as an (n, 2) array (full precision)."""
    rng = np.random.default_rng(20261126)
    t = rng.uniform(0.0, 2.0 * np.pi, n)
    r = 50.0 + 0.005 * np.cos(3 * t + 0.4) + 0.002 * np.sin(5 * t) + rng.normal(0.0, 0.001, n)
    return np.column_stack([12.3 + r * np.cos(t), -4.56 + r * np.sin(t)])


def main(path, n):
    with open(path, "w") as f:
        f.write("x,y\n")
        np.savetxt(f, ring(n), fmt="%.6f", delimiter=",")


if __name__ == "__main__":
    main(sys.argv[1], int(sys.argv[2]) if len(sys.argv) > 2 else 1_000_000)
