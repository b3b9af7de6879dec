"""pkm.simulate and pkm.scenarios against `pkm simulate` on the same scenario and seed: the same
files byte for byte, tables equal to the written CSVs, truth, scenario dicts, errors."""

import json
import os

import numpy as np
import pytest

import pkm

from conftest import parse_csv


def cli_files(run_cli, tmp_path, scenario, seed):
    out = tmp_path / "cli"
    run_cli(["simulate", scenario, "--seed", str(seed), "--out", str(out)])
    return out


def csv_body(text):
    """The rows of a measurement file (the '#' metadata lines left out)."""
    return parse_csv("".join(line for line in text.splitlines(True) if not line.startswith("#")))


@pytest.mark.parametrize("scenario", ["seed003-probe-offset", "seed004-hexapod-calibration",
                                      "exechon-calibration"])
def test_simulate_equals_cli(run_cli, tmp_path, scenario):
    out = cli_files(run_cli, tmp_path, scenario, 11)
    sim = pkm.simulate(scenario, seed=11)
    assert sim.scenario == scenario and sim.seed == 11
    assert sorted(sim.files) == sorted(os.listdir(out))
    for name, text in sim.files.items():
        assert (out / name).read_text() == text, name
    assert sim.truth == json.loads((out / "truth.json").read_text())
    assert sim.scenario_doc == json.loads((out / "scenario.json").read_text())
    assert sorted(sim.tables) == sorted(n[:-4] for n in sim.files if n.endswith(".csv"))
    for stem, table in sim.tables.items():
        rows = csv_body((out / (stem + ".csv")).read_text())
        assert list(table) == list(rows[0])
        for key, values in table.items():
            assert len(values) == len(rows)
            cli = [r[key] for r in rows]
            if values.dtype.kind == "f":  # numbers: the printed value exactly
                expected = np.array([float(v) if v != "" else np.nan for v in cli])
                np.testing.assert_array_equal(values, expected, err_msg=f"{stem}.{key}")
            else:
                assert list(values) == cli, f"{stem}.{key}"


def test_tables_metadata_and_kinds():
    sim = pkm.simulate("seed004-hexapod-calibration", seed=3)
    run1 = sim.tables["linear-x_run1"]
    assert run1["target_mm"].dtype == np.float64
    assert set(run1["direction"]) <= {"+", "-"}
    assert sim.metadata["linear-x_run1"]["scenario"] == "seed004-hexapod-calibration"
    assert sim.metadata["linear-x_run1"]["seed"] == "3"
    assert "truth" not in sim.tables and "scenario" not in sim.tables
    assert "seed003" in repr(pkm.simulate("seed003-probe-offset"))


def test_default_seed_and_another_seed():
    a = pkm.simulate("seed003-probe-offset")
    assert a.seed == a.scenario_doc["seed"]
    b = pkm.simulate("seed003-probe-offset", seed=a.seed + 1)
    assert a.files["truth.json"] != b.files["truth.json"] or any(
        a.files[n] != b.files[n] for n in a.files if n.endswith(".csv"))


def test_scenario_as_dict_and_file(tmp_path):
    a = pkm.simulate("seed003-probe-offset", seed=5)
    b = pkm.simulate(a.scenario_doc)  # scenario.json holds the seed used
    assert b.files == a.files
    path = tmp_path / "mine.json"
    path.write_text(a.files["scenario.json"])
    assert pkm.simulate(path).files == a.files
    assert pkm.simulate(str(path), seed=5).files == a.files


def test_write_as_the_cli(run_cli, tmp_path):
    out = cli_files(run_cli, tmp_path, "seed003-probe-offset", 2)
    mine = tmp_path / "mine"
    sim = pkm.simulate("seed003-probe-offset", seed=2, out=mine)
    for name in sim.files:
        assert (mine / name).read_bytes() == (out / name).read_bytes()
    with pytest.raises(ValueError, match="exists; refusing to overwrite"):
        sim.write(mine)
    (mine / "truth.json").write_text("edited")
    sim.write(mine, force=True)
    assert (mine / "truth.json").read_text() == sim.files["truth.json"]


def test_errors_carry_pkm_messages(run_cli, tmp_path):
    p = run_cli(["simulate", "no-such-scenario", "--out", str(tmp_path / "x")], check=False)
    assert p.returncode == 2
    with pytest.raises(ValueError) as e:
        pkm.simulate("no-such-scenario")
    assert str(e.value) in p.stderr
    bad = tmp_path / "bad.json"
    bad.write_text('{\n  "type": "simulation_scenario",\n  "teleport": 1\n}\n')
    p = run_cli(["simulate", str(bad), "--out", str(tmp_path / "y")], check=False)
    with pytest.raises(ValueError, match=r"bad.json:\d+") as e:
        pkm.simulate(bad)
    assert str(e.value) in p.stderr
    with pytest.raises(ValueError, match=r"^scenario:\d+"):
        pkm.simulate({"type": "simulation_scenario", "teleport": 1})
    with pytest.raises(ValueError, match="seed"):
        pkm.simulate("seed003-probe-offset", seed=-1)
    with pytest.raises(ValueError, match="seed"):
        pkm.simulate("seed003-probe-offset", seed=1.5)


def test_scenarios_list_the_cli(run_cli):
    lines = run_cli(["simulate", "--list"]).stdout.splitlines()
    listed = [f"{s['name']}\t{s['measurements']} measurements\t{s['description']}"
              for s in pkm.scenarios()]
    assert listed == lines


def test_arguments_of_the_wrong_type_raise_value_error():
    with pytest.raises(ValueError, match=r"scenario .*required, got list"):
        pkm.simulate(["seed003-probe-offset"])
    with pytest.raises(ValueError, match=r"out: .*got int"):
        pkm.simulate("seed003-probe-offset", out=3)
