"""Kinematic calibration and calibration pose planning (docs/calibration.md, docs/python.md).

``hexapod`` and ``exechon`` run ``pkm calibrate hexapod`` / ``pkm calibrate exechon`` on arrays
of observations (or files) and return a :class:`CalibrationResult`; ``plan_poses`` runs
``pkm plan-poses`` and returns a :class:`PosePlan`.
"""

from ._pkm.calibration import (  # noqa: F401
    CalibrationResult,
    PosePlan,
    exechon,
    hexapod,
    plan_poses,
)

__all__ = ["CalibrationResult", "PosePlan", "exechon", "hexapod", "plan_poses"]
