"""G-code programs (docs/gcode.md): ``moves`` as ``pkm gcode moves`` and ``run`` as ``pkm gcode
run``, on numpy arrays."""

from ._pkm.gcode import Moves, Run, moves, run  # noqa: F401

__all__ = ["Moves", "Run", "moves", "run"]
