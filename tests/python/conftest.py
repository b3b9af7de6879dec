"""Shared fixtures of the Python binding tests: the pkm program (PKM_BINARY) and a runner that
returns its standard output, so every binding is checked against the command line."""

import csv
import io
import os
import subprocess

import numpy as np
import pytest

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

# The calibration tests' shared helpers assert too: with pytest's messages.
pytest.register_assert_rewrite("calibration_helpers")


@pytest.fixture(scope="session")
def pkm_binary():
    path = os.environ.get("PKM_BINARY")
    if not path or not os.path.exists(path):
        pytest.skip("PKM_BINARY is not set: the CLI comparisons need the pkm program")
    return os.path.abspath(path)


@pytest.fixture(scope="session")
def run_cli(pkm_binary):
    """run_cli(args, stdin=None) -> stdout of `pkm ARGS` (fails the test on a non-zero exit)."""

    def run(args, stdin=None, check=True):
        p = subprocess.run([pkm_binary, *args], input=stdin, capture_output=True, text=True)
        if check:
            assert p.returncode == 0, p.stderr
        return p

    return run


@pytest.fixture(scope="session")
def s4(run_cli, tmp_path_factory):
    """The simulator's seed004-hexapod-calibration files (simulated once per run)."""
    out = tmp_path_factory.mktemp("s4") / "sim"
    run_cli(["simulate", "seed004-hexapod-calibration", "--out", str(out)])
    return out


@pytest.fixture(scope="session")
def ex(run_cli, tmp_path_factory):
    """The simulator's exechon-calibration files (simulated once per run)."""
    out = tmp_path_factory.mktemp("ex") / "sim"
    run_cli(["simulate", "exechon-calibration", "--out", str(out)])
    return out


def csv_text(header, rows):
    """A CSV text with `header` and rows written with repr (round-trip exact)."""
    out = [",".join(header)]
    for r in rows:
        out.append(",".join(repr(float(v)) for v in r))
    return "\n".join(out) + "\n"


def parse_csv(text):
    """The rows of a CSV text as a list of dicts of strings."""
    return list(csv.DictReader(io.StringIO(text)))


def column(rows, name):
    """A numeric column (empty fields as NaN)."""
    return np.array([float(r[name]) if r[name] != "" else np.nan for r in rows])
