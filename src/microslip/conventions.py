"""Names, defaults and checks shared by the library, the case files and the command line.

One home for each: a name list, a default or a value check used in more than one place is
defined here once and imported everywhere else (the registries that give the names their
meaning import the names from here, so no copy can drift). This module stands on the bottom
floor beside :mod:`microslip.errors` and :mod:`microslip.params`: it imports only the
standard library and :mod:`microslip.errors`.

Units: N, mm, MPa, N/mm^3.

>>> check_choice("pairing", "spatial", PAIRINGS)
'spatial'
>>> check_whole("cycles", 0, 1, 1000)
Traceback (most recent call last):
...
microslip.errors.ParameterError: cycles must be a whole number in [1, 1000], got 0
"""

from __future__ import annotations

import math
import numbers
from collections.abc import Iterable
from typing import Any

from .errors import ParameterError

__all__ = [
    "BACKBONE_NAMES",
    "CCX_CONTACT_FORMULATIONS",
    "CLAMP_MODELS",
    "COUPLINGS",
    "DEFAULT_COUPLING",
    "DEFAULT_ELEMENTS",
    "DEFAULT_INTERFACE_MODES",
    "DEFAULT_MESH",
    "DEFAULT_NORMAL_CONTACT",
    "DEFAULT_NORMAL_SLOPE",
    "DEFAULT_ROM_MODES",
    "DEFAULT_STICK_SLOPE",
    "DENSITY_RANGE",
    "JOINT_MODELS",
    "MAX_MODE",
    "MAX_ROM_MODES",
    "PAIRINGS",
    "TRANSVERSE",
    "check_choice",
    "check_positive",
    "check_whole",
]

#: The clamp's two 1-D models and load cases, the paper's tip and centre models (Eqs 2-10,
#: Eqs 11-18): the keys of :data:`microslip.models.MODELS`, the force components of a planar
#: load path, the loads of an FE backbone, the clamp joints of a structure.
CLAMP_MODELS: tuple[str, ...] = ("tip", "centre")

#: Joint models of a structure (``--joint``, ``[[joint]] model``): one spring-slider,
#: Segalman's Iwan, or a clamp model behind a series spring.
JOINT_MODELS: tuple[str, ...] = ("jenkins", "iwan", *CLAMP_MODELS)

#: Couplings of a two-directional joint, the keys of
#: :data:`microslip.dynamics.operators2d.COUPLINGS`: one circular Coulomb limit, or the
#: paper's decoupled sum of two independent directions.
COUPLINGS: tuple[str, ...] = ("circular", "decoupled")

#: Coupling of a two-directional joint unless one is given.
DEFAULT_COUPLING = "circular"

#: How the elements along and across a two-directional clamp joint are matched, the keys of
#: :data:`microslip.dynamics.operators2d.PAIRINGS`: by slip order, or by position on the bar.
PAIRINGS: tuple[str, ...] = ("ordered", "spatial")

#: What a two-directional tip or centre joint may be across (its second direction), the keys
#: of :data:`microslip.meshdynamics.spec.TRANSVERSE`: the clamp's other 1-D model, or the built-in
#: FE's first loading of the centre force across the bar.
TRANSVERSE: tuple[str, ...] = (*CLAMP_MODELS, "fe")

#: Jenkins elements of an Iwan, tip or centre joint unless given (``--elements``).
DEFAULT_ELEMENTS = 200

#: Mesh of the finite-element models unless one is given (:mod:`microslip.meshlevels`).
DEFAULT_MESH = "coarse"

#: Stick slope lambda of the penalty friction law, N/mm^3 (the shear traction per unit of
#: elastic slip before gross slip). 1e4 is within about 0.1 % of the rigid-stick limit on the
#: Table 1 bar (docs/validation.md, stick-slope study; docs/solver.md).
DEFAULT_STICK_SLOPE = 1.0e4


#: Slope of the linear pressure-overclosure law, N/mm^3 (penetration F_N/(L w K) ~ 1e-6 mm):
#: ``penalty`` normal contact, both FE solvers.
DEFAULT_NORMAL_SLOPE = 1.0e5
#: Normal contact of a clamp on a mesh unless one is named: ``fixed``, the clamping step's
#: normal forces held (the paper's reading). CalculiX models ``penalty`` only and refuses it
#: (docs/interpretation.md, "The mesh structure's library home").
DEFAULT_NORMAL_CONTACT = "fixed"

#: CalculiX's contact formulations on a mesh of the user's own, the first the one that solves
#: the built-in solver's equations (validate --mesh's default); what each is:
#: :data:`microslip.fe.calculix.meshdeck.CONTACT_FORMULATIONS`.
CCX_CONTACT_FORMULATIONS = ("node-to-surface", "face-to-face")

# -- the structure on a mesh (modal --mesh, frf --mesh, reduce; microslip.meshdynamics)
#: Highest mode number a mesh study takes (the eigen-solve computes that many).
MAX_MODE = 50
#: Fixed-interface modes of the contact-node ROM unless the case says (the cantilever's stuck
#: frequencies then equal the full FE's to about 1e-6).
DEFAULT_ROM_MODES = 60
#: Most fixed-interface modes ``--rom-modes`` takes.
MAX_ROM_MODES = 2000
#: Characteristic constraint modes of the interface-reduced model unless the case says (the
#: studied mode's first-loading shapes come on top; docs/interpretation.md, "interface").
DEFAULT_INTERFACE_MODES = 10
#: The whole joint's backbones (the keys of
#: :data:`microslip.meshdynamics.jointbackbone.BACKBONES`; a test holds the two equal).
BACKBONE_NAMES = ("fe", "work", "tip", "centre")

def _u(unit: str) -> str:
    return f" ({unit})" if unit else ""


def check_choice(what: str, value: Any, names: Iterable[str]) -> str:
    """``value`` if it is one of ``names`` (a registry's keys), else an error listing them.

    >>> check_choice("strain-energy definition", "chord", ("secant", "branch"))
    Traceback (most recent call last):
    ...
    microslip.errors.ParameterError: unknown strain-energy definition 'chord'; choose one of \
secant, branch
    """
    valid = tuple(names)
    if not isinstance(value, str) or value not in valid:
        raise ParameterError(f"unknown {what} {value!r}; choose one of {', '.join(valid)}")
    return value


def check_positive(name: str, value: Any, unit: str = "", *, upper: float = math.inf,
                   inclusive_upper: bool = False) -> float:
    """Return ``value`` as a float if it is finite and in ``(0, upper)``, else raise.

    >>> check_positive("mu", 0.8)
    0.8
    >>> check_positive("mu", -0.2)
    Traceback (most recent call last):
    ...
    microslip.errors.ParameterError: mu must be > 0, got -0.2
    """
    try:
        x = float(value)
    except (TypeError, ValueError):
        raise ParameterError(f"{name} must be a number > 0{_u(unit)}, got {value!r}") from None
    if not math.isfinite(x):
        raise ParameterError(f"{name} must be finite and > 0{_u(unit)}, got {value!r}")
    if x <= 0.0:
        raise ParameterError(f"{name} must be > 0{_u(unit)}, got {value!r}")
    if x > upper or (x == upper and not inclusive_upper):
        rel = "<=" if inclusive_upper else "<"
        raise ParameterError(f"{name} must be {rel} {upper:g}{_u(unit)}, got {value!r}")
    return x


def check_whole(name: str, value: Any, low: int, high: float = math.inf) -> int:
    """Return ``value`` as an int if it is a whole number (not a bool, not a float) in
    ``[low, high]``, else raise; ``high = inf`` states the bound as ``>= low``.

    >>> check_whole("tip_symmetry", 2, 1)
    2
    >>> check_whole("tip_symmetry", 0, 1)
    Traceback (most recent call last):
    ...
    microslip.errors.ParameterError: tip_symmetry must be a whole number >= 1, got 0
    """
    if isinstance(value, bool) or not isinstance(value, numbers.Integral) \
            or not low <= int(value) <= high:
        rng = f">= {low}" if high == math.inf else f"in [{low}, {int(high)}]"
        raise ParameterError(f"{name} must be a whole number {rng}, got {value!r}")
    return int(value)

#: Densities (kg/m^3) a material of an engineering part can have: outside, a unit mistake
#: (t/mm^3 or g/cm^3 for kg/m^3).
DENSITY_RANGE = (100.0, 30000.0)
