"""The examples in examples/python run headless (plots, when matplotlib is installed, to a
temporary folder)."""

import os
import subprocess
import sys

from conftest import REPO

EXAMPLES = os.path.join(REPO, "examples", "python")


def run_example(name, *args):
    p = subprocess.run([sys.executable, os.path.join(EXAMPLES, name), *args],
                       capture_output=True, text=True, env=dict(os.environ, MPLBACKEND="Agg"))
    assert p.returncode == 0, p.stderr
    return p.stdout


def test_fit_circle(run_cli, tmp_path):
    run_cli(["simulate", "seed003-probe-offset", "--out", str(tmp_path / "s3")])
    out = run_example("fit_circle.py", str(tmp_path / "s3" / "probe_circle_compensated.csv"),
                      str(tmp_path))
    assert "roundness" in out


def test_hexapod_path(tmp_path):
    out = run_example("hexapod_path.py", str(tmp_path))
    assert "FK round trip" in out


def test_gcode_struts(tmp_path):
    out = run_example("gcode_struts.py", str(tmp_path))
    assert "result: all checks pass" in out and "strut lengths" in out
