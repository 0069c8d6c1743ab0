"""The keys of a case file: section, name, unit, range, default, meaning (one table).

Every key a case file may hold is one :class:`Key` in :data:`KEYS`; the parser, the
commented template and the documentation (docs/casefile.md) all read this table. A key is
addressed by its dotted name, ``section.name`` (``geometry.length``, ``load.planar.ratio``);
top-level keys have no section.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from ..errors import ParameterError
from ..fe.case import DEFAULT_STICK_SLOPE
from ..params import PRESETS

__all__ = [
    "CLAMP_KEYS",
    "DEFAULT_AMPLITUDE_FRACTION",
    "FUTURE_PRESSURE_LAWS",
    "KEYS",
    "PRESSURE_LAWS",
    "SECTIONS",
    "Key",
]

#: Default load amplitude of a case, as a fraction of the slip limit mu F_N of its clamp.
DEFAULT_AMPLITUDE_FRACTION = 0.5

#: Clamping pressure laws accepted now, and those planned (issue 11) but not yet available.
PRESSURE_LAWS = ("uniform", "parabolic", "power:N[:EDGE]", "table:FILE.csv")
FUTURE_PRESSURE_LAWS: tuple[str, ...] = ()

#: Uniaxial load cases of a case file.
LOAD_MODELS = ("tip", "centre")

Check = Callable[[str, Any], Any]


def _number(name: str, value: Any, unit: str) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise ParameterError(f"case key {name} must be a number{_u(unit)}, got {value!r}")
    x = float(value)
    if not math.isfinite(x):
        raise ParameterError(f"case key {name} must be finite{_u(unit)}, got {value!r}")
    return x


def _u(unit: str) -> str:
    return f" ({unit})" if unit else ""


def positive(unit: str = "", upper: float = math.inf) -> Check:
    """A check: a finite number in (0, upper)."""
    def check(name: str, value: Any) -> float:
        x = _number(name, value, unit)
        if not 0.0 < x < upper:
            rng = "> 0" if upper == math.inf else f"in (0, {upper:g})"
            raise ParameterError(f"case key {name} must be {rng}{_u(unit)}, got {value!r}")
        return x
    return check


def interval(low: float, high: float, unit: str = "", closed: bool = False) -> Check:
    """A check: a finite number in [low, high), or [low, high] if ``closed``."""
    def check(name: str, value: Any) -> float:
        x = _number(name, value, unit)
        if not (low <= x < high or (closed and x == high)):
            raise ParameterError(f"case key {name} must be in [{low:g}, {high:g}"
                                 f"{']' if closed else ')'}{_u(unit)}, got {value!r}")
        return x
    return check


def text(name: str, value: Any) -> str:
    if not isinstance(value, str):
        raise ParameterError(f"case key {name} must be a string, got {value!r}")
    return value


def choice(options: tuple[str, ...], later: tuple[str, ...] = ()) -> Check:
    """A check: one of ``options``; names in ``later`` are planned but refused for now."""
    def check(name: str, value: Any) -> str:
        s = text(name, value)
        if s in later:
            raise ParameterError(f"case key {name} = {s!r} is not yet available; accepted now: "
                                 f"{', '.join(options)} (planned: {', '.join(later)})")
        if s not in options:
            raise ParameterError(f"case key {name} must be one of {', '.join(options)}, "
                                 f"got {s!r}")
        return s
    return check


def pressure_text(name: str, value: Any) -> str:
    """A check: a pressure law as ``--pressure-law`` takes it (uniform, parabolic,
    power:N[:EDGE], table:FILE.csv); the law itself is built when a command reads it."""
    s = text(name, value)
    if s in ("uniform", "parabolic") or (s.startswith(("power:", "table:")) and len(s) > 6):
        return s
    raise ParameterError(f"case key {name} must be one of {', '.join(PRESSURE_LAWS)}, "
                         f"got {s!r}")


@dataclass(frozen=True)
class Key:
    """One key of a case file."""

    section: str
    name: str
    check: Check
    unit: str
    range: str
    default: Any
    meaning: str

    @property
    def dotted(self) -> str:
        return f"{self.section}.{self.name}" if self.section else self.name


#: Sections of a case file, in the order of the template, with what they describe.
SECTIONS = {
    "": "the case",
    "geometry": "clamped zone (paper, Fig. 3)",
    "material": "the clamped body",
    "contact": "the interface",
    "clamping": "the clamping load",
    "load": "uniaxial load case (read by loop, fe, sweep, validate)",
    "load.planar": "planar load case (read by planar)",
}

_FROM_PRESET = "from preset"

KEYS: tuple[Key, ...] = (
    Key("", "name", text, "", "any text", "", "short name of the case, shown in outputs"),
    Key("", "description", text, "", "any text", "", "what the case is"),
    Key("", "preset", choice(tuple(sorted(PRESETS))), "", " | ".join(sorted(PRESETS)), None,
        "paper parameter set used as the base that the keys below override"),
    Key("geometry", "length", positive("mm"), "mm", "> 0", _FROM_PRESET,
        "clamped length L along the load"),
    Key("geometry", "width", positive("mm"), "mm", "> 0", _FROM_PRESET,
        "depth w of the cross-section"),
    Key("geometry", "thickness", positive("mm"), "mm", "> 0", _FROM_PRESET,
        "thickness t of the cross-section"),
    Key("material", "modulus", positive("MPa"), "MPa", "> 0", _FROM_PRESET,
        "Young's modulus E"),
    Key("material", "poisson_ratio", interval(0.0, 0.5), "", "[0, 0.5)", _FROM_PRESET,
        "Poisson's ratio nu"),
    Key("contact", "friction", positive(), "", "> 0", _FROM_PRESET,
        "Coulomb friction coefficient mu"),
    Key("contact", "stick_slope", positive("N/mm^3"), "N/mm^3", "> 0", DEFAULT_STICK_SLOPE,
        "tangential contact stiffness per area before slip (FE stick slope lambda; machined "
        "metal 1e3-1e5); given, the 1-D models sit on this elastic layer, omitted they keep "
        "the paper's rigid foundation while fe uses the default"),
    Key("clamping", "normal_force", positive("N"), "N", "> 0", _FROM_PRESET,
        "clamping (normal) force F_N"),
    Key("clamping", "pressure", pressure_text, "", " | ".join(PRESSURE_LAWS), "uniform",
        "clamping pressure law along the length (as --pressure-law; uniform is the paper's)"),
    Key("load", "model", choice(LOAD_MODELS), "", " | ".join(LOAD_MODELS), "tip",
        "tip: load on the end face; centre: on the mid-length section"),
    Key("load", "amplitude", positive("N"), "N", "> 0", None,
        "load amplitude F0 (give this or amplitude_fraction)"),
    Key("load", "amplitude_fraction", positive("", 1.0), "", "(0, 1)",
        DEFAULT_AMPLITUDE_FRACTION, "load amplitude as a fraction of the slip limit mu F_N"),
    Key("load.planar", "tip_amplitude", positive("N"), "N", "> 0", None,
        "amplitude of the tip model (with centre_amplitude, or give ratio)"),
    Key("load.planar", "centre_amplitude", positive("N"), "N", "> 0", None,
        "amplitude of the centre model"),
    Key("load.planar", "ratio", positive(), "", "> 0", None,
        "force ratio R = F_T(tip)/F_T(centre) on the paper's levels"),
    Key("load.planar", "phase_deg", interval(-360.0, 360.0, "degrees", closed=True), "degrees",
        "[-360, 360]", 0.0, "phase of the centre force ahead of the tip force"),
)

#: Dotted key -> ClampParams field, for the seven values that make a clamp.
CLAMP_KEYS = {
    "geometry.length": "length",
    "geometry.width": "width",
    "geometry.thickness": "thickness",
    "material.modulus": "modulus",
    "material.poisson_ratio": "poisson_ratio",
    "contact.friction": "friction",
    "clamping.normal_force": "normal_force",
}
