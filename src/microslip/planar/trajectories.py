"""Force ratio, eccentricity and the load levels of the paper's planar cases (Fig. 1, Table 2).

The paper loads the clamped zone in two orthogonal in-plane directions, along the bar
("tip", Section 2.1) and across it at mid-length ("centre", Section 2.2), and names each
case by the force ratio R = F_T(tip) / F_T(centre) (Eq. 1) and the eccentricity of the
load ellipse (Fig. 1). Units: force N, angles in degrees where named ``*_deg``.

How R relates to the forces of the two 1-D models
-------------------------------------------------
Fig. 1 plots *normalised* tip and centre forces. The tip model is one of two symmetric
halves of the clamp, each carrying half the tip force (Section 2, Table 2: tip t = 25 mm,
centre t = 50 mm), which is why the paper's tip amplitudes 2000, 4000, 6000, 8000 N are half
its centre amplitudes 4000, 8000, 12000, 16000 N ("since symmetry is being used"). So the
normalised forces are the amplitude *levels* 1..4 (tip force / 2000 N, centre force /
4000 N), and R = level_tip / level_centre = 2 F_tip / F_centre is also the ratio of the
total in-plane forces on the whole clamp (:data:`TIP_SYMMETRY` halves in parallel).

Which level pair the paper used for each R is not stated; two readings are offered
(:data:`LEVEL_SCHEMES`, decision in ``docs/planar.md``):

``base`` (default)
    The minor axis at level 1, the major axis at level max(R, 1/R): R >= 1 is tip level R with
    centre level 1, R <= 1 is tip level 1 with centre level 1/R. The four tip levels appear in
    Fig. 10 (R = 1..4) and the four centre levels in Fig. 11 (R = 1..1/4), one panel each,
    which is what the text says those figures show ("as F_T is increased for each of the
    models, the stiffness decreases"), and it explains the paper's reason for the largest eta
    at the extreme R ("the combination of the ellipticity and the increase in F_T"). It
    extends to any R > 0.
``top``
    The highest pair of whole levels with level_tip / level_centre = R
    (R = 1: 4/4, 2: 4/2, 3: 3/1, 4: 4/1, 1/2: 2/4, 1/3: 1/3, 1/4: 1/4).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from fractions import Fraction
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..conventions import check_whole
from ..errors import ParameterError
from ..named import result

__all__ = [
    "CENTRE_LEVEL_FORCE",
    "LEVEL_SCHEMES",
    "PAPER_LEVELS",
    "PAPER_RATIOS",
    "TIP_LEVEL_FORCE",
    "TIP_SYMMETRY",
    "Trajectory",
    "eccentricity",
    "force_ratio",
    "paper_level_pair",
    "paper_levels",
    "ratio_from_eccentricity",
    "ratio_label",
    "trajectory",
]

#: The paper's seven force ratios R (Fig. 1), in the order of Figs 10 and 11.
PAPER_RATIOS: tuple[float, ...] = (1.0, 2.0, 3.0, 4.0, 1.0 / 2.0, 1.0 / 3.0, 1.0 / 4.0)

#: Tip-model force of amplitude level 1, N (paper, Section 5: 2000, 4000, 6000, 8000 N).
TIP_LEVEL_FORCE = 2000.0
#: Centre-model force of amplitude level 1, N (paper, Section 5: 4000 ... 16000 N).
CENTRE_LEVEL_FORCE = 4000.0
#: The paper's amplitude levels 1..4.
PAPER_LEVELS: tuple[int, ...] = (1, 2, 3, 4)
#: Number of tip models acting in parallel in the whole clamp (two symmetric halves).
TIP_SYMMETRY = 2

#: Readings of which level pair the paper used for a ratio R (see the module docstring).
LEVEL_SCHEMES: dict[str, str] = {
    "base": "minor axis at level 1, major axis at level max(R, 1/R) (any R > 0)",
    "top": "highest pair of whole levels 1..4 with level_tip / level_centre = R",
}


def _positive_ratio(r: Any, name: str = "R") -> NDArray[np.float64]:
    try:
        a = np.asarray(r, dtype=float)
    except (TypeError, ValueError):
        raise ParameterError(f"{name} must be a number > 0, got {r!r}") from None
    if not np.all(np.isfinite(a)) or np.any(a <= 0.0):
        raise ParameterError(f"{name} must be finite and > 0, got {r!r}")
    return a


def eccentricity(ratio: ArrayLike) -> Any:
    """Eccentricity of the load ellipse with semi-axes in the ratio R (Fig. 1).

    epsilon = sqrt(1 - m^2) with m = min(R, 1/R) the ratio of minor to major semi-axis; a
    float for a scalar R, an array otherwise.

    Examples
    --------
    >>> [round(eccentricity(r), 2) for r in (1, 2, 3, 4)]
    [0.0, 0.87, 0.94, 0.97]
    >>> round(eccentricity(1 / 3), 6) == round(eccentricity(3), 6)
    True
    """
    a = _positive_ratio(ratio)
    m = np.minimum(a, 1.0 / a)
    e = np.sqrt(np.maximum(1.0 - m * m, 0.0))
    return float(e) if e.ndim == 0 else e


#: R from the minor/major axis ratio m = sqrt(1 - epsilon^2), by the major load component.
_MAJOR_AXIS: dict[str, Callable[[NDArray[np.float64]], NDArray[np.float64]]] = {
    "tip": lambda m: 1.0 / m,
    "centre": lambda m: m,
}


def ratio_from_eccentricity(ecc: ArrayLike, major: str = "tip") -> Any:
    """The force ratio R of an ellipse of eccentricity epsilon, the inverse of :func:`eccentricity`.

    Parameters
    ----------
    ecc : float or array_like
        Eccentricity in [0, 1).
    major : {"tip", "centre"}
        Which load component is the major axis: ``tip`` gives R >= 1, ``centre`` R <= 1.

    Examples
    --------
    >>> round(ratio_from_eccentricity(eccentricity(3.0)), 12)
    3.0
    >>> round(ratio_from_eccentricity(eccentricity(0.25), major="centre"), 12)
    0.25
    """
    try:
        e = np.asarray(ecc, dtype=float)
    except (TypeError, ValueError):
        raise ParameterError(f"eccentricity must be a number in [0, 1), got {ecc!r}") from None
    if not np.all(np.isfinite(e)) or np.any(e < 0.0) or np.any(e >= 1.0):
        raise ParameterError(f"eccentricity must be in [0, 1), got {ecc!r}")
    try:
        ratio_of_minor = _MAJOR_AXIS[major]
    except (KeyError, TypeError):
        raise ParameterError(
            f"major must be one of {', '.join(map(repr, _MAJOR_AXIS))}, got {major!r}"
        ) from None
    r = ratio_of_minor(np.sqrt(1.0 - e * e))
    return float(r) if r.ndim == 0 else r


def force_ratio(tip_amplitude: float, centre_amplitude: float,
                tip_symmetry: int = TIP_SYMMETRY) -> float:
    """R of a pair of model amplitudes: total tip force over centre force (Eq. 1).

    The whole clamp's tip force is ``tip_symmetry`` times the tip model's (the tip model is
    one of two symmetric halves), so R = tip_symmetry F_tip / F_centre, which equals the
    paper's ratio of normalised forces (levels) for the Table 2 amplitudes.

    >>> force_ratio(8000.0, 4000.0)
    4.0
    >>> force_ratio(2000.0, 16000.0)
    0.25
    """
    ft = float(_positive_ratio(tip_amplitude, "tip amplitude (N)"))
    fc = float(_positive_ratio(centre_amplitude, "centre amplitude (N)"))
    return _check_symmetry(tip_symmetry) * ft / fc


def _check_symmetry(tip_symmetry: Any) -> int:
    return check_whole("tip_symmetry", tip_symmetry, 1)


def paper_level_pair(ratio: float, scheme: str = "base") -> tuple[float, float]:
    """(tip level, centre level) of the paper's case with force ratio R.

    Parameters
    ----------
    ratio : float
        R = level_tip / level_centre, > 0.
    scheme : str
        One of :data:`LEVEL_SCHEMES`.

    Examples
    --------
    >>> [paper_level_pair(r) for r in (1, 2, 0.25)]
    [(1.0, 1.0), (2.0, 1.0), (1.0, 4.0)]
    >>> [paper_level_pair(r, "top") for r in (1, 2, 3, 0.5)]
    [(4.0, 4.0), (4.0, 2.0), (3.0, 1.0), (2.0, 4.0)]
    """
    r = float(_positive_ratio(ratio))
    if scheme == "base":
        return (r, 1.0) if r >= 1.0 else (1.0, 1.0 / r)
    if scheme == "top":
        nearest = Fraction(r).limit_denominator(12)
        frac = nearest if abs(float(nearest) - r) <= 1e-9 * r else None
        if frac is not None:
            for lc in sorted(PAPER_LEVELS, reverse=True):
                lt = frac * lc
                if lt.denominator == 1 and int(lt) in PAPER_LEVELS:
                    return float(lt), float(lc)
        raise ParameterError(
            f"R = {r:g} is not a ratio of two whole levels 1..4 (scheme 'top'); "
            f"use scheme 'base' or one of the paper's R values"
        )
    raise ParameterError(
        f"unknown level scheme {scheme!r}; choose one of {', '.join(LEVEL_SCHEMES)}"
    )


def paper_levels(ratio: float, scheme: str = "base") -> tuple[float, float]:
    """(tip amplitude, centre amplitude) in N of the paper's case with force ratio R.

    Level l means l x 2000 N on the tip model and l x 4000 N on the centre model (Table 2).

    Examples
    --------
    >>> [paper_levels(r) for r in (4, 1 / 3)]
    [(8000.0, 4000.0), (2000.0, 12000.0)]
    >>> paper_levels(1, scheme="top")
    (8000.0, 16000.0)
    """
    lt, lc = paper_level_pair(ratio, scheme)
    return TIP_LEVEL_FORCE * lt, CENTRE_LEVEL_FORCE * lc


def ratio_label(ratio: float) -> str:
    """R as the paper prints it: ``1``, ``2``, ``0.5``, ``0.33``, ``0.25``.

    >>> [ratio_label(r) for r in PAPER_RATIOS]
    ['1', '2', '3', '4', '0.5', '0.33', '0.25']
    """
    r = float(_positive_ratio(ratio))
    return f"{r:.2f}".rstrip("0").rstrip(".") if r < 1.0 else f"{r:g}"


@result
class Trajectory:
    """A sampled planar load path of one R (the paper's Fig. 1).

    Attributes
    ----------
    ratio : float
        R, the force ratio.
    eccentricity : float
        epsilon of R (:func:`eccentricity`): the eccentricity of the path itself when the
        phase is 90 degrees (semi-axes l_t and l_c); other phases tilt and flatten the ellipse,
        and phase 0 collapses it onto a line.
    phase_deg : float
        Phase of the centre force relative to the tip force, degrees.
    theta : ndarray, shape (k,)
        Angle over one cycle, radians.
    tip, centre : ndarray, shape (k,)
        Normalised tip and centre forces (levels: tip force / 2000 N, centre force /
        4000 N, so R = tip / centre amplitude), dimensionless.
    """

    ratio: float
    eccentricity: float
    phase_deg: float
    theta: NDArray[np.float64]
    tip: NDArray[np.float64]
    centre: NDArray[np.float64]


def trajectory(ratio: float, phase_deg: float = 90.0, samples: int = 361,
               scheme: str = "base") -> Trajectory:
    """The normalised load path of the case R: tip = l_t sin(theta), centre = l_c sin(theta + phi).

    ``phase_deg = 90`` draws the ellipse of the paper's Fig. 1; ``0`` is the straight line that
    the paper's zero-phase loading actually traces (Section 1: "zero phase shift").

    Examples
    --------
    >>> t = trajectory(2.0)
    >>> round(float(t.tip.max()), 9), round(float(t.centre.max()), 9), round(t.eccentricity, 3)
    (2.0, 1.0, 0.866)
    """
    if not (isinstance(samples, (int, np.integer)) and samples >= 3):
        raise ParameterError(f"samples must be a whole number >= 3, got {samples!r}")
    phi = float(phase_deg)
    if not math.isfinite(phi):
        raise ParameterError(f"phase must be a finite angle in degrees, got {phase_deg!r}")
    lt, lc = paper_level_pair(ratio, scheme)
    theta = np.linspace(0.0, 2.0 * np.pi, int(samples))
    return Trajectory(
        ratio=float(ratio),
        eccentricity=float(eccentricity(ratio)),
        phase_deg=phi,
        theta=theta,
        tip=lt * np.sin(theta),
        centre=lc * np.sin(theta + math.radians(phi)),
    )
