"""Plausibility of values for microslip's units (N, mm, MPa): one check for options and cases.

A value in the wrong unit passes every range check (a modulus of 2.1e11 "MPa" is positive and
finite) and gives a confident, wrong answer. Two tiers:

* a value that cannot be meant in N, mm, MPa and kg/m^3 is an error, one line naming the
  likely unit mistake (:data:`IMPOSSIBLE`: a modulus above any solid's, in pascals; a density
  outside every engineering material's, in t/mm^3 or g/cm^3);
* a value far outside what a clamped metal joint has is a warning
  (:func:`plausibility_warnings`, the bands of :data:`PLAUSIBLE`).

The checks that need the mesh (a part under 1 mm across, a clamping pressure above the
modulus) are :mod:`microslip.case.meshroles`'s.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

from ..conventions import DENSITY_RANGE
from ..errors import ParameterError

__all__ = ["DENSITY_RANGE", "IMPOSSIBLE", "PLAUSIBLE", "check_impossible", "density",
           "plausibility_warnings"]

#: Quantity -> (lowest, highest meant value, unit, what a value below / above suggests):
#: outside, the value is an error. The stiffest solid (diamond) has about 1.2e6 MPa; a part
#: meant as rigid is modelled some 1000 times stiffer than steel (1e8 MPa), while a metal's
#: or a polymer's modulus in pascals is 1e9 or more. Between 1e7 and 1e9 MPa it warns
#: (:data:`PLAUSIBLE`).
IMPOSSIBLE: dict[str, tuple[float, float, str, str, str]] = {
    "modulus": (0.0, 1e9, "MPa", "", "pascals given as MPa? (70000 MPa is 7e10 Pa)"),
    "density": (*DENSITY_RANGE, "kg/m^3", "t/mm^3 or g/cm^3 given as kg/m^3? (7850 kg/m^3 is "
                "7.85e-9 t/mm^3 and 7.85 g/cm^3)", "not a solid's density"),
}


def check_impossible(values: Mapping[str, Any], where: str = "",
                     names: Mapping[str, str] | None = None) -> None:
    """Raise one ParameterError line for the first value of ``values`` (field -> value, None
    skipped) that cannot be meant (:data:`IMPOSSIBLE`); ``names`` spell the fields in the
    message (``--modulus``), ``where`` prefixes it.

    >>> check_impossible({"modulus": 2.1e11})  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    microslip.errors.ParameterError: modulus 2.1e+11 MPa is above 1e+09 MPa, ... pascals ...
    """
    for name, (low, high, unit, below, above) in IMPOSSIBLE.items():
        x = values.get(name)
        if x is None or isinstance(x, bool) or not isinstance(x, (int, float)) \
                or not math.isfinite(x) or x <= 0:
            continue  # not a number or out of range altogether: the range check says so
        shown = (names or {}).get(name, name)
        if x > high:
            what = ("far stiffer than any solid" if name == "modulus"
                    else "heavier than any solid")
            raise ParameterError(f"{where}{shown} {x:g} {unit} is above {high:g} {unit}, "
                                 f"{what}: {above}")
        if x < low:
            raise ParameterError(f"{where}{shown} {x:g} {unit} is below {low:g} {unit} of any "
                                 f"engineering material: {below}")


def density(name: str, value: Any) -> float:
    """A check of a case file's density (kg/m^3): a finite number in :data:`DENSITY_RANGE`."""
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not (
            math.isfinite(value) and value > 0):
        raise ParameterError(f"case key {name} must be a finite number > 0 (kg/m^3), got "
                             f"{value!r}")
    check_impossible({"density": float(value)}, names={"density": f"case key {name} ="})
    return float(value)

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
