"""G-code programs (docs/gcode.md): ``moves`` as ``pkm gcode moves``, ``run`` as ``pkm gcode
run``, ``compensate`` as ``pkm gcode compensate`` and ``flatten`` as ``pkm gcode flatten``, on
numpy arrays and program texts."""

from ._pkm.gcode import Moves, Run, compensate, flatten, moves, run  # noqa: F401

__all__ = ["Moves", "Run", "compensate", "flatten", "moves", "run"]
