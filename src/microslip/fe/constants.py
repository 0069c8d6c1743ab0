"""Constants of the finite-element model shared by both solvers (one definition each)."""

from __future__ import annotations

__all__ = ["DEFAULT_NORMAL_SLOPE", "DEFAULT_STICK_SLOPE"]

#: Stick slope lambda of the penalty friction law, N/mm^3 (the shear traction per unit of
#: elastic slip before gross slip). 1e4 is within about 0.1 % of the rigid-stick limit on the
#: Table 1 bar (docs/validation.md, stick-slope study; docs/solver.md).
DEFAULT_STICK_SLOPE = 1.0e4
#: Slope of the linear pressure-overclosure law, N/mm^3 (penetration F_N/(L w K) ~ 1e-6 mm;
#: CalculiX only: the built-in solver holds the contact closed).
DEFAULT_NORMAL_SLOPE = 1.0e5
