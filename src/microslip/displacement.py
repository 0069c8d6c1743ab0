"""Displacement-controlled amplitudes: the force amplitude whose virgin curve reaches a
displacement.

A vibrating structure imposes a displacement on its joint, not a force. The models are
driven by force, so a displacement amplitude d0 is turned into the force amplitude F0 whose
first loading (the backbone, recorded in the model's own force increments F0/n) ends at d0:
the root of ``d(F0) - d0`` by Brent's method (:func:`scipy.optimize.brentq`) to the last bits of
F0. Running the model at that F0 gives exactly the loop of the displacement amplitude; the
reached displacement equals d0 to a few units in the last place.

The backbone is continuous and increasing in F0 and bounded by its value just below the
macroslip force (the whole interface slips there), so the admissible displacements are
``0 < d0 < d(F_macroslip)`` (:func:`displacement_range`); beyond, the joint slips as a whole
and no force amplitude of microslip reaches d0.

:func:`invert_monotone` is the generic root-find, also used for the finite-element solvers
(one solver run per evaluation, a looser tolerance: :data:`FE_RTOL`).
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np
from scipy.optimize import brentq

from .errors import MacroslipError, ParameterError
from .models import Contact, first_loading, macroslip_force
from .options import ModelOptions
from .params import ClampParams

__all__ = [
    "FE_RTOL",
    "check_displacement",
    "displacement_range",
    "force_for_displacement",
    "force_for_fe_displacement",
    "invert_monotone",
]

#: Relative tolerance on the force of a finite-element inversion (each evaluation is a run).
FE_RTOL = 1e-9
#: Relative tolerance on the force of a 1-D model inversion: the last bits of F0.
MODEL_RTOL = 4 * np.finfo(float).eps


def check_displacement(value: float, limit: float, what: str) -> float:
    """A displacement amplitude in mm, finite and inside (0, limit); else one line naming it."""
    d = float(value)
    if not (math.isfinite(d) and 0 < d < limit):
        raise MacroslipError(
            f"displacement amplitude {value!r} mm is outside the range of {what}: "
            f"0 < displacement < {limit:.6g} mm (beyond, the joint slips as a whole)")
    return d


def invert_monotone(displacement: Callable[[float], float], target: float, upper: float,
                    rtol: float) -> float:
    """The force F in (0, upper) with ``displacement(F) == target``, by Brent's method.

    ``displacement`` must be increasing with displacement(0) = 0 and
    ``displacement(upper) > target``; ``rtol`` is the relative tolerance on F.
    """
    def residual(force: float) -> float:
        return -target if force == 0.0 else displacement(force) - target

    return float(brentq(residual, 0.0, upper, xtol=rtol * upper, rtol=rtol, maxiter=200))


def _highest_force(model: str, params: ClampParams, options: ModelOptions) -> float:
    """The largest float below the macroslip force of ``model``, N."""
    return float(np.nextafter(macroslip_force(model, params, options), 0.0))


def _final_displacement(model: str, params: ClampParams, increments: int,
                        options: ModelOptions, contact: Contact | None = None
                        ) -> Callable[[float], float]:
    def d(force: float) -> float:
        return first_loading(model, params, force, increments, options,
                             contact).peak_displacement

    return d


def displacement_range(model: str, params: ClampParams, increments: int = 1000,
                       options: ModelOptions | None = None,
                       contact: Contact | None = None) -> float:
    """The displacement (mm) the virgin curve of ``model`` (on ``contact``) reaches just below
    macroslip: displacement amplitudes must lie in (0, this)."""
    opt = options if options is not None else ModelOptions()
    return _final_displacement(model, params, increments, opt, contact)(
        _highest_force(model, params, opt))


def force_for_displacement(model: str, params: ClampParams, displacement: float,
                           increments: int = 1000, options: ModelOptions | None = None,
                           contact: Contact | None = None) -> float:
    """The force amplitude F0 (N) whose first loading of ``model`` ends at ``displacement`` mm.

    Parameters
    ----------
    model : {"tip", "centre"}
    params : ClampParams
    displacement : float
        Displacement amplitude d0, mm, in (0, :func:`displacement_range`).
    increments : int
        Force increments of the first loading (the same n as the run that follows: the
        backbone depends on it).
    options : ModelOptions, optional
    contact : Contact, optional
        The interface under the bar (:class:`microslip.models.Contact`); default rigid.

    Returns
    -------
    float
        F0 in N, below the macroslip force.

    Raises
    ------
    MacroslipError
        ``displacement`` outside the admissible range (the message gives it).

    Notes
    -----
    Solves d_n(F0) = d0 for the backbone of Eqs 2-10 (tip) or Eqs 11-18 (centre) as
    computed (force increments F0/n), so that the loop at F0 is the loop of d0.
    """
    opt = options if options is not None else ModelOptions()
    if not isinstance(displacement, (int, float)) or isinstance(displacement, bool):
        raise ParameterError(f"displacement amplitude must be a number in mm, got "
                             f"{displacement!r}")
    upper = _highest_force(model, params, opt)
    d = _final_displacement(model, params, increments, opt, contact)
    target = check_displacement(displacement, d(upper), f"the {model} model")
    return invert_monotone(d, target, upper, MODEL_RTOL)


def force_for_fe_displacement(displacement: Callable[[float], float], target: float,
                              guess: float, upper: float, rtol: float = FE_RTOL) -> float:
    """The force (N) at which a finite-element run reaches ``target`` mm, by Brent's method.

    ``displacement(F)`` runs the solver at amplitude F and returns its peak displacement;
    ``guess`` (e.g. the 1-D model's inversion) starts the bracket, which widens by 25 % a step,
    and ``upper`` (just below macroslip) bounds it. A target beyond ``displacement(upper)`` is
    refused with the admissible range.
    """
    memo: dict[float, float] = {}

    def d(force: float) -> float:
        if force not in memo:
            memo[force] = displacement(force)
        return memo[force]

    lo = hi = min(guess, upper)
    if d(hi) < target:
        while d(hi) < target:
            if hi >= upper:
                check_displacement(target, d(upper), "the finite-element model")
            lo, hi = hi, min(1.25 * hi, upper)
    else:
        while d(lo) >= target:
            hi, lo = lo, 0.8 * lo
    return float(brentq(lambda f: d(f) - target, lo, hi, xtol=rtol * lo, rtol=rtol,
                        maxiter=100))
