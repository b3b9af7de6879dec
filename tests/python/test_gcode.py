"""pkm.gcode.moves, run, compensate and flatten against `pkm gcode moves|run|compensate|flatten`
on the same program: the moves CSV, the joint CSV (--out) and the report (--report), the
compensated and flattened programs byte for byte with their notes, bounded memory, errors."""

import json
import math
import os

import numpy as np
import pytest

import pkm

from conftest import REPO, column, parse_csv

GCODE = os.path.join(REPO, "examples", "gcode")
HEXAPOD_PROGRAM = os.path.join(GCODE, "hexapod_contour.ngc")
EXECHON_PROGRAM = os.path.join(GCODE, "exechon_contour.ngc")
AXES = ["x", "y", "z", "a", "b", "c"]


@pytest.mark.parametrize("program,tools", [("drilling.ngc", None), ("pocket_loops.ngc", None),
                                           ("sphere.ngc", "tools.tbl")])
def test_moves_equal_cli(run_cli, program, tools):
    path = os.path.join(GCODE, program)
    options = ["--tool-table", os.path.join(GCODE, tools)] if tools else []
    out = run_cli(["gcode", "moves", path, *options])
    m = pkm.gcode.moves(path, tool_table=os.path.join(GCODE, tools) if tools else None)
    assert m.csv == out.stdout
    assert m.note in out.stderr
    rows = parse_csv(out.stdout)
    assert len(m) == len(rows) == len(m.line)
    np.testing.assert_array_equal(m.line, [int(r["line"]) for r in rows])
    assert m.line.dtype == np.int64
    assert list(m.kind) == [r["kind"] for r in rows]
    assert list(m.plane) == [r["plane"] for r in rows]
    np.testing.assert_array_equal(m.position, np.column_stack([column(rows, k) for k in AXES]))
    np.testing.assert_array_equal(m.center,
                                  np.column_stack([column(rows, k) for k in ("cx", "cy", "cz")]))
    np.testing.assert_array_equal(m.turns, column(rows, "turns"))
    np.testing.assert_array_equal(m.feed, column(rows, "feed"))
    assert np.isnan(m.feed[m.kind == "rapid"]).all()


def test_moves_from_text_and_options(run_cli, tmp_path):
    text = "G10 L2 P1 X100\nG0 X1 Y2\nG2 X11 Y2 I5 J0 F300\nM2\n"
    m = pkm.gcode.moves(text)
    assert list(m.kind) == ["rapid", "arc"]
    np.testing.assert_array_equal(m.center[1], [106, 2, np.nan])
    assert m.turns[1] == -1 and m.ended_by_m2 and m.lines == 4
    tools = os.path.join(GCODE, "tools.tbl")
    prog = tmp_path / "tool.ngc"
    prog.write_text("T1 M6\nG43\nG0 X0 Y0 Z0\n/G0 X5\nM2\n")
    cli = run_cli(["gcode", "moves", str(prog), "--tool-table", tools, "--block-delete"])
    mine = pkm.gcode.moves(str(prog), tool_table=tools, block_delete=True)
    assert mine.csv == cli.stdout and len(mine) == 1


@pytest.mark.parametrize("shape", ["sphere", "pocket", "drill", "face"])
def test_make_equals_the_cli_and_runs(run_cli, shape):
    names = [p[0] for p in pkm.gcode.shape_parameters(shape)]
    values = {names[0]: 3.0} if shape != "face" else {"step": 7.5}
    mine = pkm.gcode.make(shape, feed=450, **values)
    option = "--" + next(iter(values)).replace("_", "-")
    cli = run_cli(["gcode", "make", shape, option, str(next(iter(values.values()))), "--feed", "450"])
    assert mine == cli.stdout
    assert mine.startswith(f"G21 G90 G17 F450 (pkm gcode make {shape})\n") and mine.endswith("M2\n")
    assert pkm.gcode.run("hexapod-default", mine).ok


def test_make_refuses_unknown_parameters():
    with pytest.raises(ValueError, match="unknown parameter 'radius_mm'"):
        pkm.gcode.make("sphere", radius_mm=3)
    with pytest.raises(ValueError, match="unknown shape 'cube'"):
        pkm.gcode.make("cube")


def test_bad_program_line_raises_with_the_line(run_cli, tmp_path):
    bad = tmp_path / "bad.ngc"
    bad.write_text("G0 X0\nG1 X1 F100\nG1 X2 Q\n")
    p = run_cli(["gcode", "moves", str(bad)], check=False)
    assert p.returncode == 2
    with pytest.raises(ValueError, match=r"bad\.ngc:3: ") as e:
        pkm.gcode.moves(bad)
    assert str(e.value) in p.stderr
    with pytest.raises(ValueError, match=r"^upload:3: "):
        pkm.gcode.moves(bad.read_text(), name="upload")
    with pytest.raises(ValueError, match=r"^program:3: "):
        pkm.gcode.run("hexapod-default", bad.read_text())
    with pytest.raises(ValueError, match="cannot open"):
        pkm.gcode.moves(tmp_path / "missing.ngc")
    with pytest.raises(ValueError, match="tool-units"):
        pkm.gcode.moves("G0 X1\n", tool_units="furlong")


def joint_csv_and_report(run_cli, tmp_path, program, *args):
    joints, report = tmp_path / "j.csv", tmp_path / "r.json"
    p = run_cli(["gcode", "run", program, "--out", str(joints), "--report", str(report), *args],
                check=False)
    assert p.returncode in (0, 1), p.stderr
    return p, parse_csv(joints.read_text()), json.loads(report.read_text())


@pytest.mark.parametrize("machine,program,joints", [
    ("hexapod-default", HEXAPOD_PROGRAM, [f"q{i}" for i in range(6)]),
    ("mxt700s-like", EXECHON_PROGRAM, ["q1", "q2", "q3", "wrist_c", "wrist_a"]),
])
def test_run_equals_cli(run_cli, tmp_path, machine, program, joints):
    p, rows, report = joint_csv_and_report(run_cli, tmp_path, program, "--machine", machine)
    r = pkm.gcode.run(machine, program)
    assert r.report == report
    assert r.text == p.stdout and str(r) == p.stdout
    assert r.ok == report["ok"] and r.total_points == report["points"] == len(rows)
    np.testing.assert_array_equal(r.t, column(rows, "t"))
    np.testing.assert_array_equal(r.line, [int(x["line"]) for x in rows])
    np.testing.assert_array_equal(r.pose, np.column_stack([column(rows, k) for k in AXES]))
    np.testing.assert_array_equal(r.joints, np.column_stack([column(rows, k) for k in joints]))
    np.testing.assert_array_equal(r.index, np.arange(len(rows)))
    assert len(r.joint_names) == len(joints) == len(r.joint_units)


def test_run_on_loaded_machines_and_options(run_cli, tmp_path):
    _, _, report = joint_csv_and_report(run_cli, tmp_path, HEXAPOD_PROGRAM, "--tolerance", "0.05",
                                        "--max-joint-velocity", "150", "--strut-diameter", "40")
    hexapod = pkm.load_machine("hexapod-default")
    r = pkm.gcode.run(hexapod, HEXAPOD_PROGRAM, tolerance=0.05, max_joint_velocity=150,
                      strut_diameter=40)
    assert r.report == report
    # A changed geometry is what runs (longer struts: other stroke margins).
    longer = hexapod.with_geometry(length_offsets=hexapod.length_offsets + 5)
    changed = pkm.gcode.run(longer, HEXAPOD_PROGRAM)
    assert not np.array_equal(changed.joints, pkm.gcode.run(hexapod, HEXAPOD_PROGRAM).joints)
    exechon = pkm.load_machine("mxt700s-like")
    assert pkm.gcode.run(exechon, EXECHON_PROGRAM).report["machine_type"] == "exechon"


def test_run_writes_the_cli_files(run_cli, tmp_path):
    joints, report = tmp_path / "cli.csv", tmp_path / "cli.json"
    run_cli(["gcode", "run", HEXAPOD_PROGRAM, "--out", str(joints), "--report", str(report)])
    pkm.gcode.run("hexapod-default", HEXAPOD_PROGRAM, out=tmp_path / "j.csv",
                  report=tmp_path / "r.json")
    assert (tmp_path / "j.csv").read_bytes() == joints.read_bytes()
    assert (tmp_path / "r.json").read_bytes() == report.read_bytes()
    with pytest.raises(ValueError, match="exists; pass --force"):
        pkm.gcode.run("hexapod-default", HEXAPOD_PROGRAM, out=tmp_path / "j.csv")


def test_decimated_path_keeps_the_ends():
    full = pkm.gcode.run("hexapod-default", HEXAPOD_PROGRAM)
    r = pkm.gcode.run("hexapod-default", HEXAPOD_PROGRAM, path_points=20)
    assert 20 <= len(r.t) < len(full.t)
    assert r.index[0] == 0 and r.index[-1] == full.total_points - 1
    np.testing.assert_array_equal(r.joints, full.joints[r.index])
    np.testing.assert_array_equal(r.t, full.t[r.index])
    assert r.report == full.report  # the checks see every point
    none = pkm.gcode.run("hexapod-default", HEXAPOD_PROGRAM, path_points=0)
    assert none.joints.shape == (0, 0) and none.total_points == 0


def test_point_limit_bounds_memory(run_cli, tmp_path):
    program = tmp_path / "helix.ngc"
    program.write_text("G0 X0 Y0 Z200\nG1 X10 F600\nG2 X10 Y0 I-10 J0 Z150 P100000000\nM2\n")
    p = run_cli(["gcode", "run", str(program), "--max-points", "1000"], check=False)
    assert p.returncode == 2
    with pytest.raises(ValueError, match=r"helix\.ngc:3: .*--max-points") as e:
        pkm.gcode.run("hexapod-default", program, max_points=1000)
    assert str(e.value) in p.stderr
    with pytest.raises(ValueError, match="--max-points"):
        pkm.gcode.run("hexapod-default", program)  # the default limit, refused quickly


def test_violations_and_errors(run_cli, tmp_path):
    program = "G0 X0 Y0 Z200\nG1 Z100 F600\nG1 Z-300\nM2\n"
    r = pkm.gcode.run("hexapod-default", program)
    assert not r.ok and r.report["checks"]["stroke"]["violations"] > 0
    assert r.report["checks"]["stroke"]["first_violation"]["line"] == 3
    with pytest.raises(pkm.LimitError, match=r"program:3: stroke violated"):
        pkm.gcode.run("hexapod-default", program, raise_on_violation=True)
    with pytest.raises(ValueError, match="no-such-machine"):
        pkm.gcode.run("no-such-machine", program)
    with pytest.raises(ValueError, match="--orientation applies to Exechon"):
        pkm.gcode.run("hexapod-default", program, orientation="axes")
    with pytest.raises(ValueError, match="--tolerance must be > 0"):
        pkm.gcode.run("hexapod-default", program, tolerance=-1)
    with pytest.raises(ValueError, match="B.*Exechon has no B axis"):
        pkm.gcode.run("mxt700s-like", "G0 X0 Y0 Z50\nG1 B5 F100\nM2\n")
    with pytest.raises(ValueError, match="no motion"):
        pkm.gcode.run("hexapod-default", "G21\nM2\n")


def test_arguments_of_the_wrong_type_raise_value_error():
    with pytest.raises(ValueError, match=r"program .*required, got list"):
        pkm.gcode.moves(["G0 X1"])
    with pytest.raises(ValueError, match=r"machine .*required, got int"):
        pkm.gcode.run(3, HEXAPOD_PROGRAM)
    with pytest.raises(ValueError, match=r"tool_table: .*got float"):
        pkm.gcode.moves("G0 X1\n", tool_table=1.5)


def test_violations_listed_per_check():
    program = "G0 X0 Y0 Z200\nG1 Z100 F600\nG1 Z-300\nM2\n"
    r = pkm.gcode.run("hexapod-default", program, max_violations=3)
    stroke = [v for v in r.violations if v["check"] == "stroke"]
    assert 1 <= len(stroke) <= 3
    first = r.report["checks"]["stroke"]["first_violation"]
    assert stroke[0]["line"] == first["line"] == 3
    assert stroke[0]["item"] == first["item"] and stroke[0]["margin"] == first["margin"]
    np.testing.assert_array_equal(stroke[0]["position"], first["position"])
    assert all(v["margin"] < 0 for v in r.violations)
    assert pkm.gcode.run("hexapod-default", program).violations == []


# --- compensate and flatten ----------------------------------------------------------------


def renamed_machine(tmp_path, builtin, swaps):
    """A built-in machine file with its name + "-calibrated" and text replacements `swaps`, as
    `pkm calibrate --out` names a result (so the nominal machine is found from the name)."""
    with open(os.path.join(REPO, "data", "machines", builtin + ".json")) as f:
        text = f.read()
    for old, new in swaps:
        assert old in text, old
        text = text.replace(old, new, 1)
    path = tmp_path / (builtin + "-calibrated.json")
    path.write_text(text)
    return str(path)


def calibrated_hexapod(tmp_path):
    return renamed_machine(tmp_path, "hexapod-default", [
        ('"name": "pkm-hx1200"', '"name": "pkm-hx1200-calibrated"'),
        ('"tool_offset": [0, 0, -200]', '"tool_offset": [0.2, 0, -200.3]')])


def calibrated_exechon(tmp_path):
    return renamed_machine(tmp_path, "mxt700s-like", [
        ('"name": "mxt700s-like"', '"name": "mxt700s-like-calibrated"'),
        ('"dA": -443.4', '"dA": -443.1'), ('"tool_length": 200', '"tool_length": 200.2')])


def check_compensation(run_cli, program, cli_args, kwargs):
    """pkm.gcode.compensate(program, **kwargs) against `pkm gcode compensate PROGRAM CLI_ARGS`:
    the same program text, the note on standard error, and a report that matches it."""
    p = run_cli(["gcode", "compensate", program, *cli_args])
    text, report = pkm.gcode.compensate(program, **kwargs)
    assert text == p.stdout
    assert p.stderr == f"pkm: note: {report['note']}\n"
    assert report["desired"].shape == report["command"].shape == (len(report["line"]), 6)
    assert report["line"].dtype == np.int64
    xyz = np.linalg.norm(report["command"][:, :3] - report["desired"][:, :3], axis=1)
    assert math.isclose(xyz.max(), report["max_correction"], rel_tol=1e-12)
    return text, report


def test_compensate_hexapod_equals_the_cli(run_cli, tmp_path):
    cal = calibrated_hexapod(tmp_path)
    text, report = check_compensation(run_cli, HEXAPOD_PROGRAM, ["--machine", cal],
                                      {"machine": cal})
    assert "nominal pkm-hx1200 -> calibrated pkm-hx1200-calibrated" in report["note"]
    assert report["motion_lines"] > 0 and report["max_correction"] > 0.1
    check_compensation(run_cli, HEXAPOD_PROGRAM, ["--machine", cal],
                       {"machine": pkm.load_machine(cal)})  # a loaded machine, as its file
    check_compensation(run_cli, HEXAPOD_PROGRAM,
                       ["--machine", cal, "--nominal", "hexapod-default", "--tolerance", "0.05"],
                       {"machine": cal, "nominal": "hexapod-default", "tolerance": 0.05})
    # From the text, written to a file as --out writes it.
    with open(HEXAPOD_PROGRAM) as f:
        source = f.read()
    out = tmp_path / "comp.ngc"
    mine, _ = pkm.gcode.compensate(source, machine=cal, out=out, name=HEXAPOD_PROGRAM)
    assert mine == text and out.read_text() == text
    with pytest.raises(ValueError, match="exists; pass --force"):
        pkm.gcode.compensate(source, machine=cal, out=out)
    pkm.gcode.compensate(source, machine=cal, out=out, force=True)


@pytest.mark.parametrize("orientation", ["vector", "axes"])
def test_compensate_exechon_equals_the_cli(run_cli, tmp_path, orientation):
    cal = calibrated_exechon(tmp_path)
    _, report = check_compensation(run_cli, EXECHON_PROGRAM,
                                   ["--machine", cal, "--orientation", orientation],
                                   {"machine": cal, "orientation": orientation})
    assert f"--orientation {orientation}" in report["note"]
    check_compensation(run_cli, EXECHON_PROGRAM, ["--machine", cal, "--orientation", orientation],
                       {"machine": pkm.load_machine(cal), "orientation": orientation})


def test_compensate_hybrid_frame_equals_the_cli(run_cli, tmp_path):
    frame = tmp_path / "frame.txt"
    frame.write_text("# pkm-base-frame\nbase_rpy_rad = 0 0 0.003\nbase_offset_mm = 0 0 0\n"
                     "per_x2 = 0 -4e-05 0\n")
    program = tmp_path / "p.ngc"
    program.write_text("G21 G90\nN5 G1 X10 Y20 Z-1 F500 (cut)\nM2\n")
    for extra, kw in (([], {}), (["--base-frame-not-in-controller"],
                                 {"base_frame_not_in_controller": True})):
        text, _ = check_compensation(
            run_cli, str(program), ["--hybrid-frame", str(frame), "--x2", "1000", *extra],
            dict(hybrid_frame=frame, x2=1000, **kw))
        assert "(cut)" in text


def test_compensate_errors_raise_with_pkms_message(run_cli, tmp_path):
    cal = calibrated_hexapod(tmp_path)
    bad = tmp_path / "b.ngc"
    bad.write_text("G0 X0 Y0 Z200\nG92 X[#1]\n")  # a non-constant G92 word: refused
    p = run_cli(["gcode", "compensate", "--machine", cal, str(bad)], check=False)
    assert p.returncode == 2
    message = p.stderr.strip().removeprefix("pkm: error: ")
    with pytest.raises(ValueError) as e:
        pkm.gcode.compensate(bad, machine=cal)
    assert str(e.value) == message and "b.ngc:2:" in message
    with pytest.raises(ValueError, match="--machine CAL.json"):
        pkm.gcode.compensate("G0 X0\n")
    with pytest.raises(ValueError, match="--x2"):
        pkm.gcode.compensate("G0 X0\n", hybrid_frame=bad)
    with pytest.raises(ValueError, match="--tolerance must be > 0"):
        pkm.gcode.compensate("G0 X0\n", machine=cal, tolerance=-1)
    with pytest.raises(ValueError, match="--orientation"):
        pkm.gcode.compensate("G0 X0\n", machine=cal, orientation="axes")
    with pytest.raises(ValueError, match="--nominal"):
        pkm.gcode.compensate("G0 X0 Y0 Z200\nM2\n", machine="hexapod-default")
    with pytest.raises(ValueError, match="cannot open"):
        pkm.gcode.compensate(tmp_path / "missing.ngc", machine=cal)
    with pytest.raises(ValueError, match="orientation is for Exechon machines; pkm-hx1200-cal"):
        pkm.gcode.compensate("G0 X0\n", machine=pkm.load_machine(cal), orientation="axes")
    with pytest.raises(ValueError, match="machine"):
        pkm.gcode.compensate("G0 X0\n", machine=3)


@pytest.mark.parametrize("program,tools", [("sphere.ngc", "tools.tbl"),
                                           ("pocket_loops.ngc", None), ("drilling.ngc", None)])
def test_flatten_equals_the_cli(run_cli, tmp_path, program, tools):
    path = os.path.join(GCODE, program)
    options = ["--tool-table", os.path.join(GCODE, tools)] if tools else []
    p = run_cli(["gcode", "flatten", path, *options])
    text, report = pkm.gcode.flatten(path, tool_table=os.path.join(GCODE, tools) if tools else None)
    assert text == p.stdout
    assert p.stderr == f"pkm: note: {report['note']}\n"
    assert len(report["source_line"]) == text.count("\n")
    with open(path) as f:
        source = f.read().splitlines()
    assert 1 <= report["source_line"].min() and report["source_line"].max() <= len(source)
    # Flattening is idempotent, and the flat program makes the same moves.
    again, _ = pkm.gcode.flatten(text, tool_table=os.path.join(GCODE, tools) if tools else None)
    assert again == text
    out = tmp_path / "flat.ngc"
    pkm.gcode.flatten(path, tool_table=os.path.join(GCODE, tools) if tools else None, out=out)
    assert out.read_text() == text


def test_flatten_options_and_errors(run_cli, tmp_path):
    program = "o100 repeat [3]\nG1 X[#5420 + 1] F100\n/G0 Y1\no100 endrepeat\nM2\n"
    text, report = pkm.gcode.flatten(program, block_delete=True)
    assert text.splitlines() == ["G1 X1 F100", "G1 X2 F100", "G1 X3 F100", "M2"]
    assert report["had_o_words"] and report["blocks"] == 4
    (tmp_path / "p.ngc").write_text(program)
    p = run_cli(["gcode", "flatten", str(tmp_path / "p.ngc"), "--block-delete"])
    assert pkm.gcode.flatten(tmp_path / "p.ngc", block_delete=True)[0] == p.stdout
    with pytest.raises(ValueError, match="program:2:"):
        pkm.gcode.flatten("G0 X0\nG1 X1 Q\n")
    with pytest.raises(ValueError, match="loop"):
        pkm.gcode.flatten("o1 while [1]\nG0 X1\no1 endwhile\n", max_iterations=10)


def test_moves_and_flatten_take_an_ini(tmp_path):
    (tmp_path / "m.var").write_text("5220 2\n5241 10\n")
    ini = tmp_path / "m.ini"
    ini.write_text("[RS274NGC]\nPARAMETER_FILE = m.var\n[SETUP]\nXPOS = 3\n")
    program = "G0 X#<_ini[setup]xpos>\nM2\n"
    m = pkm.gcode.moves(program, ini=ini)
    assert m.position[0][0] == 13.0  # G55 from the parameter file, X from the INI
    text, _ = pkm.gcode.flatten(program, ini=str(ini))
    assert text.splitlines()[0] == "G0 X3"
    with pytest.raises(ValueError, match=r"program:1: named parameter"):
        pkm.gcode.moves(program)
