"""The examples in examples/python run headless, and their plots (matplotlib, Debian's
python3-matplotlib) are written as PNG files to a temporary folder and are real pictures: a PNG of
at least 400 x 300 pixels with drawn content (many colours, not a blank canvas)."""

import os
import subprocess
import sys

import numpy as np
import pytest

from conftest import REPO

EXAMPLES = os.path.join(REPO, "examples", "python")
PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"
MIN_WIDTH, MIN_HEIGHT = 400, 300  # pixels; matplotlib's default figure is 640 x 480
MIN_COLOURS = 16  # lines, text and axes anti-aliased: hundreds; a blank canvas: 1


def run_example(name, *args):
    p = subprocess.run([sys.executable, os.path.join(EXAMPLES, name), *args],
                       capture_output=True, text=True, env=dict(os.environ, MPLBACKEND="Agg"))
    assert p.returncode == 0, p.stderr
    return p.stdout


def assert_plot(path):
    """`path` is a PNG file with a drawn plot in it."""
    pytest.importorskip("matplotlib", reason="python3-matplotlib draws the examples' plots")
    import matplotlib.image

    assert os.path.exists(path), path
    with open(path, "rb") as f:
        assert f.read(8) == PNG_SIGNATURE, path
    image = matplotlib.image.imread(path)
    assert image.shape[0] >= MIN_HEIGHT and image.shape[1] >= MIN_WIDTH, image.shape
    colours = np.unique(image.reshape(-1, image.shape[2]), axis=0)
    assert len(colours) >= MIN_COLOURS, f"{path}: {len(colours)} colours"


def test_fit_circle(run_cli, tmp_path):
    run_cli(["simulate", "seed003-probe-offset", "--out", str(tmp_path / "s3")])
    out = run_example("fit_circle.py", str(tmp_path / "s3" / "probe_circle_compensated.csv"),
                      str(tmp_path))
    assert "roundness" in out
    assert_plot(tmp_path / "circle.png")


def test_hexapod_path(tmp_path):
    out = run_example("hexapod_path.py", str(tmp_path))
    assert "FK round trip" in out
    assert_plot(tmp_path / "struts.png")


def test_gcode_struts(tmp_path):
    out = run_example("gcode_struts.py", str(tmp_path))
    assert "result: all checks pass" in out and "strut lengths" in out
    assert_plot(tmp_path / "gcode_struts.png")
