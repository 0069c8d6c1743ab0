"""Tip-loaded microslip model (paper, Section 2.1, Eqs 2-10)."""

from __future__ import annotations

from typing import Any, NamedTuple

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..options import ModelOptions

__all__ = ["TipState", "tip_initial", "tip_step"]


class TipState(NamedTuple):
    """State after increment i; every field broadcasts over a trailing batch shape."""

    force: NDArray[np.float64]  #: F_T(i), N
    displacement: NDArray[np.float64]  #: delta_x(i), mm
    slip_length: NDArray[np.float64]  #: u_i, mm
    width: NDArray[np.float64]  #: w_i, mm
    thickness: NDArray[np.float64]  #: t_i, mm


def tip_initial(p: Any) -> TipState:
    """The unloaded state: no force, no slip, the original cross-section."""
    w = np.asarray(p.width, dtype=float)
    t = np.asarray(p.thickness, dtype=float)
    z = np.zeros(np.broadcast(w, t).shape)
    return TipState(z, z, z, w + z, t + z)


def tip_step(force: ArrayLike, s: TipState, p: Any, opt: ModelOptions) -> TipState:
    """Advance the tip model by one force increment.

    Parameters
    ----------
    force : array_like
        The new total tip force F_T(i), N (>= 0, below mu F_N).
    s : TipState
        State of increment i - 1.
    p : ClampParams or any object with the same attributes as arrays
        ``length, width, thickness, modulus, poisson_ratio, friction, normal_force``.
    opt : ModelOptions

    Returns
    -------
    TipState
        The response at increment i, which is also the state for increment i + 1.

    Notes
    -----
    With q = mu F_N / L (Eq. 2) the slip zone grows from the loaded end:

    1. Length update (Eq. 4): L_i = L + delta_(i-1); the slip length is
       u_i = F_i L_i / (mu F_N).
    2. Poisson update (Eqs 6-7), with f = dF_i = F_i - F_(i-1) (``consistent``) or
       f = F_i (``paper-literal``)::

           w_i = w_(i-1) - nu w_(i-1) f / (E w_(i-1) t_(i-1))
           t_i = t_(i-1) - nu t_(i-1) f / (E w_(i-1) t_(i-1))

    3. Stiffness of the slipping part (Eq. 9): k_i = 2 E w_i t_i / u_i.
    4. Displacement (Eq. 10): delta_i = F_i / k_i = F_i u_i / (2 E w_i t_i).

    With both updates off, delta = F^2 / (2 E A q), the rigid-foundation solution of
    Goodman & Klumpp, whatever the increment size.
    """
    f = np.asarray(force, dtype=float)
    length = p.length + s.displacement if opt.length_update else p.length + 0.0 * f
    u = f * length / (p.friction * p.normal_force)
    if opt.poisson == "off":
        w, t = s.width, s.thickness
    else:
        fp = f - s.force if opt.poisson == "consistent" else f
        strain = p.poisson_ratio * fp / (p.modulus * s.width * s.thickness)
        w = s.width - s.width * strain
        t = s.thickness - s.thickness * strain
    delta = f * u / (2.0 * p.modulus * w * t)
    return TipState(f + 0.0 * delta, delta, u + 0.0 * delta, w + 0.0 * delta, t + 0.0 * delta)
