"""Constants of the finite-element model shared by both solvers (one definition each)."""

from __future__ import annotations

from ..conventions import (
    CCX_CONTACT_FORMULATIONS,
    DEFAULT_NORMAL_CONTACT,
    DEFAULT_NORMAL_SLOPE,
    DEFAULT_STICK_SLOPE,
)

__all__ = ["CCX_CONTACT_FORMULATIONS", "DEFAULT_NORMAL_CONTACT", "DEFAULT_NORMAL_SLOPE",
           "DEFAULT_STICK_SLOPE"]

#: Stick slope lambda of the penalty friction law, N/mm^3: defined with the other shared
#: defaults in :mod:`microslip.conventions` (the 1-D models' fit and the case files take it
#: too, without importing the FE).
#: The normal contact's default and its penalty slope, and CalculiX's contact formulations:
#: defined in :mod:`microslip.conventions` (the option table and the case files take them
#: without importing the FE).
