"""Nodal Coulomb friction on a rigid base: circular limit, penalty stick, radial return.

The law itself is :data:`microslip.contactlaw.CONTACT_LAWS` (``coulomb``), written once for
this solver and the harmonic-balance elements; here it is applied to every contact node at
once and its results named.

Each contact node i carries a tangential spring of stiffness ``k_i = lambda A_i`` (the stick
slope lambda in N/mm^3, as CalculiX's ``*FRICTION`` second value, times the node's tributary
area A_i in mm^2) in series with a Coulomb slider whose limit is the *circle*
``|tau_i| <= mu N_i`` (N_i the node's normal force, N). With the tangential displacement
g_i = (u_x, u_y) of the node and its accumulated slip s_i (mm), the friction force the node
exerts on the base is ``tau_i = k_i (g_i - s_i)``; the base pushes the body with ``-tau_i``.

The return mapping is backward Euler, i.e. the closest-point projection onto the circle
(radial return), and its linearisation is the consistent tangent (Simo & Hughes 1998,
Ch. 2; Wriggers 2006, Ch. 5)::

    tau_trial = k (g - s_n)
    stick  (|tau_trial| <= mu N):  tau = tau_trial,                 d tau / d g = k I
    slip   (|tau_trial| >  mu N):  tau = mu N n, n = tau_trial / |tau_trial|,
                                   s_(n+1) = g - tau / k,
                                   d tau / d g = k (mu N / |tau_trial|) (I - n n^T)

The slip tangent is symmetric and positive semi-definite; its null direction is n (no
resistance along the slip). Everything is vectorised over the contact nodes.
Units: force N, displacement mm, stiffness N/mm.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from ...contactlaw import get_contact_law

__all__ = ["FrictionResponse", "friction_dissipation", "return_map"]

FloatArray = NDArray[np.float64]
BoolArray = NDArray[np.bool_]

#: The nodes' contact law.
LAW = get_contact_law("coulomb")


@dataclass(frozen=True, eq=False)
class FrictionResponse:
    """Response of all contact nodes to one trial of tangential displacements.

    Attributes
    ----------
    force : ndarray, shape (n, 2)
        tau_i, the friction force of each node on the base, N (the body feels -tau_i).
    tangent : ndarray, shape (n, 3)
        The consistent tangent d tau / d g as its entries (D_xx, D_xy, D_yy), N/mm.
    slipping : ndarray of bool, shape (n,)
        True where the node slides (trial force outside the circle).
    slip : ndarray, shape (n, 2)
        Updated accumulated slip s_(n+1), mm.
    """

    force: FloatArray
    tangent: FloatArray
    slipping: BoolArray
    slip: FloatArray


def return_map(g: FloatArray, slip: FloatArray, stiffness: FloatArray, limit: FloatArray
               ) -> FrictionResponse:
    """Radial return of the circular Coulomb law at every contact node (vectorised).

    Parameters
    ----------
    g : ndarray, shape (n, 2)
        Tangential displacements of the contact nodes, mm.
    slip : ndarray, shape (n, 2)
        Slip s_n at the end of the previous increment, mm.
    stiffness : ndarray, shape (n,)
        Stick stiffness k_i = lambda A_i, N/mm.
    limit : ndarray, shape (n,)
        Friction limit mu N_i, N.

    Returns
    -------
    FrictionResponse

    Examples
    --------
    >>> import numpy as np
    >>> r = return_map(np.array([[0.5, 0.0], [3.0, 4.0]]), np.zeros((2, 2)),
    ...                np.array([1.0, 1.0]), np.array([1.0, 1.0]))
    >>> r.slipping.tolist(), r.force.round(3).tolist(), r.slip.round(3).tolist()
    ([False, True], [[0.5, 0.0], [0.6, 0.8]], [[0.0, 0.0], [2.4, 3.2]])
    """
    fx, fy, sx, sy, txx, txy, tyy, _, _, sl = LAW.return_map(
        g[:, 0], g[:, 1], slip[:, 0], slip[:, 1], stiffness, limit)
    force = np.column_stack([fx, fy])
    tangent = np.column_stack([txx, txy, tyy])
    slipping = sl > 0.0
    new_slip = np.column_stack([sx, sy])
    return FrictionResponse(force, tangent, slipping, new_slip)


def friction_dissipation(force: FloatArray, slip_old: FloatArray, slip_new: FloatArray
                         ) -> float:
    """Energy dissipated by friction in one increment, sum_i tau_i . (s_(n+1) - s_n), N·mm.

    Exact for the backward-Euler return map: the converged force is at the limit and parallel
    to the slip increment, so each term is mu N_i |Delta s_i| >= 0.
    """
    return float(np.sum(force * (slip_new - slip_old)))
