"""The registry of load cases: name -> where the force acts and how its slip is reported.

A load case is a uniform traction along the bar on one cross-section. Code that depends on
the load case asks its :class:`LoadCase` (the loaded section, the slip-length domains)
instead of comparing names, so a new case is one entry of :data:`LOAD_CASES`.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from types import MappingProxyType
from typing import Any

from .. import closedform as cf
from ..errors import ParameterError

__all__ = ["LOAD_CASES", "LoadCase", "load_case"]


@dataclass(frozen=True)
class LoadCase:
    """One load case of the clamped bar.

    Attributes
    ----------
    name : str
    section : float
        Position of the loaded cross-section as a fraction of the length L (1: end face).
    description : str
        Where the force acts, in words.
    domains : tuple of (str, float, float)
        Slip-length domains ``(name, x_min / L, x_max / L)`` (paper, Fig. 8): the slipping
        length is reported per domain; the first domain is the headline slip length.
    halves : int
        Tip-loaded bars the case is made of: the section load F splits into ``halves`` bars of
        length L / halves each loaded by F / halves at the section (tip 1, centre 2).
    displacement, dissipated_energy : callable
        The rigid-foundation closed forms (:mod:`microslip.closedform`) ``f(F, EA, q)``: peak
        displacement of the loaded section (mm) and W_d (N·mm).
    """

    name: str
    section: float
    description: str
    domains: tuple[tuple[str, float, float], ...]
    halves: int
    displacement: Callable[[Any, float, float], Any]
    dissipated_energy: Callable[[float, float, float], float]

    def virgin_constant(self, ea: float, q: float) -> float:
        """c of the virgin curve d = F^2 / c, N/mm: 2 EA q for one tip-loaded bar; halves^2
        times that when the section load F splits into ``halves`` bars loaded by F / halves."""
        return 2.0 * ea * q * self.halves ** 2

    def slip_length(self, force: float, q: float) -> float:
        """Closed-form slip length of each domain at section load ``force`` (N), mm."""
        return force / (self.halves * q)


#: The load cases of the paper's FE model (Section 4) and 1-D models: name -> LoadCase.
LOAD_CASES: Mapping[str, LoadCase] = MappingProxyType({
    "tip": LoadCase("tip", 1.0, "along the bar on the end face x = L",
                    (("tip", -math.inf, math.inf),), 1, cf.tip_displacement,
                    cf.tip_dissipated_energy),
    "centre": LoadCase("centre", 0.5, "on the mid-length section x = L/2 (along the bar "
                       "unless centre_direction says)",
                       (("tension", 0.5, math.inf), ("compression", -math.inf, 0.5)), 2,
                       cf.centre_displacement, cf.centre_dissipated_energy),
})


def load_case(name: object) -> LoadCase:
    """The :class:`LoadCase` called ``name``; one line naming the choices if there is none.

    >>> load_case("centre").section
    0.5
    """
    case = LOAD_CASES.get(name) if isinstance(name, str) else None
    if case is None:
        raise ParameterError(f"unknown load case {name!r}; choose one of {', '.join(LOAD_CASES)}")
    return case
