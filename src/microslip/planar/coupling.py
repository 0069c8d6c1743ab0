"""The paper's model coupling (Section 3, Eqs 19-23): one resultant loop from two 1-D loops.

The paper applies both components "at the same frequency with a zero phase shift"
(Section 1), so both 1-D loops are traversed at the same load fraction s in [-1, 1]:
F_tip = A_t s, F_centre = A_c s. Point by point (Eqs 19-20)::

    delta_r = sqrt(delta_t^2 + delta_c^2) sign(delta_t)
    F_r     = sqrt(F_t^2 + F_c^2)         sign(F_t)

and the loss factor of the resultant loop follows from Eqs 21-23. The resultant loop is a
bookkeeping device, not the work done by the load; see :mod:`microslip.planar.loadpath` for
the work-based alternative and ``docs/planar.md`` for the comparison.

Units: force N, displacement mm, energy N·mm.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from ..conventions import check_choice
from ..energy import DEFAULT_STRAIN_ENERGY, STRAIN_ENERGY, damping_from_loop, strain_energy
from ..errors import ParameterError
from ..hysteresis import masing_loop
from ..results import Backbone, DampingResult, HysteresisLoop

__all__ = [
    "paper_coupling",
    "paper_loss_factors",
    "resultant",
    "resultant_backbone",
    "resultant_loop",
]

#: Largest difference of the load fractions F/A of the two loops accepted as "the same".
_FRACTION_TOL = 1e-9


def resultant(tip: NDArray[np.float64], centre: NDArray[np.float64]) -> NDArray[np.float64]:
    """sqrt(x_t^2 + x_c^2) sign(x_t) (Eqs 19-20), with sign(x_c) where x_t is exactly 0.

    The paper's factor x_t / |x_t| is undefined at x_t = 0; taking the sign of the centre
    component there keeps the magnitude (the two components of a zero-phase loop change sign
    together unless the loop shapes differ).

    >>> resultant(np.array([3.0, -3.0, 0.0]), np.array([4.0, -4.0, -2.0])).tolist()
    [5.0, -5.0, -2.0]
    """
    t = np.asarray(tip, dtype=float)
    c = np.asarray(centre, dtype=float)
    sign = np.where(t != 0.0, np.sign(t), np.sign(c))
    return np.asarray(np.hypot(t, c) * sign, dtype=float)


def _check_same_fractions(tip_force: NDArray[np.float64], centre_force: NDArray[np.float64],
                          what: str) -> None:
    if tip_force.shape != centre_force.shape:
        raise ParameterError(
            f"the tip and centre {what} must have the same number of points (run both models "
            f"with the same increments), got {tip_force.size} and {centre_force.size}"
        )
    at = float(np.max(np.abs(tip_force)))
    ac = float(np.max(np.abs(centre_force)))
    if not (at > 0.0 and ac > 0.0):
        raise ParameterError(f"the tip and centre {what} need a force amplitude > 0 N")
    err = float(np.max(np.abs(tip_force / at - centre_force / ac)))
    if err > _FRACTION_TOL:
        raise ParameterError(
            f"the tip and centre {what} must be sampled at the same load fractions F/F0 "
            f"(zero phase, same increments); they differ by up to {err:.3g}"
        )


def resultant_loop(tip_loop: HysteresisLoop, centre_loop: HysteresisLoop) -> HysteresisLoop:
    """The paper's resultant hysteresis loop (Eqs 19-20) of two loops at equal load fractions.

    Parameters
    ----------
    tip_loop, centre_loop : HysteresisLoop
        Loops of the same number of points, point k of each at the same load fraction
        F/F0 (e.g. :func:`~microslip.masing_loop` of backbones with equal increments).

    Returns
    -------
    HysteresisLoop
        ``source="paper-coupling"``, same number of points, starting at the resultant peak.

    Examples
    --------
    >>> from microslip.results import HysteresisLoop
    >>> t = HysteresisLoop(np.array([3.0, -3.0, 3.0]), np.array([1.0, -1.0, 1.0]))
    >>> c = HysteresisLoop(np.array([4.0, -4.0, 4.0]), np.array([2.0, -2.0, 2.0]))
    >>> resultant_loop(t, c).force.tolist()
    [5.0, -5.0, 5.0]
    """
    ft = np.asarray(tip_loop.force, dtype=float)
    fc = np.asarray(centre_loop.force, dtype=float)
    _check_same_fractions(ft, fc, "loops")
    return HysteresisLoop(
        force=resultant(ft, fc),
        displacement=resultant(np.asarray(tip_loop.displacement, dtype=float),
                               np.asarray(centre_loop.displacement, dtype=float)),
        source="paper-coupling",
        meta={"equations": "Eqs 19-20", "tip": dict(tip_loop.meta),
              "centre": dict(centre_loop.meta)},
    )


def resultant_backbone(tip: Backbone, centre: Backbone) -> Backbone:
    """The resultant first-loading curve (Eqs 19-20 applied to the two backbones).

    Needed by the strain-energy definitions that read the virgin curve (``backbone``) or the
    stored energy (``stored``: the sum of the energies held in the two bars). Slip lengths and
    cross-sections of both models are kept side by side, domains ``tip`` then the centre ones;
    ``params`` and ``options`` stay None (each model's are on its own backbone).
    """
    _check_same_fractions(np.asarray(tip.force, dtype=float),
                          np.asarray(centre.force, dtype=float), "backbones")
    return Backbone(
        model="resultant",
        force=resultant(tip.force, centre.force),
        displacement=resultant(tip.displacement, centre.displacement),
        domains=tuple(tip.domains) + tuple(centre.domains),
        slip_length=np.hstack([tip.slip_length, centre.slip_length]),
        width=np.hstack([tip.width, centre.width]),
        thickness=np.hstack([tip.thickness, centre.thickness]),
        stored_energy=np.asarray(tip.stored_energy) + np.asarray(centre.stored_energy),
    )


def paper_coupling(tip: Backbone, centre: Backbone,
                   strain_energy_kind: str = DEFAULT_STRAIN_ENERGY) -> DampingResult:
    """W_d, U and eta of the paper's resultant loop (Eqs 19-23) from the two backbones.

    Parameters
    ----------
    tip, centre : Backbone
        First loadings of the tip and centre models with the same number of increments.
    strain_energy_kind : str
        Definition of U (:data:`microslip.STRAIN_ENERGY`). The paper's figures are read with
        ``branch`` (Eq. 22: integral along the loading branch from F = 0 to the peak).

    Returns
    -------
    DampingResult
        Of the resultant loop; its ``backbone`` is :func:`resultant_backbone`.

    Examples
    --------
    With both corrections off both backbones are quadratic, the resultant loop is a scaled
    copy of each loop, and eta is the quadratic-curve value at any amplitudes:

    >>> import math
    >>> from microslip import ModelOptions, first_loading, preset
    >>> opt = ModelOptions.uncorrected()
    >>> t = first_loading("tip", preset("table2-tip"), 6000.0, 200, opt)
    >>> c = first_loading("centre", preset("table2-centre"), 4000.0, 200, opt)
    >>> r = paper_coupling(t, c, "branch")
    >>> round(r.loss_factor * 5 * math.pi / 4, 4)  # 4/(5 pi), to the discretisation error
    1.0
    >>> from microslip import damping_from_loop, masing_loop
    >>> round(r.loss_factor / damping_from_loop(masing_loop(t), t, "branch").loss_factor, 12)
    1.0
    """
    check_choice("strain-energy definition", strain_energy_kind, STRAIN_ENERGY)
    loop = resultant_loop(masing_loop(tip), masing_loop(centre))
    return damping_from_loop(loop, resultant_backbone(tip, centre), strain_energy_kind)


def paper_loss_factors(result: DampingResult) -> dict[str, float]:
    """eta of a resultant loop under every strain-energy definition (same W_d), dimensionless."""
    w = result.dissipated_energy
    out = {}
    for kind in STRAIN_ENERGY:
        u = strain_energy(result.loop, result.backbone, kind)
        out[kind] = w / (2.0 * np.pi * u)
    return out
