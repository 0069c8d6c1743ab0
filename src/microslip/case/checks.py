"""The types and checks of the option table (:mod:`.table`) and its :class:`Option`.

The argparse types (:func:`number`, :func:`mesh_level`, ...) turn a command-line string into a
value or one usage line; the checks (:func:`positive`, :func:`interval`, ...) validate a case
file's values and name the key, the unit and the allowed range.
"""

from __future__ import annotations

import argparse
import math
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from ..errors import ParameterError
from ..meshlevels import LEVELS, is_mesh_spec

__all__ = ["Check", "Option", "choice", "exponent", "interval", "mesh_file", "mesh_level",
           "mesh_or_file", "mesh_text", "number", "positive", "pressure_text", "set_name",
           "text", "whole"]

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


def harmonics_count(text: str) -> str | int:
    """argparse type of ``--harmonics``: ``auto`` or a whole number (its range is checked
    where the balance is built)."""
    if text == "auto":
        return text
    try:
        return int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"not auto or a whole number: {text!r}") from None


def set_name(text: str) -> str:
    """argparse type: a non-empty set name of a mesh file."""
    if not text.strip():
        raise argparse.ArgumentTypeError("a set name must not be empty")
    return text


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
    action, nargs : optional
        argparse ``action`` (``store_true``, ``append``, ...) and ``nargs``.
    spelling : str or None
        The flag when it is not ``--`` plus the name (``overwrite`` is ``--force``).
    default : object
        The option's default on every command that does not give its own (None: nothing;
        an on/off option is off).
    """

    name: str
    help: str
    unit: str = ""
    range: str = ""
    type: Callable[[str], Any] | None = number
    metavar: str | tuple[str, ...] | None = None
    choices: tuple[str, ...] | None = None
    key: str | None = None
    joint_key: str | None = None
    check: Check | None = None
    scope: str = "all"
    case_default: Any = None
    case_note: str = ""
    action: Any = None
    nargs: int | str | None = None
    spelling: str | None = None
    default: Any = None

    @property
    def flag(self) -> str:
        """The command-line spelling: ``spelling``, else ``--`` plus the name with dashes."""
        return self.spelling or "--" + self.name.replace("_", "-")


