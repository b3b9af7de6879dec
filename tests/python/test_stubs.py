"""The type stubs (python/pkm/*.pyi, docs/python.md "Type stubs"): installed next to the module
with py.typed, valid Python, an entry for every public callable of the module (functions, classes
and their public methods and properties, found by introspection), and the same as
scripts/python_stubs.py writes from the built module (so a changed binding fails here until its
stubs are regenerated)."""

import ast
import inspect
import os
import subprocess
import sys

import pytest

import pkm
from conftest import REPO

MODULES = {"__init__.pyi": pkm, "calibration.pyi": pkm.calibration, "gcode.pyi": pkm.gcode,
           "metrology.pyi": pkm.metrology}
PACKAGE = os.path.dirname(pkm.__file__)


def stub_tree(file):
    with open(os.path.join(PACKAGE, file)) as f:
        return ast.parse(f.read(), filename=file)


def stub_entries(tree):
    """{name: set of member names} of the stub's top-level functions and classes."""
    entries = {}
    for node in tree.body:
        if isinstance(node, ast.FunctionDef):
            entries[node.name] = set()
        elif isinstance(node, ast.ClassDef):
            entries[node.name] = {n.name for n in node.body if isinstance(n, ast.FunctionDef)}
    return entries


def public_members(cls):
    return {n for n, v in vars(cls).items()
            if (not n.startswith("_") and (callable(v) or isinstance(v, property)))
            or n == "__getattr__"}


def test_stubs_are_installed_with_py_typed():
    assert os.path.exists(os.path.join(PACKAGE, "py.typed"))
    for file in MODULES:
        assert os.path.exists(os.path.join(PACKAGE, file)), file


@pytest.mark.parametrize("file", sorted(MODULES))
def test_every_public_callable_has_a_stub_entry(file):
    module = MODULES[file]
    entries = stub_entries(stub_tree(file))
    for name in module.__all__:
        obj = getattr(module, name)
        if inspect.ismodule(obj):
            continue
        assert name in entries, f"{module.__name__}.{name} has no stub"
        if inspect.isclass(obj) and not issubclass(obj, BaseException):
            missing = public_members(obj) - entries[name]
            assert not missing, f"{module.__name__}.{name}: no stub for {sorted(missing)}"


def test_stub_signatures_name_the_keywords():
    """A spot check of what the generator read: parameter names and keyword-only markers."""
    entries = {n.name: n for n in stub_tree("gcode.pyi").body if isinstance(n, ast.FunctionDef)}
    compensate = entries["compensate"].args
    assert [a.arg for a in compensate.args] == ["program"]
    assert {"machine", "nominal", "hybrid_frame", "x2", "tolerance", "out"} <= \
        {a.arg for a in compensate.kwonlyargs}
    hexapod = next(n for n in stub_tree("__init__.pyi").body
                   if isinstance(n, ast.ClassDef) and n.name == "Hexapod")
    ik = next(n for n in hexapod.body if isinstance(n, ast.FunctionDef) and n.name == "ik")
    assert ik.args.args[0].arg == "self" and ik.args.args[1].arg == "poses"


def test_stubs_are_up_to_date():
    p = subprocess.run([sys.executable, os.path.join(REPO, "scripts", "python_stubs.py"),
                        "--check", os.path.join(REPO, "python", "pkm")],
                       capture_output=True, text=True)
    assert p.returncode == 0, p.stdout + p.stderr
