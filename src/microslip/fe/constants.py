"""Constants of the finite-element model shared by both solvers (one definition each)."""

from __future__ import annotations

from ..conventions import DEFAULT_STICK_SLOPE

__all__ = ["CCX_CONTACT_FORMULATIONS", "DEFAULT_NORMAL_SLOPE", "DEFAULT_STICK_SLOPE"]

#: Stick slope lambda of the penalty friction law, N/mm^3: defined with the other shared
#: defaults in :mod:`microslip.conventions` (the 1-D models' fit and the case files take it
#: too, without importing the FE).
#: Slope of the linear pressure-overclosure law, N/mm^3 (penetration F_N/(L w K) ~ 1e-6 mm;
#: CalculiX only: the built-in solver holds the contact closed).
DEFAULT_NORMAL_SLOPE = 1.0e5
#: CalculiX's contact formulations on a mesh of the user's own, the first the one that solves
#: the built-in solver's equations (validate --mesh's default); what each is:
#: :data:`microslip.fe.calculix.meshdeck.CONTACT_FORMULATIONS`.
CCX_CONTACT_FORMULATIONS = ("node-to-surface", "face-to-face")
