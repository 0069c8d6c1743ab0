"""Plausibility of values for microslip's units (N, mm, MPa): one check for options and cases.

A value in the wrong unit passes every range check (a modulus of 2.1e11 "MPa" is positive and
finite) and gives a confident, wrong answer. :func:`plausibility_warnings` names values that
are far outside what a clamped metal joint in N-mm-MPa has; the thresholds are in
:data:`PLAUSIBLE`.
"""

from __future__ import annotations

import math
from collections.abc import Mapping

from ..errors import ParameterError

__all__ = ["PLAUSIBLE", "plausibility_warnings"]

#: Quantity -> (low, high, unit, what a value below low / above high suggests).
PLAUSIBLE: dict[str, tuple[float, float, str, str, str]] = {
    "modulus": (1e2, 1e7, "MPa", "GPa given as MPa?", "pascals given as MPa?"),
    "length": (0.05, 1e4, "mm", "metres given as mm?", "micrometres given as mm?"),
    "width": (0.05, 1e4, "mm", "metres given as mm?", "micrometres given as mm?"),
    "thickness": (0.05, 1e4, "mm", "metres given as mm?", "micrometres given as mm?"),
    "friction": (-math.inf, 2.0, "", "", "a friction coefficient above 2 is not a metal contact"),
}


def plausibility_warnings(values: Mapping[str, float | None], where: str = "") -> list[str]:
    """One sentence per implausible value of ``values`` (field name -> value, None skipped).

    A normal force <= 0 is an error, not a warning. ``where`` prefixes each sentence (for
    example ``"case clamp.toml: "``).

    >>> plausibility_warnings({"modulus": 2.1e11, "length": 30.0})
    ['modulus 2.1e+11 MPa is above 1e+07 MPa: pascals given as MPa?']
    """
    force = values.get("normal_force")
    if force is not None and not (math.isfinite(force) and force > 0):
        raise ParameterError(f"{where}normal_force must be finite and > 0 N, got {force!r}")
    out = []
    for name, (low, high, unit, below, above) in PLAUSIBLE.items():
        x = values.get(name)
        if x is None or not math.isfinite(x) or x <= 0:
            continue  # out of range altogether: the range check says so, in one line
        u = f" {unit}" if unit else ""
        if x < low:
            out.append(f"{where}{name} {x:g}{u} is below {low:g}{u}: {below}")
        elif x > high:
            out.append(f"{where}{name} {x:g}{u} is above {high:g}{u}: {above}")
    return out
