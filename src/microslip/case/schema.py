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

from ..conventions import (
    CLAMP_MODELS,
    COUPLINGS,
    DEFAULT_MESH,
    DEFAULT_STICK_SLOPE,
    JOINT_MODELS,
    PAIRINGS,
    TRANSVERSE,
)
from ..errors import ParameterError
from ..meshlevels import LEVELS, is_mesh_spec
from ..params import PRESETS

__all__ = [
    "ACROSS_KEYS",
    "CLAMP_KEYS",
    "COUPLINGS",
    "DEFAULT_AMPLITUDE_FRACTION",
    "DEFAULT_FE_MESH",
    "FUTURE_PRESSURE_LAWS",
    "JOINT_CLAMP_SECTIONS",
    "JOINT_KEYS",
    "JOINT_MODELS",
    "JOINT_USES",
    "KEYS",
    "PAIRINGS",
    "PRESSURE_LAWS",
    "SECTIONS",
    "TRANSVERSE",
    "Key",
]

#: Default load amplitude of a case, as a fraction of the slip limit mu F_N of its clamp.
DEFAULT_AMPLITUDE_FRACTION = 0.5

#: Clamping pressure laws accepted now, and those planned (issue 11) but not yet available.
PRESSURE_LAWS = ("uniform", "parabolic", "power:N[:EDGE]", "table:FILE.csv")
FUTURE_PRESSURE_LAWS: tuple[str, ...] = ()

#: Uniaxial load cases of a case file: the clamp's two models.
LOAD_MODELS = CLAMP_MODELS

#: Mesh of the FE's first loading across the bar (``transverse = "fe"``) unless given.
DEFAULT_FE_MESH = DEFAULT_MESH

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


def mesh_text(name: str, value: Any) -> str:
    """A check: a mesh level or ``NXxNYxNZ``, as ``microslip fe --mesh`` takes it."""
    s = text(name, value)
    if is_mesh_spec(s):
        return s
    raise ParameterError(f"case key {name} must be one of {', '.join(LEVELS)} or NXxNYxNZ, "
                         f"got {s!r}")


def whole(low: int, high: int) -> Check:
    """A check: a whole number in [low, high]."""
    def check(name: str, value: Any) -> int:
        if isinstance(value, bool) or not isinstance(value, int) or not low <= value <= high:
            raise ParameterError(f"case key {name} must be a whole number in [{low}, {high}], "
                                 f"got {value!r}")
        return int(value)
    return check


def exponent(name: str, value: Any) -> float:
    """A check: Segalman's chi, in (-1, 0]."""
    x = _number(name, value, "")
    if not -1.0 < x <= 0.0:
        raise ParameterError(f"case key {name} must be in (-1, 0], got {value!r}")
    return x


def _dof(name: str, value: Any, low: int) -> int:
    if isinstance(value, bool) or not isinstance(value, int) or value < low:
        raise ParameterError(f"case key {name} must hold whole DOF numbers >= {low} (0-based, "
                             f"-1 for the ground as J), got {value!r}")
    return int(value)


def joint_dofs(name: str, value: Any) -> tuple[tuple[int, int], ...]:
    """A check: where a joint sits, as ``[i, j]`` per direction (j = -1: the ground).

    ``[I]`` or ``[I, J]``: one direction, between DOF I and the ground or DOF J (as
    ``--joint-dof``); ``[[I, J], [K, L]]`` (or ``[[I], [K]]``): two directions, one pair per
    direction (as the (n, 2, 2) ``joints`` array of a structure file).
    """
    shape = ("must be [I], [I, J] (one direction) or [[I, J], [K, L]] (two directions), "
             "0-based")
    if not isinstance(value, list) or not value:
        raise ParameterError(f"case key {name} {shape}, got {value!r}")
    rows = value if all(isinstance(v, list) for v in value) else [value]
    if len(rows) > 2 or any(not 1 <= len(r) <= 2 for r in rows):
        raise ParameterError(f"case key {name} {shape}, got {value!r}")
    out = tuple((_dof(name, r[0], 0), _dof(name, r[1], -1) if len(r) == 2 else -1)
                for r in rows)
    if any(i == j for i, j in out):
        raise ParameterError(f"case key {name}: a joint connects two different DOFs, got "
                             f"{value!r}")
    return out


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
    "structure": "a structure from a file with its joints (read by modal and frf)",
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
    Key("structure", "file", text, "", "path", None,
        "reduced model: FILE.npz (M, K, optional C, joints) or a Matrix Market directory, "
        "SI units; relative to the case file (as --structure)"),
    Key("structure", "coupling", choice(COUPLINGS), "", " | ".join(COUPLINGS), None,
        "two-directional joints: one circular Coulomb limit or the paper's decoupled sum "
        "(as --coupling; circular if neither is given)"),
)


#: Number of Jenkins elements of an iwan, tip or centre joint when ``elements`` is not given
#: (as ``--elements``; :data:`microslip.dynamics.distributions.DEFAULT_ELEMENTS`).
_ELEMENTS_NOTE = "default 200, as --elements"

#: The keys of one ``[[joint]]`` table (section ``joint``); a tip or centre joint also takes
#: ``preset`` and the clamp sections of :data:`JOINT_CLAMP_SECTIONS`.
JOINT_KEYS: tuple[Key, ...] = (
    Key("joint", "dofs", joint_dofs, "", "[I], [I, J] or [[I, J], [K, L]]", None,
        "where the joint sits: DOF I (0-based) to the ground, I to J, or one pair per "
        "direction for a two-directional joint (J = -1: the ground)"),
    Key("joint", "model", choice(JOINT_MODELS), "", " | ".join(JOINT_MODELS), None,
        "jenkins: one spring-slider; iwan: Segalman's 4-parameter Iwan; tip, centre: the "
        "clamp's microslip model behind a series spring"),
    Key("joint", "stiffness", positive("N/mm"), "N/mm", "> 0", None,
        "jenkins: spring stiffness; iwan: initial stiffness K_T; tip, centre: the series "
        "spring (or give contact.stick_slope) (as --joint-stiffness)"),
    Key("joint", "slip_force", positive("N"), "N", "> 0", None,
        "jenkins, iwan: macroslip force F_S (as --slip-force)"),
    Key("joint", "chi", exponent, "", "(-1, 0]", None, "iwan: density exponent (as --chi)"),
    Key("joint", "beta", interval(0.0, math.inf), "", "[0, inf)", None,
        "iwan: macroslip elements' share of the stiffness (as --beta)"),
    Key("joint", "elements", whole(2, 100_000), "", "[2, 100000]", None,
        f"iwan, tip, centre: Jenkins elements ({_ELEMENTS_NOTE})"),
    Key("joint", "coupling", choice(COUPLINGS), "", " | ".join(COUPLINGS), None,
        "a two-directional joint's coupling (default: [structure] coupling, --coupling, "
        "else circular)"),
    Key("joint", "transverse", choice(TRANSVERSE), "", " | ".join(TRANSVERSE), None,
        "two-directional tip, centre: the joint across the bar (second direction): the clamp's "
        "tip or centre model (same clamp and series spring) or fe, the built-in FE's first "
        "loading of the centre force across the bar (needs contact.stick_slope); omitted, "
        "the joint's own model (as --transverse)"),
    Key("joint", "pairing", choice(PAIRINGS), "", " | ".join(PAIRINGS), None,
        "with transverse, circular coupling: how the elements along and across are matched; "
        "spatial (default): by position on the bar, ordered: by slip order (as --pairing)"),
    Key("joint", "fe_mesh", mesh_text, "", f"{' | '.join(LEVELS)} | NXxNYxNZ",
        DEFAULT_FE_MESH, "with transverse = fe: the FE mesh, as microslip fe --mesh (as "
        "--fe-mesh)"),
)

#: Joint model -> the keys of :data:`JOINT_KEYS` it uses besides dofs, model, coupling and
#: the keys across (:data:`ACROSS_KEYS`, checked on their own).
JOINT_USES: dict[str, frozenset[str]] = {
    "jenkins": frozenset({"stiffness", "slip_force"}),
    "iwan": frozenset({"stiffness", "slip_force", "chi", "beta", "elements"}),
    "tip": frozenset({"stiffness", "elements"}),
    "centre": frozenset({"stiffness", "elements"}),
}

#: The keys of a joint across (:data:`JOINT_KEYS`): transverse and what only it uses.
ACROSS_KEYS = ("transverse", "pairing", "fe_mesh")

#: Clamp sections a tip or centre joint may hold, overriding the case's own clamp.
JOINT_CLAMP_SECTIONS = ("geometry", "material", "contact", "clamping")

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
