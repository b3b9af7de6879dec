"""pkm.calibration.hexapod against the pkm program: calibration from files and from arrays gives
the summary `pkm calibrate hexapod --json` prints (same numbers), the calibrated machine file it
writes, and the numbers of its text summary to the printed precision; a round trip on simulated
data with a known truth recovers the geometry within the reported uncertainty; str(result) is the
text `pkm calibrate` prints; bad input raises ValueError with pkm's message and ConvergenceError
only on request. The seed 004 example runs headless. The Exechon, the uncertainty sources and pose
planning: test_calibration_exechon_planning.py."""

import json
import math
import os
import re
import subprocess
import sys

import numpy as np
import pytest

import pkm
from calibration_helpers import GAUGE, POSE, cli_text, masked, read_table, vector, without
from conftest import REPO
from test_examples import assert_plot


# --- hexapod -------------------------------------------------------------------------------


def test_hexapod_from_files_equals_the_cli(run_cli, s4, tmp_path):
    pose, hold = str(s4 / "tracker-pose.csv"), str(s4 / "tracker-holdout.csv")
    reg = str(s4 / "tracker-pose-registration.csv")
    cli = json.loads(run_cli(["calibrate", "hexapod", "--machine", "hexapod-default", "--data",
                              pose, "--holdout", hold, "--registration", reg, "--out",
                              str(tmp_path / "cli.json"), "--json"]).stdout)
    r = pkm.calibration.hexapod("hexapod-default", files=[pose], holdout=[hold], registration=reg)
    assert r.to_dict()["world_frame"] == "registered"
    assert r.to_dict()["outputs"] == {"machine": "", "hal": "", "summary": ""}
    written = r.save(tmp_path / "py.json")
    assert written == [str(tmp_path / n) for n in
                       ("py.json", "py.hal", "py.pkmhexkins.hal", "py.summary.json")]
    assert without(r.to_dict(), "outputs") == without(cli, "outputs")
    assert r.to_dict()["outputs"]["machine"] == str(tmp_path / "py.json")
    with open(tmp_path / "py.summary.json") as f:
        assert f.read() == r.to_json()
    for suffix in (".json", ".hal", ".pkmhexkins.hal"):
        with open(tmp_path / ("py" + suffix)) as a, open(tmp_path / ("cli" + suffix)) as b:
            assert a.read() == b.read(), suffix
    with pytest.raises(ValueError, match="exists"):
        r.save(tmp_path / "py.json")
    r.save(tmp_path / "py.json", force=True)
    # The calibrated machine compensates a program at once, as its file does.
    program = os.path.join(REPO, "examples", "gcode", "hexapod_contour.ngc")
    text, rep = pkm.gcode.compensate(program, machine=r.machine)
    from_file, rep_file = pkm.gcode.compensate(program, machine=tmp_path / "py.json")
    assert text == from_file and rep["note"] == rep_file["note"]
    assert rep["max_correction"] > 1.0  # seed 004: millimetres of joint errors


def test_hexapod_from_arrays_equals_the_files(run_cli, s4, tmp_path):
    meta, poses = read_table(s4 / "tracker-pose.csv", POSE)
    _, held = read_table(s4 / "tracker-holdout.csv", POSE)
    cli = run_cli(["calibrate", "hexapod", "--machine", "hexapod-default", "--data",
                   str(s4 / "tracker-pose.csv"), "--holdout", str(s4 / "tracker-holdout.csv"),
                   "--out", str(tmp_path / "cli.json")])
    r = pkm.calibration.hexapod("hexapod-default", poses=poses, holdout=held, frame="tracker",
                                target_offset=vector(meta["smr offset mm"]))
    with open(tmp_path / "cli.summary.json") as f:
        doc = json.load(f)
    same = ("data", "worst_observations", "outputs")
    assert without(r.to_dict(), *same) == without(doc, *same)
    assert [w["residual"] for w in r.worst_observations] == \
        [w["residual"] for w in doc["worst_observations"]]
    assert r.worst_observations[0]["source"].startswith("poses:")
    # The text summary's numbers, to its printed precision.
    text = cli.stdout
    m = re.search(r"held-out TCP error: RMS (\S+) -> (\S+), max (\S+) -> (\S+)", text)
    h = r.holdout
    assert m.groups() == tuple(f"{v:.6g}" for v in (h["before"]["rms"], h["after"]["rms"],
                                                     h["before"]["max"], h["after"]["max"]))
    m = re.search(r"identifiable: (\d+) of (\d+) unknowns \(condition number (\S+)\)", text)
    assert m.groups() == (str(r.rank), str(r.identifiability["parameters"]),
                          f"{r.condition_number:.4g}")
    assert text.count("not identifiable:") == len(r.identifiability["unidentifiable"])
    m = re.search(r"fitted residuals \(mm\): RMS (\S+) -> (\S+), max", text)
    assert m.groups() == (f"{r.residuals_before['rms']:.6g}", f"{r.residuals_after['rms']:.6g}")


def test_hexapod_result_attributes(s4, tmp_path):
    r = pkm.calibration.hexapod("hexapod-default", files=[str(s4 / "tracker-pose.csv")],
                                holdout=[str(s4 / "tracker-holdout.csv")])
    doc = r.to_dict()
    params = doc["parameters"]
    assert list(r.parameter_names) == [p["name"] for p in params]
    assert np.array_equal(r.parameters, [p["estimate"] for p in params])
    assert np.array_equal(r.initial, [p["initial"] for p in params])
    assert np.array_equal(r.standard_deviation, [p["sigma"] for p in params])
    assert np.array_equal(r.free, [p["free"] for p in params])
    assert r.covariance.shape == (42, 42)
    assert np.allclose(np.sqrt(np.diag(r.covariance)), r.standard_deviation, rtol=1e-12)
    assert r.rank == doc["identifiability"]["rank"] == 42
    ident = r.identifiability
    assert ident["parameters"] == 48 and list(ident["names"][-6:]) == [
        "frame.x", "frame.y", "frame.z", "frame.rx", "frame.ry", "frame.rz"]
    assert ident["null_space"].shape == (48, 6) and len(ident["singular_values"]) == 48
    assert r.residuals_after == doc["residuals"]["after"]
    assert r.converged and r.iterations == doc["solver"]["iterations"]
    assert r.measurement_frame.shape == (4, 4) and r.frame_sigma.shape == (6,)
    assert np.allclose(r.measurement_frame[:3, 3], doc["measurement_frame"]["position"])
    # Per held-out pose errors agree with the summary's statistics.
    for key in ("before", "after"):
        e = getattr(r, "holdout_errors_" + key)
        assert len(e) == 50
        assert math.isclose(np.sqrt(np.mean(e ** 2)), r.holdout[key]["rms"], rel_tol=1e-12)
        assert math.isclose(e.max(), r.holdout[key]["max"], rel_tol=1e-15)
    assert r.backlash is None and r.backlash_sigma is None
    assert any("200 poses" in n for n in r.notices)
    # The calibrated machine is usable at once and is the file save() writes.
    assert isinstance(r.machine, pkm.Hexapod)
    assert r.machine.name == "pkm-hx1200-calibrated"
    home = np.array([0, 0, 200, 0, 0, 0.0])
    assert np.allclose(r.machine.fk(r.machine.ik(home))[0], home, atol=1e-9)
    p = r.parameters.reshape(6, 7)
    assert np.array_equal(r.machine.base_joints, p[:, :3])
    assert np.array_equal(r.machine.platform_joints, p[:, 3:6])
    assert np.array_equal(r.machine.length_offsets, p[:, 6])
    r.save(tmp_path / "cal.json")
    assert np.array_equal(pkm.load_machine(tmp_path / "cal.json").ik(home), r.machine.ik(home))
    assert "rank 42" in repr(r) and "to_dict" in dir(r)


def test_hexapod_gauges_from_arrays_equal_the_file_and_convergence_is_raised_on_request(run_cli,
                                                                                       s4):
    path = str(s4 / "constrained-motion.csv")
    meta, gauges = read_table(path, GAUGE)
    tips = np.array([vector(t) for t in re.findall(r"\([^)]*\)", meta["gauge points mm"])])
    cli = json.loads(run_cli(["calibrate", "hexapod", "--machine", "hexapod-default", "--data",
                              path, "--out", "/nonexistent-dir/none.json",
                              "--allow-large-changes", "--json"], check=False).stdout or "{}")
    r = pkm.calibration.hexapod("hexapod-default", gauges=gauges, gauge_points=tips,
                                allow_large_changes=True)
    assert not r.converged and r.iterations == 100
    assert r.observations["constrained_sets"] == 1 and r.observations["equations"] == 72
    f = pkm.calibration.hexapod("hexapod-default", files=path, allow_large_changes=True)
    same = ("data", "worst_observations", "outputs")
    assert without(r.to_dict(), *same) == without(f.to_dict(), *same)
    if cli:  # the program refuses to write into a missing folder before fitting
        assert without(cli, *same) == without(f.to_dict(), *same)
    with pytest.raises(pkm.ConvergenceError, match="did not converge after 100 iterations"):
        pkm.calibration.hexapod("hexapod-default", gauges=gauges, gauge_points=tips,
                                allow_large_changes=True, raise_on_failure=True)
    with pytest.raises(ValueError, match="implausibly far"):
        pkm.calibration.hexapod("hexapod-default", gauges=gauges, gauge_points=tips)


@pytest.mark.parametrize("cli_args,kwargs", [
    (["--fix", "offset0,base1.z"], {"fix": ["offset0", "base1.z"]}),
    (["--loss", "cauchy", "--loss-scale", "0.01"], {"loss": "cauchy", "loss_scale": 0.01}),
    (["--backlash"], {"backlash": True}),
    (["--monte-carlo", "4", "--threads", "1", "--sigma-position", "0.004"],
     {"monte_carlo": 4, "threads": 1, "sigma_position": 0.004}),
    (["--uncertainty-trials", "20", "--threads", "1"], {"uncertainty_trials": 20, "threads": 1}),
])
def test_hexapod_options_equal_the_cli(run_cli, s4, tmp_path, cli_args, kwargs):
    pose, hold = str(s4 / "tracker-pose.csv"), str(s4 / "tracker-holdout.csv")
    cli = json.loads(run_cli(["calibrate", "hexapod", "--machine", "hexapod-default", "--data",
                              pose, "--holdout", hold, "--out", str(tmp_path / "cli.json"),
                              "--json", *cli_args]).stdout)
    r = pkm.calibration.hexapod("hexapod-default", files=[pose], holdout=[hold], **kwargs)
    doc = without(r.to_dict(), "outputs")
    for d in (doc, cli):  # wall times
        d.get("monte_carlo", {}).pop("seconds", None)
        d.get("uncertainty", {}).get("monte_carlo", {}).pop("seconds", None)
    assert doc == without(cli, "outputs")
    if "backlash" in kwargs:
        assert np.array_equal(r.backlash, cli["backlash"]["values"])
    if "fix" in kwargs:
        assert not r.free[list(r.parameter_names).index("offset0")]
    if "monte_carlo" in kwargs:
        assert r.monte_carlo["trials"] == 4
    if r.expanded_uncertainty is not None:
        assert np.array_equal(r.expanded_uncertainty,
                              [np.nan if p["U"] is None else p["U"] for p in cli["parameters"]],
                              equal_nan=True)


def random_poses(n, seed):
    rng = np.random.default_rng(seed)
    lo = np.array([-150, -150, 150, -8, -8, -15.0])
    return lo + (-2 * lo * [1, 1, 0, 1, 1, 1] + [0, 0, 100, 0, 0, 0]) * rng.random((n, 6))


def test_round_trip_recovers_a_known_geometry():
    nominal = pkm.load_machine("hexapod-default")
    rng = np.random.default_rng(4)
    truth = nominal.with_geometry(
        base_joints=nominal.base_joints + rng.normal(0, 1.0, (6, 3)),
        platform_joints=nominal.platform_joints + rng.normal(0, 1.0, (6, 3)),
        length_offsets=nominal.length_offsets + rng.normal(0, 1.0, 6))
    poses = random_poses(150, 1)
    readings = truth.ik(poses)
    exact = pkm.calibration.hexapod(nominal, poses=np.hstack([readings, poses]), frame="world")
    assert exact.rank == 42
    true = np.hstack([truth.base_joints, truth.platform_joints,
                      truth.length_offsets[:, None]]).ravel()
    assert np.max(np.abs(exact.parameters - true)) < 1e-6
    # 5 µm position and 10 µrad orientation noise: within 4 σ of the reported uncertainty.
    noisy = poses.copy()
    noisy[:, :3] += rng.normal(0, 0.005, (150, 3))
    noisy[:, 3:] += np.degrees(rng.normal(0, 10e-6, (150, 3)))
    r = pkm.calibration.hexapod(nominal, poses=np.hstack([readings, noisy]), frame="world",
                                holdout=np.hstack([truth.ik(random_poses(30, 2)),
                                                   random_poses(30, 2)]))
    z = np.abs(r.parameters - true) / r.standard_deviation
    assert np.count_nonzero(z < 4) >= 40, z
    assert r.holdout["after"]["rms"] < 0.02 < r.holdout["before"]["rms"]


def test_points_and_distances_from_arrays_equal_their_files(s4, tmp_path):
    same = ("data", "worst_observations", "outputs")
    path = str(s4 / "tracker-point.csv")
    meta, points = read_table(path, POSE[:9])
    a = pkm.calibration.hexapod("hexapod-default", points=points, frame="tracker",
                                target_offset=vector(meta["smr offset mm"]))
    f = pkm.calibration.hexapod("hexapod-default", files=path)
    assert without(a.to_dict(), *same) == without(f.to_dict(), *same)
    assert a.observations["points"] == 105
    # Ball-bar lengths to a pivot, exact for a machine with known errors.
    nominal = pkm.load_machine("hexapod-default")
    truth = nominal.with_geometry(length_offsets=nominal.length_offsets + [0.3, -0.2, 0.1, 0, 0.2,
                                                                           -0.1])
    poses = random_poses(80, 5)
    pivot = np.array([10.0, -20.0, 0.5])
    rows = np.column_stack([truth.ik(poses), np.linalg.norm(poses[:, :3] - pivot, axis=1)])
    text = "# pivot mm: (10, -20, 0.5)\nl0,l1,l2,l3,l4,l5,distance\n" + "".join(
        ",".join(repr(float(v)) for v in r) + "\n" for r in rows)
    (tmp_path / "bar.csv").write_text(text)
    fixed = [n for n in pkm.calibration.hexapod(nominal, files=str(tmp_path / "bar.csv"),
                                                allow_large_changes=True).parameter_names
             if not n.startswith("offset")]
    a = pkm.calibration.hexapod(nominal, distances=rows, pivot=pivot, fix=fixed)
    f = pkm.calibration.hexapod(nominal, files=str(tmp_path / "bar.csv"), fix=fixed)
    assert without(a.to_dict(), *same) == without(f.to_dict(), *same)
    assert a.observations["distances"] == 80 and a.rank == 6
    assert np.allclose(a.machine.length_offsets, truth.length_offsets, atol=1e-6)


def test_hexapod_errors_raise_value_error_with_pkms_message(s4, tmp_path):
    _, poses = read_table(s4 / "tracker-pose.csv", POSE)
    cal = pkm.calibration.hexapod
    with pytest.raises(ValueError, match=r"poses: expected an array of shape \(N, 12\)"):
        cal("hexapod-default", poses=poses[:, :11], frame="tracker")
    bad = poses.copy()
    bad[3, 7] = np.nan
    with pytest.raises(ValueError, match="poses.*row 3.*not a finite number"):
        cal("hexapod-default", poses=bad, frame="tracker")
    with pytest.raises(ValueError, match="too few observations: 3 poses"):
        cal("hexapod-default", poses=poses[:3], frame="world")
    with pytest.raises(ValueError, match="do not state their frame"):
        cal("hexapod-default", poses=poses)
    with pytest.raises(ValueError, match="nosuch"):
        cal("hexapod-default", poses=poses, frame="tracker", fix=["nosuch"])
    with pytest.raises(ValueError, match="--loss must be none, huber or cauchy"):
        cal("hexapod-default", poses=poses, frame="tracker", loss="l1")
    with pytest.raises(ValueError, match="no-such-machine"):
        cal("no-such-machine", poses=poses, frame="tracker")
    with pytest.raises(ValueError, match="gauge_points"):
        cal("hexapod-default", gauges=np.zeros((3, 16)))
    with pytest.raises(ValueError, match="--data: give at least one"):
        cal("hexapod-default")
    with pytest.raises(ValueError, match="--db"):
        cal("hexapod-default", poses=poses, frame="tracker", db=tmp_path / "pkm.db")
    with pytest.raises(ValueError, match="target_offset"):
        cal("hexapod-default", poses=poses, frame="tracker", target_offset=[1, 2])
    with pytest.raises(ValueError, match="no-such-file"):
        cal("hexapod-default", files=[str(tmp_path / "no-such-file.csv")])


@pytest.mark.parametrize("options", [[], ["--monte-carlo", "3", "--threads", "1"],
                                     ["--backlash"]])
def test_hexapod_str_is_the_cli_text(pkm_binary, s4, tmp_path, monkeypatch, options):
    pose, hold = str(s4 / "tracker-pose.csv"), str(s4 / "tracker-holdout.csv")
    reg = str(s4 / "tracker-pose-registration.csv")
    cli = cli_text(pkm_binary, tmp_path / "cli", ["calibrate", "hexapod", "--machine",
                                                  "hexapod-default", "--data", pose,
                                                  "--holdout", hold, "--registration", reg,
                                                  "--out", "cal.json", *options])
    kw = {"monte_carlo": 3, "threads": 1} if "--monte-carlo" in options else {}
    kw["registration"] = reg
    if "--backlash" in options:
        kw["backlash"] = True
    (tmp_path / "py").mkdir()
    monkeypatch.chdir(tmp_path / "py")
    r = pkm.calibration.hexapod("hexapod-default", files=[pose], holdout=[hold], **kw)
    wrote = "wrote cal.json, cal.hal, cal.summary.json\n"
    assert masked(str(r)) + wrote == masked(cli)  # nothing written yet: no "wrote" line
    r.save("cal.json")
    assert masked(str(r)) == masked(cli)
    assert masked(str(pkm.calibration.hexapod("hexapod-default", files=[pose], holdout=[hold],
                                              out="cal.json", force=True, **kw))) == masked(cli)


# --- the seed 004 example ------------------------------------------------------------------


def run_example(out_dir, *args):
    p = subprocess.run([sys.executable, os.path.join(REPO, "examples", "python",
                                                     "calibrate_hexapod.py"), str(out_dir), *args],
                       capture_output=True, text=True, env=dict(os.environ, MPLBACKEND="Agg"))
    assert p.returncode == 0, p.stderr
    return p.stdout


def test_calibrate_hexapod_example(s4, tmp_path):
    out = run_example(tmp_path, "--data", str(s4))
    assert "held-out TCP error (50 poses)" in out and "calibrated machine written" in out
    m = re.search(r"positioning error (\S+) mm with the nominal controller, (\S+) mm calibrated",
                  out)
    assert float(m.group(1)) > 10 and float(m.group(2)) < 0.5  # seed 004: 12 mm -> < 0.5 mm
    assert os.path.exists(tmp_path / "seed004-calibrated.json")
    for plot in ("holdout.png", "x_move.png"):
        assert_plot(tmp_path / plot)
    if hasattr(pkm, "simulate"):
        # Simulated in Python: the same scenario and seed as `pkm simulate`, the same numbers.
        assert run_example(tmp_path) == out


def test_hexapod_without_registration_is_marked_and_writes_no_setp_block(s4, tmp_path):
    r = pkm.calibration.hexapod("hexapod-default", files=[str(s4 / "tracker-pose.csv")])
    assert r.to_dict()["world_frame"] == "unregistered"
    assert r.save(tmp_path / "u.json") == [str(tmp_path / "u.json"),
                                           str(tmp_path / "u.summary.json")]
    assert not (tmp_path / "u.hal").exists()
    with open(tmp_path / "u.json") as f:
        assert json.load(f)["world_frame"] == "unregistered"
