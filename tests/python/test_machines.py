"""pkm.load_machine, pkm.builtin_machines and the machine objects against the CLI."""

import json
import numpy as np
import pytest

import pkm


def test_builtin_machines_match_cli(run_cli):
    assert pkm.builtin_machines("hexapod") == run_cli(["hexapod", "machines"]).stdout.split()
    assert set(pkm.builtin_machines("hexapod")) < set(pkm.builtin_machines())
    assert "mxt700s-like" in pkm.builtin_machines("exechon")


def test_load_builtin_json_and_hal(tmp_path, run_cli):
    h = pkm.load_machine("hexapod-default")
    assert isinstance(h, pkm.Hexapod)
    assert h.source == "builtin:hexapod-default"
    assert h.base_joints.shape == (6, 3) and h.platform_joints.shape == (6, 3)
    assert h.stroke.shape == (6, 2) and h.home.shape == (6,)
    assert "pkm.Hexapod" in repr(h) and h.name in str(h)
    # The JSON file of the same machine gives the same geometry.
    path = tmp_path / "m.json"
    path.write_text(h.to_json())
    j = pkm.load_machine(path)
    np.testing.assert_array_equal(j.base_joints, h.base_joints)
    np.testing.assert_array_equal(j.platform_joints, h.platform_joints)
    hal = tmp_path / "kinematics.hal"  # a genhexkins setp block, as `pkm hexapod hal` writes it
    hal.write_text(run_cli(["hexapod", "hal", "-m", "hexapod-linuxcnc-sim"]).stdout)
    m = pkm.load_machine(hal)
    assert isinstance(m, pkm.Hexapod) and m.source.endswith("kinematics.hal")
    sim = pkm.load_machine("hexapod-linuxcnc-sim")
    np.testing.assert_array_equal(m.base_joints, sim.base_joints)
    e = pkm.load_machine("mxt700s-like")
    assert isinstance(e, pkm.Exechon) and e.hybrid
    assert json.loads(e.to_json())["type"] == "exechon"


def test_describe_matches_cli(run_cli):
    h = pkm.load_machine("hexapod-linuxcnc-sim")
    assert str(h) == run_cli(["hexapod", "describe", "-m", "hexapod-linuxcnc-sim"]).stdout
    assert h.to_json() == run_cli(["hexapod", "describe", "-m", "hexapod-linuxcnc-sim", "--json"]).stdout


def test_with_geometry_is_a_new_machine():
    h = pkm.load_machine()
    base = h.base_joints
    base[0, 0] += 1.0
    g = h.with_geometry(base_joints=base)
    assert g.base_joints[0, 0] == base[0, 0] and h.base_joints[0, 0] == base[0, 0] - 1.0
    pose = np.array([0, 0, 200, 0, 0, 0.0])
    assert g.ik(pose)[0] != h.ik(pose)[0]
    with pytest.raises(ValueError, match="base_joints"):
        h.with_geometry(base_joints=np.zeros((5, 3)))


def test_errors_name_the_input(tmp_path):
    with pytest.raises(ValueError, match="not a built-in") as e:
        pkm.load_machine("no-such-machine")
    for name in pkm.builtin_machines():  # every type's built-ins are offered
        assert name in str(e.value)
    bad = tmp_path / "bad.json"
    bad.write_text('{"type": "hexapod", "struts": 3}')
    with pytest.raises(ValueError, match="bad.json"):
        pkm.load_machine(str(bad))
