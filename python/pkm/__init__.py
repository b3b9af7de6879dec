"""pkm: kinematics, metrology and calibration of parallel kinematic machine tools.

Hexapods (6-UPS Stewart platforms) and Exechon tripods from numpy: the same library as the
``pkm`` command line, with the same conventions (lengths in the machine's unit, angles in
degrees, LinuxCNC roll-pitch-yaw poses x, y, z, a, b, c). See docs/python.md.
"""

from ._pkm import (  # noqa: F401
    ConvergenceError,
    Exechon,
    Hexapod,
    LimitError,
    builtin_machines,
    load_machine,
)
from . import calibration, metrology  # noqa: E402,F401

__all__ = [
    "ConvergenceError",
    "Exechon",
    "Hexapod",
    "LimitError",
    "builtin_machines",
    "calibration",
    "load_machine",
    "metrology",
]
