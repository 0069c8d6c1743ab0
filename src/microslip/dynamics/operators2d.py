"""The two-directional joint: 2-D Jenkins elements with one circular Coulomb limit each.

A joint that moves in two in-plane directions (two modes with close frequencies) slips
when the resultant of its tangential force reaches the friction limit, in whatever
direction: :class:`CircularIwan` is the 1-D operator's set of Jenkins elements (same
stiffnesses and slip displacements, so the same backbone along any line) with circular slip
limits and radial return. The paper's decoupled sum, two independent 1-D operators, is
:data:`COUPLINGS` ``["decoupled"]``.

Units: displacement mm, force N, stiffness N/mm.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
from numpy.typing import NDArray

from ..errors import ParameterError
from ..named import readonly, result
from .kernels2d import circular_periodic_kernel
from .operators import IwanOperator

__all__ = ["COUPLINGS", "CircularIwan", "circular"]

Array = NDArray[np.float64]


@result
class CircularIwan:
    """A parallel set of 2-D Jenkins elements with circular slip limits.

    Parameters
    ----------
    name : str
        Label.
    stiffness, slip : ndarray, shape (n,)
        Isotropic spring stiffness k_i (N/mm) and slip displacement phi_i (mm) of each
        element (slip force k_i phi_i in any direction), as :class:`IwanOperator`.

    Notes
    -----
    Radial return (:mod:`.kernels2d`). Along one axis every step is the 1-D return mapping,
    so the operator is the 1-D :class:`IwanOperator` of the same elements (tested to
    1e-12). On a circular orbit of radius A > phi_i an element dissipates
    ``W_d = 2 pi k_i phi_i sqrt(A^2 - phi_i^2)`` per cycle (REFERENCES.md, 2-D Jenkins);
    two decoupled 1-D elements give ``8 k_i phi_i (A - phi_i)``.
    """

    name: str
    stiffness: np.ndarray
    slip: np.ndarray

    def __post_init__(self) -> None:
        axial = IwanOperator(self.name, self.stiffness, self.slip)  # the same checks
        object.__setattr__(self, "stiffness", readonly(np.array(axial.stiffness)))
        object.__setattr__(self, "slip", readonly(np.array(axial.slip)))

    #: Relative displacement components the operator takes.
    directions = 2

    @property
    def axial(self) -> IwanOperator:
        """The 1-D operator of the same elements: the joint along any fixed line."""
        return IwanOperator(self.name, self.stiffness, self.slip)

    @property
    def initial_stiffness(self) -> float:
        """sum_i k_i, N/mm, in every direction."""
        return float(self.stiffness.sum())

    @property
    def slip_force(self) -> float:
        """Macroslip force sum_i k_i phi_i, N (resultant)."""
        return float(self.stiffness @ self.slip)

    def periodic_force_projected(self, u: Array, basis: Array) -> tuple[Array, Array]:
        """Closed periodic force (N, shape (N, 2)) at the displacement samples ``u`` (mm,
        (N, 2)) and ``jb[t, a, b, c] = d f_t,a / d C_b,c`` (N/mm, (N, 2, 2, m)) for
        ``u[:, b] = basis @ C_b`` (``basis`` (N, m))."""
        u = np.ascontiguousarray(u, dtype=np.float64)
        basis = np.ascontiguousarray(basis, dtype=np.float64)
        if u.ndim != 2 or u.shape[1] != 2 or u.shape[0] == 0 or not np.all(np.isfinite(u)):
            raise ParameterError(f"2-D displacement samples must be finite of shape (N, 2), "
                                 f"got {u.shape}")
        if basis.ndim != 2 or basis.shape[0] != u.shape[0]:
            raise ParameterError(f"basis must have shape ({u.shape[0]}, m), got {basis.shape}")
        f = np.zeros(u.shape)
        jb = np.zeros((u.shape[0], 2, 2, basis.shape[1]))
        start = int(np.argmax(np.hypot(u[:, 0], u[:, 1])))
        failed = circular_periodic_kernel(u, self.stiffness, self.slip, start, basis, f, jb)
        if failed:
            raise ParameterError(f"the periodic state of {failed} circular Jenkins "
                                 "element(s) did not converge")
        return f, jb

    def periodic_force(self, u: Array) -> Array:
        """Closed periodic force (N, (N, 2)) at the displacement samples ``u`` (mm, (N, 2))."""
        return self.periodic_force_projected(u, np.zeros((np.shape(u)[0], 1)))[0]


def circular(joint: IwanOperator) -> CircularIwan:
    """The 2-D joint with circular slip limits built from a 1-D joint's elements (its
    backbone along any line)."""
    return CircularIwan(joint.name, joint.stiffness, joint.slip)


def _decoupled(joint: IwanOperator) -> tuple[IwanOperator, IwanOperator]:
    return joint, joint


def _circular(joint: IwanOperator) -> tuple[CircularIwan]:
    return (circular(joint),)


#: Coupling name -> the operators of a two-directional joint built from a 1-D joint:
#: ``circular`` one :class:`CircularIwan` on both directions, ``decoupled`` one
#: :class:`IwanOperator` per direction (the paper's sum).
COUPLINGS: dict[str, Callable[[IwanOperator], tuple[IwanOperator | CircularIwan, ...]]] = {
    "circular": _circular, "decoupled": _decoupled}
