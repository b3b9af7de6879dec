"""Shared by the calibration binding tests (test_calibration.py,
test_calibration_exechon_planning.py): the simulator's files read as arrays, the summary compared
without what differs between runs, and the text `pkm` prints run in a folder."""

import json
import os
import re
import subprocess

import numpy as np

from conftest import column, parse_csv

POSE = ["l0", "l1", "l2", "l3", "l4", "l5", "x", "y", "z", "a", "b", "c"]
GAUGE = ["station", "x_mm", "y_mm", "z_mm", "a_deg", "b_deg", "c_deg", "l0_mm", "l1_mm",
         "l2_mm", "l3_mm", "l4_mm", "l5_mm", "g0_mm", "g1_mm", "g2_mm"]
EXECHON = ["q1", "q2", "q3", "c", "a", "x", "y", "z"]
HYBRID = ["x2", "y2", "xp", "yp", "zp", "x", "y", "z"]


def read_table(path, columns):
    """A simulator file as (metadata dict, (N, len(columns)) array), numbers parsed exactly."""
    meta, lines = {}, []
    with open(path) as f:
        for line in f:
            if line.startswith("#"):
                key, _, value = line[1:].partition(":")
                meta[key.strip()] = value.strip()
            elif line.strip():
                lines.append(line)
    rows = parse_csv("".join(lines))
    return meta, np.column_stack([column(rows, c) for c in columns])


def vector(text):
    """'(x, y, z)' as an array."""
    return np.array([float(v) for v in text.strip("()").split(",")])


def without(doc, *keys):
    """The summary without members that differ between runs or name the inputs."""
    doc = json.loads(json.dumps(doc))
    for part in [doc] + ([doc["hybrid"]] if "hybrid" in doc else []):
        if "solver" in part:
            part["solver"].pop("seconds", None)
        for key in keys:
            part.pop(key, None)
    return doc


def masked(text):
    """A text summary with the solver's wall time masked (as tests/golden/normalise.sh does)."""
    return re.sub(r"(iterations, )[0-9.]+ s", r"\1<T> s", text)


def cli_text(pkm_binary, folder, args):
    """The text `pkm ARGS` prints when run in `folder` (created), which must succeed."""
    folder.mkdir()
    p = subprocess.run([os.path.abspath(pkm_binary), *args], cwd=folder, capture_output=True,
                       text=True)
    assert p.returncode == 0, p.stderr
    return p.stdout

