"""pkm.metrology: every `pkm analyze <kind>` from arrays (or files) against the command's --json
output on the same numbers."""

import json

import numpy as np
import pytest

import pkm

from conftest import parse_csv


def strip_sources(value):
    """The document without the members that name the input (file, line)."""
    if isinstance(value, dict):
        return {k: strip_sources(v) for k, v in value.items() if k not in ("file", "line")}
    if isinstance(value, list):
        return [strip_sources(v) for v in value]
    return value


def number(v):
    """A field as pkm writes it: strings as they are, integral numbers without '.0'."""
    if isinstance(v, str):
        return v
    return str(int(v)) if float(v).is_integer() else repr(float(v))


def write_table(path, columns):
    names = list(columns)
    n = len(columns[names[0]])
    lines = [",".join(names)]
    for i in range(n):
        lines.append(",".join(number(v[i]) for v in columns.values()))
    path.write_text("\n".join(lines) + "\n")
    return str(path)


def read_table(path):
    """A pkm CSV file (comment lines '#') as a dict of columns: numbers as arrays, else strings."""
    rows = parse_csv("".join(l for l in open(path) if not l.startswith("#")))
    out = {}
    for k in rows[0]:
        values = [r[k] for r in rows]
        try:
            out[k] = np.array([float(v) for v in values]) if not values[0].startswith(("+", "-x", "-y")) else values
        except ValueError:
            out[k] = values
    return out


@pytest.fixture(scope="module")
def sims(run_cli, tmp_path_factory):
    root = tmp_path_factory.mktemp("sim")
    out = {}
    for name, scenario in (("s0", "seed000-parallelism"), ("s1", "seed001-diagonals"),
                           ("s3", "seed003-probe-offset")):
        run_cli(["simulate", scenario, "--out", str(root / name)])
        out[name] = root / name
    return out


def cli_json(run_cli, args):
    return json.loads(run_cli(["analyze", *args, "--json"]).stdout)


def test_circle_from_array(run_cli, tmp_path):
    rng = np.random.default_rng(3)
    t = np.linspace(0, 2 * np.pi, 37)[:-1]
    xy = np.column_stack([5 + 20 * np.cos(t), -3 + 20 * np.sin(t)]) + rng.normal(0, 1e-3, (36, 2))
    r = pkm.metrology.circle(xy)
    path = write_table(tmp_path / "c.csv", {"x": xy[:, 0], "y": xy[:, 1]})
    assert strip_sources(r.to_dict()) == strip_sources(cli_json(run_cli, ["circle", "--data", path]))
    assert isinstance(r.center, np.ndarray) and r.center.shape == (2,)
    assert r.radius == pytest.approx(20, abs=1e-2)
    for key in ("roundness_lsc", "roundness_mzc"):
        assert key in dir(r)
    assert "roundness" in str(r)
    with pytest.raises(AttributeError, match="no attribute 'nope'"):
        r.nope


def test_circle_fit_and_budget_keywords(run_cli, tmp_path):
    t = np.linspace(0, 2 * np.pi, 41)[:-1]
    xy = np.column_stack([1 + 5.01 * np.cos(t), 2 + 4.99 * np.sin(t)])
    both = pkm.metrology.circle(xy)
    lsc = pkm.metrology.circle(xy, fit="lsc", budget=False)
    assert lsc.radius == both.radius and "roundness_mzc" not in dir(lsc)
    assert lsc.to_dict()["fit"] == "lsc" and lsc.to_dict()["uncertainty"] == {"coverage_factor": 2.0} or not lsc.to_dict()["uncertainty"].get("radius")
    mzc = pkm.metrology.circle(xy, fit="mzc")
    assert mzc.roundness_mzc == both.roundness_mzc and "radius" not in dir(mzc)
    # A view of a wider array (not contiguous) and float32 give the same circle.
    wide = np.column_stack([xy, np.zeros(len(xy))])
    assert pkm.metrology.circle(wide[:, :2], fit="lsc").radius == pytest.approx(both.radius, abs=1e-12)
    assert pkm.metrology.circle(xy.astype(np.float32), fit="lsc").radius == pytest.approx(both.radius, abs=1e-5)
    with pytest.raises(ValueError, match="--fit 'lse'"):
        pkm.metrology.circle(xy, fit="lse")


def test_circular_and_probe_offset_from_arrays(sims, run_cli):
    s3 = sims["s3"]
    files = [str(s3 / "probe_circle_uncompensated.csv"), str(s3 / "probe_circle_compensated.csv")]
    tables = [{k: v for k, v in read_table(f).items() if k in ("x", "y")} for f in files]
    r = pkm.metrology.circular(tables, nominal_radius=20)
    cli = cli_json(run_cli, ["circular", "--data", *files, "--nominal-radius", "20"])
    assert strip_sources(r.to_dict()) == strip_sources(cli)
    offset = read_table(s3 / "probe_offset.csv")
    r = pkm.metrology.probe_offset(offset, ring_diameter=40.001)
    cli = cli_json(run_cli, ["probe-offset", "--data", str(s3 / "probe_offset.csv"),
                             "--ring-diameter", "40.001"])
    assert strip_sources(r.to_dict()) == strip_sources(cli)


def test_iso230_2_from_array(run_cli, tmp_path):
    targets = np.arange(0, 500, 50.0)
    rows = []
    rng = np.random.default_rng(5)
    for run in (1, 2, 3):
        for d in (1, -1):
            for t in targets[:: d]:
                rows.append((t, d, run, t + 1e-3 * np.sin(t / 80) + d * 2e-4 + rng.normal(0, 1e-4)))
    a = np.array(rows)
    r = pkm.metrology.iso230_2(a)
    path = write_table(tmp_path / "p.csv", {"target": a[:, 0], "direction": a[:, 1],
                                            "run": a[:, 2], "measured": a[:, 3]})
    assert strip_sources(r.to_dict()) == strip_sources(cli_json(run_cli, ["iso230-2", "--data", path]))


def test_straightness_parallelism_squareness_from_arrays(run_cli, tmp_path):
    x = np.linspace(0, 400, 21)
    dev = 1e-3 * np.sin(x / 60) + 2e-6 * x
    dev2 = 1e-3 * np.cos(x / 50) - 1e-6 * x
    for ref in ("endpoint", "lsq", "minzone"):
        r = pkm.metrology.straightness(np.column_stack([x, dev]), reference=ref)
        path = write_table(tmp_path / "s.csv", {"position": x, "deviation": dev})
        cli = cli_json(run_cli, ["straightness", "--data", path, "--reference", ref])
        assert strip_sources(r.to_dict()) == strip_sources(cli)
    a = write_table(tmp_path / "a.csv", {"position": x, "deviation": dev2})
    r = pkm.metrology.parallelism(np.column_stack([x, dev]), np.column_stack([x, dev2]),
                                  reference_sign=-1, szX2=1e-5)
    cli = cli_json(run_cli, ["parallelism", "--reference", path, "--axis", a,
                             "--reference-sign", "-1", "--szX2", "1e-05"])
    assert strip_sources(r.to_dict()) == strip_sources(cli)
    u = np.linspace(0, 300, 16)
    v = 0.5 * u
    s = np.hypot(u, v)
    d = -2e-5 * u * v / np.maximum(s, 1) + 1e-4 * np.sin(u / 40)
    r = pkm.metrology.squareness([np.column_stack([u, v, d])])
    p = write_table(tmp_path / "d.csv", {"u": u, "v": v, "deviation": d})
    assert strip_sources(r.to_dict()) == strip_sources(cli_json(run_cli, ["squareness", "--data", p]))


def test_simulator_files_equal_cli(sims, run_cli):
    s0, s1 = sims["s0"], sims["s1"]
    diag = sorted(str(p) for p in s1.glob("diag-*_run*.csv"))
    r = pkm.metrology.diagonals(diag, size=[500, 400, 300])
    cli = cli_json(run_cli, ["diagonals", "--size", "500,400,300", "--data", *diag])
    assert strip_sources(r.to_dict()) == strip_sources(cli)
    sq = sorted(str(p) for p in s0.glob("diagonal-x2-y2_run*.csv"))
    r2 = pkm.metrology.squareness(sq)
    cli = cli_json(run_cli, ["squareness", "--data", *sq])
    assert strip_sources(r2.to_dict()) == strip_sources(cli)
    assert r2.kind == "squareness"
    lin = sorted(str(p) for p in s0.glob("linear-x2_run*.csv"))
    r = pkm.metrology.iso230_2(lin)
    assert strip_sources(r.to_dict()) == strip_sources(cli_json(run_cli, ["iso230-2", "--data", *lin]))


def test_bad_tables_raise_value_error(tmp_path):
    with pytest.raises(ValueError, match=r"data: expected an array of shape \(N, 2\)"):
        pkm.metrology.circle(np.zeros((4, 3)))
    with pytest.raises(ValueError, match="row 1 column 0 is not a finite number"):
        pkm.metrology.circle(np.array([[0, 1.0], [np.nan, 1], [1, 0]]))
    with pytest.raises(ValueError, match="column 'y' has 2 rows"):
        pkm.metrology.circle({"x": [1.0, 2, 3], "y": [1.0, 2]})
    with pytest.raises(ValueError):
        pkm.metrology.circle(np.zeros((2, 2)))  # too few points: pkm's message
    with pytest.raises(ValueError, match="no-such.csv"):
        pkm.metrology.circle(str(tmp_path / "no-such.csv"))
    with pytest.raises(ValueError, match="reference"):
        pkm.metrology.straightness(np.zeros((5, 2)), reference="best")
    with pytest.raises(ValueError, match="centre 'x'"):
        pkm.metrology.circular(np.zeros((5, 2)), centre="x")
