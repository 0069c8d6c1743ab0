"""Parameters of a clamped zone, validated once at the boundary.

Units throughout microslip: force N, length mm, modulus MPa (N/mm^2), energy N·mm.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass
from typing import Any

from .conventions import check_positive
from .errors import ParameterError

__all__ = ["PRESETS", "ClampParams", "check_amplitude", "check_positive", "preset"]


def check_amplitude(value: Any) -> float:
    """Validate a load amplitude in N (finite, > 0)."""
    return check_positive("amplitude", value, "N")


@dataclass(frozen=True)
class ClampParams:
    """Geometry, material and clamping of one clamped zone (paper, Tables 1 and 2).

    Parameters
    ----------
    length : float
        Length L of the clamped zone along the load, mm (paper's Fig. 3).
    width : float
        Depth w of the cross-section, mm.
    thickness : float
        Thickness t of the cross-section, mm.
    modulus : float
        Young's modulus E, MPa.
    poisson_ratio : float
        Poisson's ratio nu, in (0, 0.5).
    friction : float
        Coulomb friction coefficient mu, > 0.
    normal_force : float
        Clamping (normal) force F_N, N, uniformly distributed over the interface.

    Examples
    --------
    >>> p = preset("table1")
    >>> round(p.macroslip_force, 1)
    356.0
    >>> dataclasses.replace(p, friction=-0.2)
    Traceback (most recent call last):
    ...
    microslip.errors.ParameterError: friction must be > 0, got -0.2
    """

    length: float
    width: float
    thickness: float
    modulus: float
    poisson_ratio: float
    friction: float
    normal_force: float

    def __post_init__(self) -> None:
        checked = {
            "length": check_positive("length", self.length, "mm"),
            "width": check_positive("width", self.width, "mm"),
            "thickness": check_positive("thickness", self.thickness, "mm"),
            "modulus": check_positive("modulus", self.modulus, "MPa"),
            "friction": check_positive("friction", self.friction),
            "normal_force": check_positive("normal_force", self.normal_force, "N"),
        }
        nu = self.poisson_ratio
        try:
            nu_f = float(nu)
        except (TypeError, ValueError):
            raise ParameterError(f"poisson_ratio must be a number, got {nu!r}") from None
        if not (math.isfinite(nu_f) and 0.0 <= nu_f < 0.5):
            raise ParameterError(f"poisson_ratio must be in [0, 0.5), got {nu!r}")
        checked["poisson_ratio"] = nu_f
        for k, v in checked.items():
            object.__setattr__(self, k, v)

    @property
    def area(self) -> float:
        """Cross-section A = w t, mm^2."""
        return self.width * self.thickness

    @property
    def axial_stiffness(self) -> float:
        """E A, N."""
        return self.modulus * self.area

    @property
    def friction_per_length(self) -> float:
        """Limiting friction force per unit length q = mu F_N / L (Eq. 2), N/mm."""
        return self.friction * self.normal_force / self.length

    @property
    def macroslip_force(self) -> float:
        """mu F_N, N: the total friction force the interface can carry (Eq. 5)."""
        return self.friction * self.normal_force

    def replace(self, **changes: float) -> ClampParams:
        """A copy with some values changed (validated again)."""
        return dataclasses.replace(self, **changes)

    def as_dict(self) -> dict[str, float]:
        return dataclasses.asdict(self)


#: Parameter sets of the paper, with the load amplitude the paper applies (N) where it gives one.
#: Table 2's zones are held in the reading of docs/interpretation.md §6: the paper's t (25 and
#: 50 mm) is the contact width w, its w (10 mm) the depth t normal to the contact; the paper's
#: models depend on w t only, so its numbers are the same either way.
PRESETS: dict[str, tuple[ClampParams, float | None]] = {
    "table1": (ClampParams(254.0, 25.4, 3.18, 68947.0, 0.3, 0.8, 445.0), 267.0),
    "table2-tip": (ClampParams(50.0, 25.0, 10.0, 10000.0, 0.3, 0.8, 20000.0), 8000.0),
    "table2-centre": (ClampParams(50.0, 50.0, 10.0, 10000.0, 0.3, 0.8, 20000.0), 16000.0),
}


def preset(name: str) -> ClampParams:
    """The clamped-zone parameters of a named preset (see :data:`PRESETS`)."""
    try:
        return PRESETS[name][0]
    except KeyError:
        raise ParameterError(
            f"unknown preset {name!r}; choose one of {', '.join(sorted(PRESETS))}"
        ) from None
