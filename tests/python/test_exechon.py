"""pkm.Exechon: ik, fk, ik_wrist, check and drm_circle against `pkm exechon ...` on the same input."""

import numpy as np
import pytest

import pkm

from conftest import column, csv_text, parse_csv

POINTS = np.array([[1500, -200, -50], [1500, -200, -50], [1510, -190, -60], [1490, -210, -40.0]])
DIRECTIONS = np.array([[0, 0, -1], [0.2, 0, -0.98], [0.1, 0.1, -0.99], [0, -0.15, -0.99]])


@pytest.fixture(scope="module")
def exechon():
    return pkm.load_machine("mxt700s-like")


def test_ik_and_check_equal_cli(exechon, run_cli):
    text = csv_text("x,y,z,i,j,k".split(","), np.hstack([POINTS, DIRECTIONS]))
    rows = parse_csv(run_cli(["exechon", "ik", "--poses", "-"], text).stdout)
    r = exechon.ik(POINTS, DIRECTIONS)
    for k, name in enumerate(["q1", "q2", "q3", "c", "a"]):
        np.testing.assert_array_equal(r["joints"][:, k], column(rows, name))
    np.testing.assert_array_equal(r["drm"], column(rows, "drm"))
    np.testing.assert_array_equal(r["x2y2"], np.column_stack([column(rows, "x2"), column(rows, "y2")]))
    assert list(r["status"]) == [row["status"] for row in rows]
    rows = parse_csv(run_cli(["exechon", "check", "--poses", "-"], text).stdout)
    c = exechon.check(POINTS, DIRECTIONS)
    assert list(c["status"]) == [row["status"] for row in rows]
    np.testing.assert_array_equal(c["stroke_margin"].min(axis=1), column(rows, "min_stroke_margin"))
    np.testing.assert_array_equal(c["condition_number"], column(rows, "condition_number"))


def test_fk_equals_cli_and_round_trips(exechon, run_cli):
    r = exechon.ik(POINTS, DIRECTIONS)
    joints = r["joints"]
    text = csv_text("q1,q2,q3,c,a,x2,y2".split(","), np.hstack([joints, r["x2y2"]]))
    rows = parse_csv(run_cli(["exechon", "fk", "--joints", "-"], text).stdout)
    points, directions, status, iterations = exechon.fk(joints, x2y2=r["x2y2"])
    for k, name in enumerate("xyz"):
        np.testing.assert_array_equal(points[:, k], column(rows, name))
    np.testing.assert_array_equal(iterations, [int(row["iterations"]) for row in rows])
    np.testing.assert_allclose(points, POINTS, atol=1e-7)
    unit = DIRECTIONS / np.linalg.norm(DIRECTIONS, axis=1)[:, None]
    np.testing.assert_allclose(directions, unit, atol=1e-9)
    assert (status == "ok").all()


def test_wrist_and_drm_equal_cli(run_cli):
    zoppi = pkm.load_machine("exechon-zoppi2010")
    readings, e, status = zoppi.ik_wrist([[20, 700, 1020]])
    rows = parse_csv(run_cli(["exechon", "ik", "-m", "exechon-zoppi2010", "--wrist", "-"],
                             "sx,sy,sz\n20,700,1020\n").stdout)
    np.testing.assert_array_equal(readings[0], [float(rows[0][k]) for k in ("q1", "q2", "q3")])
    np.testing.assert_array_equal(e[0], [float(rows[0][k]) for k in ("alpha", "beta", "h")])
    assert status[0] == rows[0]["status"]
    ex = pkm.load_machine("mxt700s-like")
    d = ex.drm_circle([0, 0, -100], 25, step=10)
    out = run_cli(["exechon", "drm", "--circle", "0,0,-100,25", "--step", "10"]).stdout
    assert f"# max |phi_drm| {d['max_abs_phi_deg']!r} deg" in out
    with pytest.raises(ValueError, match="invalid circle"):
        ex.drm_circle([0, 0, -100], -1)


def test_bad_input(exechon):
    with pytest.raises(ValueError, match="directions: 2 rows for 4 points"):
        exechon.ik(POINTS, DIRECTIONS[:2])
    with pytest.raises(ValueError, match="x2y2"):
        pkm.load_machine("exechon-zoppi2010").ik(POINTS, DIRECTIONS, x2y2=np.zeros((4, 2)))
    with pytest.raises(ValueError, match="not a finite number"):
        exechon.fk(np.full((1, 5), np.inf))
    far = exechon.ik([[1500, -200, 5000]], [0, 0, -1])
    assert far["status"][0] == "stroke"  # solved, out of stroke: the readings are given
    with pytest.raises(pkm.LimitError):
        exechon.ik([[1500, -200, 5000]], [0, 0, -1], raise_on_failure=True)
