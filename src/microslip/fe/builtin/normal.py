"""Normal contact of the bottom face with the rigid base: held fixed, or a unilateral penalty.

``fixed`` (the paper's reading, the default): u_z = 0 at every bottom node; the normal forces
N_i are the z-reactions of the clamping step and stay fixed during the tangential loading.

``penalty``: u_z of the bottom nodes is free; node i presses on the base with

    N_i = k_n A_i max(0, -u_z,i)        (k_n the normal slope, N/mm^3; A_i its area, mm^2)

(CalculiX's linear pressure-overclosure law, lumped at the nodes). A node with u_z > 0 has
lifted off (N_i = 0). The friction limit mu N_i follows N_i, so the tangential load's moment
moves the pressure towards the loaded edge. The contribution of node i to the tangent is
k_n A_i on its u_z diagonal while closed (u_z <= 0) and 0 when open: a semi-smooth Newton
step with an active set. The limits mu N_i are lagged within an increment: after the
residual converges with the current limits, they are reset to mu N_i(u) and the iteration
continues until both the residual and the change of the limits are below the tolerance, so
the converged increment satisfies the fully coupled equations. Units: N, mm.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from ...errors import ParameterError

__all__ = ["NORMAL_CONTACTS", "PenaltyNormal", "check_normal_contact"]

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.int64]


@dataclass(frozen=True, eq=False)
class PenaltyNormal:
    """Unilateral penalty springs of the contact nodes.

    Attributes
    ----------
    stiffness : ndarray, shape (n_c,)
        k_n A_i, N/mm.
    dofs : ndarray of int, shape (n_c,)
        Free-dof positions of the nodes' u_z.
    slope : float
        k_n, N/mm^3.
    gap : ndarray, shape (n_c,), or None
        Initial gaps g_0 to the base, mm (a curved contact face); None: 0.
    """

    stiffness: FloatArray
    dofs: IntArray
    slope: float
    gap: FloatArray | None = None

    def penetration(self, u: FloatArray) -> FloatArray:
        """-(u_z + g_0), mm: how far each node is pressed into the base (g_0 its initial gap,
        0 on a flat face)."""
        un = u[self.dofs]
        return np.asarray(-un if self.gap is None else -(un + self.gap), dtype=float)

    def forces(self, u: FloatArray) -> FloatArray:
        """N_i >= 0, N: the base's push on the body along +z."""
        return np.asarray(self.stiffness * np.maximum(self.penetration(u), 0.0), dtype=float)

    def closed(self, u: FloatArray) -> NDArray[np.bool_]:
        """True where the node touches the base (u_z + g_0 <= 0)."""
        return np.asarray(self.penetration(u) >= 0.0)

    def tangent(self, u: FloatArray) -> FloatArray:
        """d N_i / d(-u_z,i): k_n A_i closed, 0 open, N/mm."""
        return np.where(self.closed(u), self.stiffness, 0.0)


#: Normal-contact readings of the built-in solver: name -> description.
NORMAL_CONTACTS: dict[str, str] = {
    "fixed": "u_z = 0 at the interface; normal forces from the clamping step, then fixed "
             "(the paper's reading)",
    "penalty": "unilateral penalty k_n A_i max(0, -u_z): the pressure follows the load, "
               "lift-off allowed",
}


def check_normal_contact(name: str) -> str:
    """``name`` if it is in :data:`NORMAL_CONTACTS`; one clear error otherwise."""
    if name not in NORMAL_CONTACTS:
        raise ParameterError(f"unknown normal contact {name!r}; choose one of "
                             f"{', '.join(NORMAL_CONTACTS)}")
    return name

