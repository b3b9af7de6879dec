"""G-code programs (docs/gcode.md): ``moves`` as ``pkm gcode moves``, ``run`` as ``pkm gcode
run``, ``compensate`` as ``pkm gcode compensate``, ``flatten`` as ``pkm gcode flatten`` and
``make`` as ``pkm gcode make`` (the composite machining commands), on numpy arrays and program
texts."""

from ._pkm.gcode import (  # noqa: F401
    Moves,
    Run,
    compensate,
    flatten,
    make,
    moves,
    run,
    shape_parameters,
)

__all__ = ["Moves", "Run", "compensate", "flatten", "make", "moves", "run", "shape_parameters"]
