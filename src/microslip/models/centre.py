"""Centre-loaded microslip model (paper, Section 2.2, Eqs 11-18)."""

from __future__ import annotations

from typing import Any, NamedTuple

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..options import ModelOptions

__all__ = ["CentreState", "centre_initial", "centre_step"]

#: Sign of the elongation of each domain under a positive load: tension, compression.
_SIGN = np.array([1.0, -1.0])


class CentreState(NamedTuple):
    """State after increment i. Domain arrays have a leading axis of 2: (tension, compression),
    then the batch shape."""

    force: NDArray[np.float64]  #: F_T(i), N
    displacement: NDArray[np.float64]  #: delta_x(i) of the loaded section (Eq. 18), mm
    domain_displacement: NDArray[np.float64]  #: delta_x(it), delta_x(ic) (Eq. 17), mm, >= 0
    slip_length: NDArray[np.float64]  #: u_it, u_ic, mm
    width: NDArray[np.float64]  #: w_it, w_ic, mm
    thickness: NDArray[np.float64]  #: t_it, t_ic, mm


def centre_initial(p: Any) -> CentreState:
    """The unloaded state."""
    w = np.asarray(p.width, dtype=float)
    t = np.asarray(p.thickness, dtype=float)
    z = np.zeros(np.broadcast(w, t).shape)
    z2 = np.zeros((2, *z.shape))
    return CentreState(z, z, z2, z2, w + z2, t + z2)


def _sign(ndim: int) -> NDArray[np.float64]:
    return _SIGN.reshape((2,) + (1,) * ndim)


def centre_step(force: ArrayLike, s: CentreState, p: Any, opt: ModelOptions) -> CentreState:
    """Advance the centre model by one force increment.

    Parameters
    ----------
    force : array_like
        The new total centre force F_T(i), N.
    s : CentreState
        State of increment i - 1.
    p : ClampParams or any object with the same attributes as arrays
    opt : ModelOptions

    Returns
    -------
    CentreState
        The response at increment i, also the state for increment i + 1.

    Notes
    -----
    The bar is split at mid-length into a tension and a compression domain that act in
    parallel (Section 2.2). Per domain d (sign s_d = +1 tension, -1 compression):

    1. Domain force and slip length (Eqs 11, 17), ``physical`` reading: F_d = F/2 and
       u_d = F_d / q_d with q_d = (mu F_N / 2) / l_d on the half length
       l_d = L/2 + s_d delta_d(i-1) (length update) or L/2, i.e. u_d = F l_d / (mu F_N).
       ``paper`` reading: F_d = F and Eq. 11 as printed,
       u_d = F (L + delta_d(i-1)) / (4 mu F_N).
    2. Poisson update (Eqs 12-15) from the previous mean strain e_d = delta_d(i-1) / u_d(i-1)::

           w_d = w (1 - s_d nu e_d),  t_d = t (1 - s_d nu e_d)    (consistent)

       ``paper-literal`` keeps the printed ``+`` of Eq. 15 for t of the tension domain.
    3. Stiffness (Eq. 16) k_d = 2 E w_d t_d / u_d and displacement (Eq. 17)
       delta_d = F_d / k_d.
    4. Loaded section (Eq. 18): delta = (k_t delta_t + k_c delta_c) / (k_t + k_c)
       = (F_t + F_c) / (k_t + k_c), the two domains as parallel springs.

    With both updates off, both readings give delta = F^2 / (8 E A q), the exact result
    for a centre-loaded bar on a rigid Coulomb foundation.
    """
    f = np.asarray(force, dtype=float)
    sign = _sign(np.ndim(s.displacement))
    fn = p.friction * p.normal_force
    prev = s.domain_displacement
    if opt.centre == "physical":
        f_d = 0.5 * f
        half = 0.5 * p.length + (sign * prev if opt.length_update else 0.0 * prev)
        u = f * half / fn
    else:
        f_d = f + 0.0 * f
        full = p.length + (prev if opt.length_update else 0.0 * prev)
        u = f * full / (4.0 * fn)
    if opt.poisson == "off":
        w, t = s.width, s.thickness
    else:
        with np.errstate(divide="ignore", invalid="ignore"):
            e = np.where(s.slip_length > 0.0, prev / s.slip_length, 0.0)
        grow = 1.0 - sign * p.poisson_ratio * e
        w = p.width * grow
        if opt.poisson == "paper-literal":
            # Eq. 15 as printed: t_it = t + delta t nu / u, the tension domain thickens.
            t = p.thickness * (1.0 + p.poisson_ratio * e)
        else:
            t = p.thickness * grow
    area = w * t
    delta_d = f_d * u / (2.0 * p.modulus * area)
    # Eq. 18 with k_d delta_d = F_d: delta = 2 F_d / (k_t + k_c), k_d = 2 E A_d / u_d.
    with np.errstate(divide="ignore", invalid="ignore"):
        compliance = np.where(
            u[0] * u[1] > 0.0,
            u[0] * u[1] / (2.0 * p.modulus * (area[0] * u[1] + area[1] * u[0])),
            0.0,
        )
    delta = 2.0 * f_d * compliance
    return CentreState(f + 0.0 * delta, delta, delta_d, u, w + 0.0 * u, t + 0.0 * u)
