"""Measurement analysis: one function per ``pkm analyze <kind>`` (docs/analysis.md).

Each returns a :class:`AnalysisResult` whose attributes are the keys of the command's ``--json``
document.
"""

from ._pkm.metrology import (  # noqa: F401
    AnalysisResult,
    circle,
    circular,
    diagonals,
    iso230_2,
    parallelism,
    probe_offset,
    squareness,
    straightness,
)

__all__ = [
    "AnalysisResult",
    "circle",
    "circular",
    "diagonals",
    "iso230_2",
    "parallelism",
    "probe_offset",
    "squareness",
    "straightness",
]
