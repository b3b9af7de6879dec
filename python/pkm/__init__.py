"""pkm: kinematics, metrology and calibration of parallel kinematic machine tools.

Hexapods (6-UPS Stewart platforms) and Exechon tripods from numpy: the same library as the
``pkm`` command line, with the same conventions (lengths in the machine's unit, angles in
degrees, LinuxCNC roll-pitch-yaw poses x, y, z, a, b, c). See docs/python.md.
"""

from ._pkm import (  # noqa: F401
    CampaignSummary,
    ConvergenceError,
    Exechon,
    Hexapod,
    LimitError,
    Simulation,
    builtin_machines,
    campaign_sensitivity,
    campaigns,
    load_machine,
    run_campaign,
    scenarios,
    simulate,
)
from . import calibration, gcode, metrology  # noqa: E402,F401

__all__ = [
    "CampaignSummary",
    "ConvergenceError",
    "Exechon",
    "Hexapod",
    "LimitError",
    "Simulation",
    "builtin_machines",
    "calibration",
    "campaign_sensitivity",
    "campaigns",
    "gcode",
    "load_machine",
    "metrology",
    "run_campaign",
    "scenarios",
    "simulate",
]
