"""The one option table: every option the command line and the case files share.

Each :class:`Option` states its name (argparse destination, ``--flag`` spelling), its type,
unit, range, meaning and the case-file key that gives it (``contact.stick_slope``) or the key
of a ``[[joint]]`` table (``stiffness``). The command line builds its arguments from it
(:func:`add_option`), the case schema its keys (:mod:`.schema`), and ``--case`` maps keys
onto options through it (:data:`CASE_DESTS`), so a flag and its key cannot drift apart.

The checks here (:func:`positive`, :func:`interval`, ...) validate a case file's values and
name the key, the unit and the allowed range; the command line checks its values where the
library takes them (``ClampParams``, the joints), with the same ranges.

Units: N, mm, MPa, N/mm, N/mm^3, degrees.
"""

from __future__ import annotations

import argparse
import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from ..conventions import (
    CLAMP_MODELS,
    COUPLINGS,
    DEFAULT_ELEMENTS,
    DEFAULT_MESH,
    DEFAULT_STICK_SLOPE,
    JOINT_MODELS,
    PAIRINGS,
    TRANSVERSE,
)
from ..errors import ParameterError
from ..meshlevels import FIXED_COUNTS, LEVELS, MESH_LEVELS, is_mesh_spec

__all__ = [
    "CASE_DESTS",
    "MESH_HELP",
    "OPTIONS",
    "PRESSURE_LAWS",
    "SOLVERS",
    "Check",
    "Option",
    "add_option",
    "add_solver",
    "choice",
    "exponent",
    "interval",
    "mesh_level",
    "mesh_text",
    "number",
    "positive",
    "pressure_text",
    "text",
    "whole",
]

#: Clamping pressure laws (as ``--pressure-law`` and ``clamping.pressure`` take them).
PRESSURE_LAWS = ("uniform", "parabolic", "power:N[:EDGE]", "table:FILE.csv")

Check = Callable[[str, Any], Any]


# --- argparse types ------------------------------------------------------------------------

def number(text: str) -> float:
    """argparse type: any float syntax (validation of the range happens in the model)."""
    try:
        return float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"not a number: {text!r}") from None


def mesh_level(text: str) -> str:
    """argparse type: a mesh level of :mod:`microslip.meshlevels` or ``NXxNYxNZ``."""
    if is_mesh_spec(text):
        return text
    raise argparse.ArgumentTypeError(
        f"unknown mesh {text!r}; choose one of {', '.join(LEVELS)} or NXxNYxNZ")


def mesh_or_file(text: str) -> str:
    """argparse type of ``fe --mesh``: a mesh level, ``NXxNYxNZ``, or a mesh file that exists
    (``.inp`` or a format meshio reads: :mod:`microslip.fe.meshfile`)."""
    if is_mesh_spec(text):
        return text
    if Path(text).is_file():
        return text
    raise argparse.ArgumentTypeError(
        f"unknown mesh {text!r}: neither a level ({', '.join(LEVELS)}), NXxNYxNZ, nor an "
        "existing mesh file (.inp, .msh, .vtu, ...)")


def mesh_file(text: str) -> str:
    """argparse type: a mesh file that exists (``modal --mesh``)."""
    if Path(text).is_file():
        return text
    raise argparse.ArgumentTypeError(f"no mesh file {text!r} (.inp, .msh, .vtu, ...)")


def set_name(text: str) -> str:
    """argparse type: a non-empty set name of a mesh file."""
    if not text.strip():
        raise argparse.ArgumentTypeError("a set name must not be empty")
    return text


def harmonics_count(text: str) -> str | int:
    """argparse type of ``--harmonics``: ``auto`` or a whole number (its range is checked
    where the balance is built)."""
    if text == "auto":
        return text
    try:
        return int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(
            f"not auto or a whole number: {text!r}") from None


# --- case-value checks ---------------------------------------------------------------------

def _u(unit: str) -> str:
    return f" ({unit})" if unit else ""


def _number(name: str, value: Any, unit: str) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise ParameterError(f"case key {name} must be a number{_u(unit)}, got {value!r}")
    x = float(value)
    if not math.isfinite(x):
        raise ParameterError(f"case key {name} must be finite{_u(unit)}, got {value!r}")
    return x


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
    """A check: a string."""
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
    """A check: a mesh level or ``NXxNYxNZ``, as ``--mesh`` takes it."""
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


# --- the table -----------------------------------------------------------------------------

@dataclass(frozen=True)
class Option:
    """One option of the command line and, where it has one, its case-file key.

    Attributes
    ----------
    name : str
        argparse destination; the flag is ``--`` plus the name with dashes.
    help : str
        What it is (the command-line help and the case file's comment).
    unit, range : str
        Unit ("" if none) and allowed range, as the help and the template print them.
    type : callable or None
        argparse type (None: a string; with ``choices``).
    metavar : str or None
        argparse metavar.
    choices : tuple of str or None
        Allowed values of a name option.
    key : str or None
        Dotted case-file key (``geometry.length``), None if the case file has none.
    joint_key : str or None
        Key of a ``[[joint]]`` table (``stiffness``), None if none.
    check : callable or None
        Check of a case value (``check(dotted_key, value) -> value``).
    scope : str
        Which commands read ``key``: ``all``, ``load`` (the uniaxial load case), ``planar``
        (the planar one) or ``mesh`` (a mesh of the user's own: ``fe``).
    case_default : object
        The default a case file documents for ``key`` (None: none).
    case_note : str
        What the case file adds to the meaning (how the key combines with others).
    """

    name: str
    help: str
    unit: str = ""
    range: str = ""
    type: Callable[[str], Any] | None = number
    metavar: str | None = None
    choices: tuple[str, ...] | None = None
    key: str | None = None
    joint_key: str | None = None
    check: Check | None = None
    scope: str = "all"
    case_default: Any = None
    case_note: str = ""

    @property
    def flag(self) -> str:
        return "--" + self.name.replace("_", "-")


_FROM_PRESET = "from preset"

#: --mesh help: the mesh levels of :mod:`microslip.meshlevels`.
MESH_HELP = (
    f"mesh level, the same elements for both solvers (builtin C3D8I, calculix C3D20R): "
    f"{', '.join(MESH_LEVELS)} are accuracy levels with counts from the geometry (on the "
    f"Table 1 bar 24x4x1, 48x4x1, 96x8x2; a squat body, L < 20 t, gets graded layers), "
    + ", ".join(f"{k} {'x'.join(map(str, v))}" for k, v in FIXED_COUNTS.items())
    + f", or NXxNYxNZ counts (default {DEFAULT_MESH}; docs/solver.md 8.4)")

_OPTIONS: tuple[Option, ...] = (
    # the clamp (ClampParams fields)
    Option("length", "clamped length L along the load", "mm", "> 0", metavar="MM",
           key="geometry.length", check=positive("mm"), case_default=_FROM_PRESET),
    Option("width", "depth w of the cross-section", "mm", "> 0", metavar="MM",
           key="geometry.width", check=positive("mm"), case_default=_FROM_PRESET),
    Option("thickness", "thickness t of the cross-section", "mm", "> 0", metavar="MM",
           key="geometry.thickness", check=positive("mm"), case_default=_FROM_PRESET),
    Option("modulus", "Young's modulus E", "MPa", "> 0", metavar="MPA",
           key="material.modulus", check=positive("MPa"), case_default=_FROM_PRESET),
    Option("poisson_ratio", "Poisson's ratio nu", "", "[0, 0.5)", metavar="X",
           key="material.poisson_ratio", check=interval(0.0, 0.5), case_default=_FROM_PRESET),
    Option("friction", "Coulomb friction coefficient mu", "", "> 0", metavar="X",
           key="contact.friction", check=positive(), case_default=_FROM_PRESET),
    Option("normal_force", "clamping (normal) force F_N", "N", "> 0", metavar="N",
           key="clamping.normal_force", check=positive("N"), case_default=_FROM_PRESET),
    # the contact
    Option("stick_slope", "tangential contact stiffness per area before slip (FE stick slope "
           "lambda; machined metal 1e3-1e5)", "N/mm^3", "> 0", metavar="N/MM3",
           key="contact.stick_slope", check=positive("N/mm^3"),
           case_default=DEFAULT_STICK_SLOPE,
           case_note="given, the 1-D models sit on this elastic layer, omitted they keep the "
           "paper's rigid foundation while fe uses the default"),
    Option("pressure_law", "clamping pressure law along the length (uniform is the paper's)",
           "", " | ".join(PRESSURE_LAWS), type=None, metavar="LAW", key="clamping.pressure",
           check=pressure_text, case_default="uniform"),
    # the uniaxial load case
    Option("model", "tip: load on the end face; centre: on the mid-length section", "",
           " | ".join(CLAMP_MODELS), type=None, choices=CLAMP_MODELS, key="load.model",
           check=choice(CLAMP_MODELS), scope="load", case_default="tip"),
    Option("amplitude", "load amplitude F0", "N", "> 0", metavar="N", key="load.amplitude",
           check=positive("N"), scope="load", case_note="give this or amplitude_fraction"),
    # the planar load case
    Option("tip_amplitude", "amplitude of the tip model (one symmetric half)", "N", "> 0",
           metavar="N", key="load.planar.tip_amplitude", check=positive("N"), scope="planar",
           case_note="with centre_amplitude, or give ratio"),
    Option("centre_amplitude", "amplitude of the centre model", "N", "> 0", metavar="N",
           key="load.planar.centre_amplitude", check=positive("N"), scope="planar"),
    Option("ratio", "force ratio R = F_T(tip)/F_T(centre) on the paper's levels", "", "> 0",
           metavar="R", key="load.planar.ratio", check=positive(), scope="planar"),
    Option("phase", "phase of the centre force ahead of the tip force", "degrees",
           "[-360, 360]", metavar="DEG", key="load.planar.phase_deg",
           check=interval(-360.0, 360.0, "degrees", closed=True), scope="planar",
           case_default=0.0),
    # the finite-element model
    Option("mesh", MESH_HELP, "", f"{' | '.join(LEVELS)} | NXxNYxNZ", type=mesh_level,
           metavar="LEVEL"),
    # the user's own mesh (fe --mesh FILE)
    Option("mesh_file", "a mesh of your own clamp: .inp, .msh, .vtu, ...; hexahedra with "
           "named sets", "", "path", type=None, metavar="FILE",
           key="mesh.file", check=text, scope="mesh", case_note="relative to the case file; "
           "its loads are [[load]] tables: set, direction = [DX, DY, DZ], amplitude (N), "
           "phase_deg"),
    Option("contact_set", "set of the mesh on the rigid base (node set or element-face "
           "surface)", "", "a set name of the mesh file", type=set_name, metavar="NAME",
           key="mesh.contact_set", check=text, scope="mesh"),
    Option("clamp_set", "set of the mesh that carries the clamping pressure F_N / area", "",
           "a set name of the mesh file", type=set_name, metavar="NAME", key="mesh.clamp_set",
           check=text, scope="mesh"),
    # the structure of the user's own mesh (modal --mesh FILE; the report's structure section)
    Option("density", "density of the body of the mesh (aluminium 2700, steel 7850)",
           "kg/m^3", "> 0", metavar="KG/M3", key="mesh.density", check=positive("kg/m^3"),
           scope="mesh", case_note="with it, report adds the damping of the structure's mode"),
    Option("mode", "the structure's mode whose damping is studied, 1 the lowest stuck mode",
           "", "[1, 50]", type=int, metavar="N", key="mesh.mode", check=whole(1, 50),
           scope="mesh", case_default=1),
    Option("response_set", "set of the mesh whose mean displacement along the mode is the "
           "amplitude", "", "a set name of the mesh file", type=set_name, metavar="NAME",
           key="mesh.response_set", check=text, scope="mesh"),
    # a structure and its joints
    Option("structure", "reduced model: FILE.npz (M, K, optional C, joints) or a Matrix "
           "Market directory, SI units", "", "path", type=None, metavar="FILE",
           key="structure.file", check=text, case_note="relative to the case file"),
    Option("joint", "jenkins: one spring-slider; iwan: Segalman's 4-parameter Iwan; tip, "
           "centre: the clamp's microslip model behind a series spring", "",
           " | ".join(JOINT_MODELS), type=None, choices=JOINT_MODELS, joint_key="model",
           check=choice(JOINT_MODELS)),
    Option("joint_stiffness", "jenkins: spring stiffness; iwan: initial stiffness K_T; tip, "
           "centre: the series spring", "N/mm", "> 0", metavar="N/MM", joint_key="stiffness",
           check=positive("N/mm"), case_note="or give contact.stick_slope for tip, centre"),
    Option("slip_force", "jenkins, iwan: macroslip force F_S", "N", "> 0", metavar="N",
           joint_key="slip_force", check=positive("N")),
    Option("chi", "iwan: density exponent", "", "(-1, 0]", metavar="X", joint_key="chi",
           check=exponent),
    Option("beta", "iwan: macroslip elements' share of the stiffness", "", "[0, inf)",
           metavar="X", joint_key="beta", check=interval(0.0, math.inf)),
    Option("elements", f"iwan, tip, centre: Jenkins elements (default {DEFAULT_ELEMENTS}, "
           "more for a smoother curve)",
           "", "[2, 100000]", type=int, metavar="N", joint_key="elements",
           check=whole(2, 100_000)),
    Option("coupling", "two-directional joints: one circular Coulomb limit or the paper's "
           "decoupled sum", "", " | ".join(COUPLINGS), type=None, choices=COUPLINGS,
           key="structure.coupling", joint_key="coupling", check=choice(COUPLINGS),
           case_note="circular if none is given; a [[joint]] table's own wins over "
           "[structure]'s"),
    Option("transverse", "a two-directional tip or centre joint: the joint across the bar "
           "(second direction): the clamp's tip or centre model (same clamp and series "
           "spring) or fe, the built-in FE's first loading of the centre force across the bar "
           "(needs the stick slope)", "", " | ".join(TRANSVERSE), type=None,
           choices=TRANSVERSE, joint_key="transverse", check=choice(TRANSVERSE),
           case_note="omitted, the joint's own model"),
    Option("pairing", "with transverse and circular coupling: how the elements along and "
           "across are matched: by position on the bar (spatial, the default) or by slip "
           "order (ordered)", "", " | ".join(PAIRINGS), type=None, choices=PAIRINGS,
           joint_key="pairing", check=choice(PAIRINGS)),
    # the harmonic balance (modal, frf: docs/dynamics.md, "Harmonics chosen by an error
    # estimate")
    Option("harmonics", "harmonics of the balance: auto raises them (and the AFT samples) "
           "until the damping ratio and frequency change by less than --harmonic-tolerance; "
           "a number fixes them, 1 = single-harmonic (describing-function) balance", "",
           "auto | [1, 256]", type=harmonics_count, metavar="auto|H", scope="all"),
    Option("harmonic_tolerance", "with --harmonics auto: largest relative change of the "
           "damping ratio and frequency between two levels of harmonics (1, 3, 7, 15, 31, "
           "63) that a point accepts", "", "(0, 0.5)", metavar="X", scope="all"),
    Option("fe_mesh", f"with transverse fe: the FE mesh, as --mesh ({', '.join(LEVELS)} or "
           f"NXxNYxNZ; default {DEFAULT_MESH})", "", f"{' | '.join(LEVELS)} | NXxNYxNZ",
           type=mesh_level, metavar="LEVEL", joint_key="fe_mesh", check=mesh_text,
           case_default=DEFAULT_MESH),
)

#: Option name -> :class:`Option`.
OPTIONS: dict[str, Option] = {o.name: o for o in _OPTIONS}

#: Case key -> (argparse destination, which load case reads it: "all", "load" or "planar").
#: ``load.amplitude_fraction`` also gives the amplitude (resolved after the parse).
CASE_DESTS: dict[str, tuple[str, str]] = {
    **{o.key: (o.name, o.scope) for o in _OPTIONS if o.key is not None},
    "load.amplitude_fraction": ("amplitude", "load"),
    "mesh.file": ("mesh", "mesh"),  # the mesh file is fe's --mesh FILE
}

#: What ``--solver`` means, per command: its choices and their meaning (the default first).
SOLVERS: dict[str, dict[str, str]] = {
    "fe": {"builtin": "the built-in finite-element solver (docs/solver.md)",
           "calculix": "CalculiX (ccx; docs/validation.md)"},
    "planar": {"analytical": "the paper's decoupled 1-D models, Table 2 zones",
               "fe": "the built-in frictional FE solver, one body with coupled 2-D friction, "
                     "against its two uni-axial runs"},
    "sweep": {"batch": "the 1-D models' compiled engine",
              "fe": "one finite-element run per amplitude of --amplitude-range, saved to --out "
                    "FILE.csv as it finishes, resumed by running the same command again"},
}


def _help(opt: Option, default: Any, note: str, help_text: str | None) -> str:
    body = opt.help if help_text is None else help_text
    unit = f", {opt.unit}" if opt.unit else ""
    rng = f", {opt.range}" if opt.range and opt.choices is None and opt.type is number else ""
    shown = "" if default is None or default is argparse.SUPPRESS else f" (default {default:g})" \
        if isinstance(default, float) else f" (default {default})"
    return f"{body}{unit}{rng}{shown}{'; ' + note if note else ''}"


def add_option(group: Any, name: str, *, default: Any = None, note: str = "",
               help: str | None = None, **extra: Any) -> argparse.Action:
    """Add the option ``name`` of :data:`OPTIONS` to a parser or argument group.

    ``default`` is the command's default (shown in the help), ``note`` a command-specific
    sentence after the shared help, ``help`` a replacement of the shared help text; ``extra``
    goes to ``add_argument`` (``action="append"``, ``required=True``, ...). ``--solver`` is
    not here: :func:`add_solver` documents what it means per command.
    """
    opt = OPTIONS[name]
    kwargs: dict[str, Any] = {"dest": opt.name, "default": default,
                              "help": _help(opt, default, note, help)}
    if opt.choices is not None:
        kwargs["choices"] = list(opt.choices)
    else:
        kwargs["metavar"] = opt.metavar
    if opt.type is not None:
        kwargs["type"] = opt.type
    kwargs.update(extra)
    return group.add_argument(opt.flag, **kwargs)


def add_solver(group: Any, command: str, choices: Sequence[str] | None = None) -> argparse.Action:
    """``--solver`` of ``command``, its choices and what each means (:data:`SOLVERS`)."""
    meaning = SOLVERS[command]
    names = list(meaning if choices is None else choices)
    return group.add_argument(
        "--solver", choices=names, default=names[0],
        help="; ".join(f"{k}: {meaning[k]}" for k in names) + f" (default {names[0]})")
