"""Case files: one TOML file describes a joint and its load case (docs/casefile.md).

>>> from microslip.case import parse_case
>>> case = parse_case({"preset": "table1", "contact": {"friction": 0.5}})
>>> case.params.friction, case.amplitude()
(0.5, 111.25)
"""

from __future__ import annotations

from .model import Case, load_case, parse_case
from .schema import DEFAULT_AMPLITUDE_FRACTION, KEYS, PRESSURE_LAWS, Key
from .template import template
from .units import PLAUSIBLE, plausibility_warnings

__all__ = [
    "DEFAULT_AMPLITUDE_FRACTION",
    "KEYS",
    "PLAUSIBLE",
    "PRESSURE_LAWS",
    "Case",
    "Key",
    "load_case",
    "parse_case",
    "plausibility_warnings",
    "template",
]
