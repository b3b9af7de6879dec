"""pkm.Hexapod: ik, fk, jacobian and check against `pkm hexapod ik|fk|check` on the same input."""

import numpy as np
import pytest

import pkm

from conftest import column, csv_text, parse_csv

POSES = np.array(
    [
        [0, 0, 200, 0, 0, 0],
        [50, -20, 180, 5, -3, 10],
        [0, 0, 200, 0, 60, 0],
        [-30, 40, 220, -4, 6, -15],
        [10, 10, 150, 2, 2, 2],
    ],
    dtype=float,
)


def random_path(h, n=200, seed=1):
    rng = np.random.default_rng(seed)
    t = np.linspace(0, 1, n)[:, None]
    amplitude = np.array([40, 40, 30, 5, 5, 10.0])
    return h.home + amplitude * np.sin(2 * np.pi * (t + rng.random(6)))


@pytest.fixture(scope="module")
def hexapod():
    return pkm.load_machine("hexapod-default")


def test_ik_equals_cli(hexapod, run_cli):
    out = run_cli(["hexapod", "ik", "-m", "hexapod-default", "-p", "-"],
                  csv_text("x,y,z,a,b,c".split(","), POSES)).stdout
    rows = parse_csv(out)
    readings, status = hexapod.ik(POSES, status=True)
    cli = np.column_stack([column(rows, f"l{i}") for i in range(6)])
    np.testing.assert_array_equal(readings, cli)  # printed round-trip exact
    assert list(status) == [r["status"] for r in rows]
    np.testing.assert_array_equal(hexapod.ik(POSES), readings)
    assert hexapod.ik(POSES[1]).shape == (6,)


def test_ik_of_many_poses_on_the_cores_equals_one_by_one(hexapod):
    rng = np.random.default_rng(3)
    scale = np.where(np.arange(100_000)[:, None] % 2 == 0, 0.1, 3.0)  # within and beyond the limits
    poses = hexapod.home + scale * rng.uniform(-1, 1, (100_000, 6)) * [80, 80, 60, 10, 10, 20]
    readings, status = hexapod.ik(poses, status=True)
    for i in range(0, len(poses), 4999):
        np.testing.assert_array_equal(readings[i], hexapod.ik(poses[i]))
        assert status[i] == hexapod.ik(poses[i:i + 1], status=True)[1][0]
    assert (status != "ok").any() and (status == "ok").any()


def test_fk_file_equals_cli(hexapod, run_cli, tmp_path):
    lengths = hexapod.ik(random_path(hexapod))
    src = tmp_path / "l.csv"
    src.write_text(csv_text([f"l{i}" for i in range(6)], lengths))
    out = tmp_path / "poses.csv"
    summary = hexapod.fk_file(src, out)
    assert summary == {"rows": len(lengths), "failed": 0}
    cli = run_cli(["hexapod", "fk", "-m", "hexapod-default", "-l", str(src)]).stdout
    assert out.read_text() == cli
    with pytest.raises(ValueError, match="exists"):
        hexapod.fk_file(src, out)
    bad = tmp_path / "bad.csv"
    bad.write_text("l0,l1,l2,l3,l4,l5\n1,2,3\n")
    with pytest.raises(ValueError, match="bad.csv:2"):
        hexapod.fk_file(bad, tmp_path / "none.csv")
    assert not (tmp_path / "none.csv").exists()


def test_ik_raise_on_failure(hexapod):
    with pytest.raises(pkm.LimitError, match="row 2: stroke"):
        hexapod.ik(POSES, raise_on_failure=True)


def test_fk_equals_cli_and_round_trips(hexapod, run_cli):
    path = random_path(hexapod)
    lengths = hexapod.ik(path)
    out = run_cli(["hexapod", "fk", "-m", "hexapod-default", "-l", "-"],
                  csv_text([f"l{i}" for i in range(6)], lengths)).stdout
    rows = parse_csv(out)
    poses, status, iterations = hexapod.fk(lengths)
    cli = np.column_stack([column(rows, k) for k in "x,y,z,a,b,c".split(",")])
    np.testing.assert_array_equal(poses, cli)
    assert list(status) == [r["status"] for r in rows]
    np.testing.assert_array_equal(iterations, [int(r["iterations"]) for r in rows])
    np.testing.assert_allclose(poses, path, atol=1e-8)


def test_fk_seed_and_from_seed_equal_cli(hexapod, run_cli):
    lengths = hexapod.ik(POSES[:2])
    seed = [1, 2, 190, 1, 1, 1]
    for extra, kwargs in ((["--seed", "1,2,190,1,1,1"], {"seed": seed}),
                          (["--seed", "1,2,190,1,1,1", "--from-seed"], {"seed": seed, "from_seed": True})):
        rows = parse_csv(run_cli(["hexapod", "fk", "-l", "-", *extra],
                                 csv_text([f"l{i}" for i in range(6)], lengths)).stdout)
        poses, _, iterations = hexapod.fk(lengths, **kwargs)
        np.testing.assert_array_equal(poses[:, 0], column(rows, "x"))
        np.testing.assert_array_equal(iterations, [int(r["iterations"]) for r in rows])


def test_fk_failure_rows_are_nan_and_can_raise(hexapod):
    lengths = hexapod.ik(POSES[:2])
    lengths[1] = [1, 1, 1, 1000, 1000, 1]  # does not assemble
    poses, status, _ = hexapod.fk(lengths)
    assert status[0] == "ok" and status[1] != "ok"
    assert np.isnan(poses[1]).all()
    with pytest.raises(pkm.ConvergenceError, match="row 1"):
        hexapod.fk(lengths, raise_on_failure=True)


def test_jacobian_matches_finite_differences(hexapod):
    pose = POSES[1]
    J = hexapod.jacobian(pose)
    assert J.shape == (6, 6) and hexapod.jacobian(POSES).shape == (5, 6, 6)
    h = 1e-6
    for k in range(3):  # translation columns
        d = np.zeros(6)
        d[k] = h
        numeric = (hexapod.ik(pose + d) - hexapod.ik(pose - d)) / (2 * h)
        np.testing.assert_allclose(J[:, k], numeric, atol=1e-6)


def test_check_equals_cli(hexapod, run_cli):
    rows = parse_csv(run_cli(["hexapod", "check", "-p", "-"],
                             csv_text("x,y,z,a,b,c".split(","), POSES)).stdout)
    c = hexapod.check(POSES)
    assert list(c["status"]) == [r["status"] for r in rows]
    np.testing.assert_array_equal(c["stroke_margin"].min(axis=1), column(rows, "min_stroke_margin"))
    np.testing.assert_array_equal(c["stroke_margin"].argmin(axis=1),
                                  column(rows, "stroke_strut").astype(int))
    np.testing.assert_allclose(c["base_angle_margin_deg"].min(axis=1),
                               column(rows, "min_base_angle_margin_deg"), rtol=1e-15)
    np.testing.assert_array_equal(c["condition_number"], column(rows, "condition_number"))
    np.testing.assert_array_equal(c["min_leg_distance"], column(rows, "min_leg_distance"))
    assert [f"{a}-{b}" for a, b in c["closest_pair"]] == [r["leg_pair"] for r in rows]
    assert c["violations"][2][0]["kind"] == "stroke"
    with pytest.raises(pkm.LimitError):
        hexapod.check(POSES, raise_on_failure=True)


@pytest.mark.parametrize(
    "bad, message",
    [
        (np.zeros((3, 5)), r"shape \(N, 6\)"),
        (np.array([[0, 0, np.nan, 0, 0, 0]]), "row 0 column 2 is not a finite number"),
        ("text", "not an array of numbers"),
        (np.zeros((2, 3, 6)), "shape"),
    ],
)
def test_bad_input_raises_value_error(hexapod, bad, message):
    for f in (hexapod.ik, hexapod.check, hexapod.jacobian):
        with pytest.raises(ValueError, match=message):
            f(bad)
    with pytest.raises(ValueError, match=message.replace("poses", "lengths")):
        hexapod.fk(bad)
    with pytest.raises(ValueError, match="seed"):
        hexapod.fk(hexapod.ik(POSES), seed=[0, 0, 1])
