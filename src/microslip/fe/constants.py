"""Constants of the finite-element model shared by both solvers (one definition each)."""

from __future__ import annotations

from ..conventions import DEFAULT_STICK_SLOPE

__all__ = ["DEFAULT_NORMAL_CONTACT", "DEFAULT_NORMAL_SLOPE", "DEFAULT_STICK_SLOPE"]

#: Stick slope lambda of the penalty friction law, N/mm^3: defined with the other shared
#: defaults in :mod:`microslip.conventions` (the 1-D models' fit and the case files take it
#: too, without importing the FE).
#: Slope of the linear pressure-overclosure law, N/mm^3 (penetration F_N/(L w K) ~ 1e-6 mm):
#: ``penalty`` normal contact, both solvers.
DEFAULT_NORMAL_SLOPE = 1.0e5
#: Normal contact of a clamp on a mesh unless one is named: ``fixed``, the clamping step's
#: normal forces held (the paper's reading). CalculiX models ``penalty`` only and refuses it
#: (docs/interpretation.md, "The mesh structure's library home").
DEFAULT_NORMAL_CONTACT = "fixed"
