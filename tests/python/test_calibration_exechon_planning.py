"""pkm.calibration.exechon and pose planning against the pkm program: Exechon calibration from
files and from arrays gives the summary `pkm calibrate exechon --json` prints and its files, and
str(result) its text; the uncertainty sources of both machine kinds equal the program's; pose
planning equals `pkm plan-poses` (from a name or a loaded machine); bad input raises ValueError
with pkm's message. The hexapod: test_calibration.py."""

import json
import math

import numpy as np
import pytest

import pkm
from calibration_helpers import EXECHON, HYBRID, cli_text, masked, read_table, vector, without
from conftest import column, parse_csv


# --- Exechon -------------------------------------------------------------------------------


def test_exechon_str_is_the_cli_text(pkm_binary, ex, tmp_path, monkeypatch):
    fit, hybrid = str(ex / "tracker-fit.csv"), str(ex / "tracker-hybrid.csv")
    hold, hhold = str(ex / "tracker-holdout.csv"), str(ex / "tracker-hybrid-holdout.csv")
    cli = cli_text(pkm_binary, tmp_path / "cli", ["calibrate", "exechon", "--machine",
                                                  "mxt700s-like", "--data", fit, hybrid,
                                                  "--holdout", hold, hhold, "--errors",
                                                  "mxt700s-seed000", "--out", "cal.json"])
    assert "squareness from" in cli and "fitted residuals" in cli
    (tmp_path / "py").mkdir()
    monkeypatch.chdir(tmp_path / "py")
    r = pkm.calibration.exechon("mxt700s-like", files=[fit, hybrid], holdout=[hold, hhold],
                                errors="mxt700s-seed000", out="cal.json")
    assert masked(str(r)) == masked(cli)
    tripod = pkm.calibration.exechon("mxt700s-like", files=[fit])
    cli = cli_text(pkm_binary, tmp_path / "cli-tripod", ["calibrate", "exechon", "--machine",
                                                         "mxt700s-like", "--data", fit,
                                                         "--out", "cal.json"])
    assert masked(str(tripod)) + "wrote cal.json, cal.summary.json\n" == masked(cli)


def test_exechon_from_files_and_arrays_equals_the_cli(run_cli, ex, tmp_path):
    fit, hybrid = str(ex / "tracker-fit.csv"), str(ex / "tracker-hybrid.csv")
    hold, hhold = str(ex / "tracker-holdout.csv"), str(ex / "tracker-hybrid-holdout.csv")
    cli = json.loads(run_cli(["calibrate", "exechon", "--machine", "mxt700s-like", "--data", fit,
                              hybrid, "--holdout", hold, hhold, "--errors", "mxt700s-seed000",
                              "--out", str(tmp_path / "cli.json"), "--json"]).stdout)
    r = pkm.calibration.exechon("mxt700s-like", files=[fit, hybrid], holdout=[hold, hhold],
                                errors="mxt700s-seed000")
    r.save(tmp_path / "py.json")
    assert without(r.to_dict(), "outputs") == without(cli, "outputs")
    for suffix in (".json", ".errors.json"):
        with open(tmp_path / ("py" + suffix)) as a, open(tmp_path / ("cli" + suffix)) as b:
            assert a.read() == b.read(), suffix
    meta, points = read_table(fit, EXECHON)
    hmeta, hybrid_rows = read_table(hybrid, HYBRID)
    arrays = pkm.calibration.exechon(
        "mxt700s-like", points=points, hybrid=hybrid_rows,
        holdout=read_table(hold, EXECHON)[1], hybrid_holdout=read_table(hhold, HYBRID)[1],
        errors="mxt700s-seed000", frame="tracker", target_offset=vector(meta["smr offset mm"]),
        hybrid_target_offset=vector(hmeta["smr offset mm"]))
    same = ("data", "worst_observations", "outputs")
    assert without(arrays.to_dict(), *same) == without(cli, *same)
    # Attributes.
    assert isinstance(r.machine, pkm.Exechon)
    assert list(r.squareness_names) == ["szX2", "sxP", "syP", "szP"]
    assert np.array_equal(r.squareness, list(cli["hybrid"]["squareness"].values()))
    assert np.array_equal(r.parameters, [p["estimate"] for p in cli["parameters"]])
    assert r.covariance.shape == (32, 32) and list(r.covariance_names[-1:]) == ["frame.rz"]
    assert r.rank == cli["identifiability"]["rank"]
    assert len(r.holdout_errors_after) == cli["holdout"]["after"]["poses"]
    e = r.hybrid_holdout_errors_after
    assert math.isclose(np.sqrt(np.nanmean(e ** 2)), cli["hybrid"]["holdout"]["after"]["rms"],
                        rel_tol=1e-12)
    assert r.geometric_errors is not None
    assert without(r.to_dict())["hybrid"] == without(cli)["hybrid"] == \
        without({"hybrid": r.hybrid})["hybrid"]


@pytest.mark.parametrize("kind", ["hexapod", "exechon"])
def test_uncertainty_sources_equal_the_cli(run_cli, s4, ex, tmp_path, kind):
    sources = tmp_path / "sources.json"
    sources.write_text('{"tracker": {"accuracy_mm": 0.03, "accuracy_mm_per_m": 0.01}}\n')
    data = str(s4 / "tracker-pose.csv") if kind == "hexapod" else str(ex / "tracker-fit.csv")
    machine = "hexapod-default" if kind == "hexapod" else "mxt700s-like"
    cli = json.loads(run_cli(["calibrate", kind, "--machine", machine, "--data", data,
                              "--uncertainty", str(sources), "--out", str(tmp_path / "c.json"),
                              "--json"]).stdout)
    calibrate = getattr(pkm.calibration, kind)
    r = calibrate(machine, files=data, uncertainty=sources)
    assert without(r.to_dict(), "outputs") == without(cli, "outputs")
    assert r.uncertainty["sources"] == str(sources)
    typical = calibrate(machine, files=data)
    assert np.nanmax(r.expanded_uncertainty - typical.expanded_uncertainty) > 0
    (tmp_path / "bad.json").write_text('{"tracker": {"accuracy_mm": "a"}}\n')
    with pytest.raises(ValueError, match="bad.json:1"):
        calibrate(machine, files=data, uncertainty=tmp_path / "bad.json")


def test_exechon_errors(ex):
    _, points = read_table(ex / "tracker-fit.csv", EXECHON)
    with pytest.raises(ValueError, match=r"points: expected an array of shape \(N, 8\)"):
        pkm.calibration.exechon(points=points[:, :7], frame="tracker")
    with pytest.raises(ValueError, match="hybrid"):
        pkm.calibration.exechon("exechon-zoppi2010", hybrid=points, frame="tracker")
    with pytest.raises(ValueError, match="nosuch"):
        pkm.calibration.exechon(points=points, frame="tracker", fix=["nosuch"])


# --- pose planning -------------------------------------------------------------------------


@pytest.mark.parametrize("machine,args", [("hexapod-default", []),
                                          ("hexapod-default", ["--measurement", "point"]),
                                          ("mxt700s-like", ["--target-offset", "40,0,0"])])
def test_plan_poses_equals_the_cli(run_cli, tmp_path, machine, args):
    cli = run_cli(["plan-poses", "--machine", machine, "--count", "16", "--candidates", "120",
                   "--seed", "3", "--gcode", str(tmp_path / "cli.ngc"), *args]).stdout
    kw = {}
    if "--measurement" in args:
        kw["measurement"] = "point"
    if "--target-offset" in args:
        kw["target_offset"] = [40, 0, 0]
    plan = pkm.calibration.plan_poses(machine, count=16, candidates=120, seed=3,
                                      gcode=tmp_path / "py.ngc", **kw)
    assert plan.csv == cli
    with open(tmp_path / "cli.ngc") as a:
        assert plan.gcode == a.read()
    # A loaded machine object plans as its name does.
    loaded = pkm.calibration.plan_poses(pkm.load_machine(machine), count=16, candidates=120,
                                        seed=3, gcode=tmp_path / "loaded.ngc", **kw)
    assert loaded.csv == cli and loaded.gcode == plan.gcode
    rows = parse_csv(cli)
    names = ["x", "y", "z", "a", "b", "c"] if plan.kind == "hexapod" else \
        ["x", "y", "z", "i", "j", "k"]
    assert np.array_equal(plan.poses, np.column_stack([column(rows, n) for n in names]))
    doc = plan.to_dict()
    assert plan.rank == doc["rank"] and len(plan.chosen) == 16 and len(plan.indices) == 5
    assert plan.index_value >= plan.random_baseline
    if plan.kind == "exechon":
        assert plan.moves.shape == (17, 5)
    with pytest.raises(ValueError, match="exists"):
        pkm.calibration.plan_poses(machine, count=16, candidates=120, gcode=tmp_path / "py.ngc")


def test_plan_poses_of_a_changed_geometry_differ():
    m = pkm.load_machine("hexapod-default")
    base = m.base_joints.copy()
    base[0, 0] += 5.0  # strut 0's base joint 5 mm along x
    moved = m.with_geometry(base_joints=base)
    args = dict(count=8, candidates=60, seed=2)
    # The same candidates, but the index is evaluated on the changed geometry.
    assert pkm.calibration.plan_poses(moved, **args).index_value != \
        pkm.calibration.plan_poses(m, **args).index_value


def test_plan_poses_errors():
    with pytest.raises(ValueError, match="candidates"):
        pkm.calibration.plan_poses(count=10, candidates=5)
    with pytest.raises(ValueError, match="target-offset applies to Exechon"):
        pkm.calibration.plan_poses(pkm.load_machine("hexapod-default"), target_offset=[1, 2, 3])
    with pytest.raises(ValueError, match="machine"):
        pkm.calibration.plan_poses(3.5)
    with pytest.raises(ValueError):
        pkm.calibration.plan_poses(index="O9")
