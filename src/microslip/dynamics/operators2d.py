"""The two-directional joint: 2-D Jenkins elements with one circular Coulomb limit each.

A joint that moves in two in-plane directions (two modes with close frequencies) slips
when the resultant of its tangential force reaches the friction limit, in whatever
direction: :class:`CircularIwan` is a set of Jenkins elements with circular slip limits on
the force and springs that may be stiffer along one axis than along the other (a bar's
joint along and across it). :func:`circular` gives it the 1-D operator's elements in both
directions (the same backbone along any line, radial return); :func:`anisotropic` pairs
the elements of two 1-D joints, one per direction (:data:`PAIRINGS`). The paper's
decoupled sum, two independent 1-D operators, is :data:`COUPLINGS` ``["decoupled"]``.

Units: displacement mm, force N, stiffness N/mm.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
from numpy.typing import NDArray

from ..conventions import COUPLINGS as COUPLING_NAMES
from ..conventions import PAIRINGS as PAIRING_NAMES
from ..errors import ParameterError
from ..named import readonly, result
from .kernels2d import circular_periodic_kernel
from .operators import IwanOperator

__all__ = ["COUPLINGS", "DEFAULT_PAIRING", "PAIRINGS", "CircularIwan", "anisotropic", "circular"]

Array = NDArray[np.float64]


@result
class CircularIwan:
    """A parallel set of 2-D Jenkins elements with circular slip limits on the force.

    Parameters
    ----------
    name : str
        Label.
    stiffness, slip : ndarray, shape (n,)
        Spring stiffness k_i along x (N/mm) and slip displacement phi_i along x (mm) of
        each element, as :class:`IwanOperator`; its slip force s_i = k_i phi_i (N) is the
        same in every direction.
    stiffness_y : ndarray, shape (n,), optional
        Spring stiffness along y, N/mm, > 0 where k_i > 0 and 0 where k_i = 0 (the slip
        displacement along y is s_i / k_y,i); None: isotropic, ``stiffness``. Stored
        resolved.

    Notes
    -----
    Element i: force ``f = diag(k_i, k_y,i) (u - z)``, ``|f| <= s_i``, the slider slipping
    along the force (the return map of :mod:`.kernels2d`; radial return if isotropic).
    Along x or y every step is the 1-D return mapping, so the operator is
    :meth:`along` that axis (tested to 1e-12). Isotropic, on a circular orbit of radius
    A > phi_i an element dissipates ``W_d = 2 pi k_i phi_i sqrt(A^2 - phi_i^2)`` per cycle
    (REFERENCES.md, 2-D Jenkins); two decoupled 1-D elements give
    ``8 k_i phi_i (A - phi_i)``.
    """

    name: str
    stiffness: np.ndarray
    slip: np.ndarray
    stiffness_y: np.ndarray | None = None

    def __post_init__(self) -> None:
        axial = IwanOperator(self.name, self.stiffness, self.slip)  # the same checks
        k = np.array(axial.stiffness)
        ky = k.copy() if self.stiffness_y is None else np.array(self.stiffness_y,
                                                                 dtype=np.float64)
        if ky.shape != k.shape or not np.all(np.isfinite(ky)):
            raise ParameterError(f"stiffness_y must be finite of shape {k.shape}, got "
                                 f"{ky.shape}")
        if not (np.all(ky[k > 0.0] > 0.0) and np.all(ky[k == 0.0] == 0.0)):
            raise ParameterError("stiffness_y must be > 0 N/mm where the stiffness along x "
                                 "is > 0 and 0 where it is 0")
        object.__setattr__(self, "stiffness", readonly(k))
        object.__setattr__(self, "slip", readonly(np.array(axial.slip)))
        object.__setattr__(self, "stiffness_y", readonly(ky))

    #: Relative displacement components the operator takes.
    directions = 2

    @property
    def _ky(self) -> np.ndarray:
        return self.stiffness if self.stiffness_y is None else self.stiffness_y

    @property
    def isotropic(self) -> bool:
        """Whether every element is as stiff along y as along x."""
        return bool(np.array_equal(self._ky, self.stiffness))

    def along(self, axis: int) -> IwanOperator:
        """The 1-D operator of the joint moving along x (``axis`` 0: elements (k_i, phi_i))
        or y (1: (k_y,i, s_i / k_y,i)); either axis of an isotropic joint, and every line
        through the origin, is the same operator."""
        if axis == 0:
            return IwanOperator(self.name, self.stiffness, self.slip)
        if axis == 1:
            ky = self._ky
            ratio = np.divide(self.stiffness, ky, out=np.ones_like(ky), where=ky > 0.0)
            return IwanOperator(self.name, ky, self.slip * ratio)
        raise ParameterError(f"axis must be 0 (x) or 1 (y), got {axis!r}")

    @property
    def axial(self) -> IwanOperator:
        """The 1-D operator along x, :meth:`along` (0)."""
        return self.along(0)

    @property
    def stuck_stiffness(self) -> np.ndarray:
        """diag(sum_i k_i, sum_i k_y,i), N/mm: the slope from the virgin state."""
        return np.diag([float(self.stiffness.sum()), float(self._ky.sum())])

    @property
    def initial_stiffness(self) -> float:
        """sum_i k_i, N/mm, in every direction (isotropic joints only: otherwise
        :attr:`stuck_stiffness`)."""
        if not self.isotropic:
            raise ParameterError(f"the anisotropic joint {self.name!r} has no single initial "
                                 "stiffness: use its stuck_stiffness (2x2)")
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
        failed = circular_periodic_kernel(u, self.stiffness, self._ky, self.slip, start,
                                          basis, f, jb)
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


#: Relative difference at most of the two 1-D joints' total slip forces :func:`anisotropic`
#: pairs.
SAME_SLIP_FORCE = 1e-9

#: A pairing: ``(x_edges, y_edges)`` (cumulative slip force tau of each 1-D joint's
#: elements sorted by slip displacement, N, both from 0 to F) -> the cuts of [0, F] along
#: x (sorted, with the x edges among them) and the map tau_x -> tau_y (measure-preserving).
Pairing = Callable[[Array, Array], tuple[Array, Callable[[Array], Array]]]


def _ordered(x_edges: Array, y_edges: Array) -> tuple[Array, Callable[[Array], Array]]:
    return np.union1d(x_edges, y_edges), lambda tau: tau


def _spatial(x_edges: Array, y_edges: Array) -> tuple[Array, Callable[[Array], Array]]:
    f = x_edges[-1]
    cuts = np.union1d(x_edges, np.concatenate([(f - y_edges) / 2.0, (f + y_edges) / 2.0]))
    return np.clip(cuts, 0.0, f), lambda tau: np.abs(2.0 * tau - f)


#: Pairing name (:data:`microslip.conventions.PAIRINGS`) -> how the elements of the 1-D
#: joints along x and y are matched:
#: ``ordered`` the same order of slipping (tau_y = tau_x); ``spatial`` the bar's tip
#: loading along x against its centre loading across it, slip spreading from the loaded end
#: along x and from mid-length across (tau_y = |2 tau_x - F|).
PAIRINGS: dict[str, Pairing] = dict(zip(PAIRING_NAMES, (_ordered, _spatial), strict=True))

#: Pairing of :func:`anisotropic` (and of a coupling given two 1-D joints) unless named.
DEFAULT_PAIRING = "spatial"


def _edges(joint: IwanOperator) -> tuple[Array, Array]:
    """Cumulative slip force (N, from 0) of the elements of ``joint`` sorted by slip
    displacement, and their slip displacements (mm); elements of zero stiffness left out."""
    keep = joint.stiffness > 0.0
    order = np.argsort(joint.slip[keep], kind="stable")
    phi = joint.slip[keep][order]
    force = (joint.stiffness * joint.slip)[keep][order]
    return np.concatenate([[0.0], np.cumsum(force)]), phi


def anisotropic(x: IwanOperator, y: IwanOperator, pairing: str = DEFAULT_PAIRING) -> CircularIwan:
    """The 2-D joint that is ``x`` along x and ``y`` along y (its elements split), its
    elements matched by ``pairing`` (:data:`PAIRINGS`).

    Notes
    -----
    Each 1-D joint's elements, sorted by slip displacement, occupy intervals of the
    cumulative slip force tau in [0, F] (F = sum k phi, the same for both joints within
    :data:`SAME_SLIP_FORCE`; y's intervals are scaled to x's F). The pairing maps tau_x to
    tau_y, measure-preserving; on each interval of the common refinement (x's edges and the
    preimages of y's) one element of slip force s = its length, k_x = s / phi_x,
    k_y = s / phi_y. So along x the elements of x are split into pieces of the same total
    stiffness and slip displacement, and likewise along y.
    """
    if pairing not in PAIRINGS:
        raise ParameterError(f"unknown pairing {pairing!r}; valid: {', '.join(PAIRINGS)}")
    x_edges, x_phi = _edges(x)
    y_edges, y_phi = _edges(y)
    f = x_edges[-1]
    if abs(y_edges[-1] - f) > SAME_SLIP_FORCE * f:
        raise ParameterError(f"the joints along x and y must have the same slip force, got "
                             f"{f:.9g} N and {y_edges[-1]:.9g} N")
    y_edges = y_edges * (f / y_edges[-1])
    y_edges[-1] = f
    cuts, to_y = PAIRINGS[pairing](x_edges, y_edges)
    length = np.diff(cuts)
    mid = 0.5 * (cuts[1:] + cuts[:-1])[length > 0.0]
    length = length[length > 0.0]
    ix = np.clip(np.searchsorted(x_edges, mid) - 1, 0, x_phi.size - 1)
    iy = np.clip(np.searchsorted(y_edges, to_y(mid)) - 1, 0, y_phi.size - 1)
    return CircularIwan(f"{x.name}/{y.name}", length / x_phi[ix], x_phi[ix],
                        stiffness_y=length / y_phi[iy])


#: A coupling: ``(x, y, pairing)`` -> the operators of a two-directional joint that is the
#: 1-D joint ``x`` along its first direction and ``y`` (None: ``x``) along its second.
Coupling = Callable[[IwanOperator, IwanOperator | None, str | None],
                    tuple[IwanOperator | CircularIwan, ...]]


def _decoupled(x: IwanOperator, y: IwanOperator | None = None, pairing: str | None = None
               ) -> tuple[IwanOperator, IwanOperator]:
    if pairing is not None:
        raise ParameterError(f"pairing {pairing!r} does not apply to the decoupled coupling "
                             "(its two directions are independent); leave it out")
    return x, x if y is None else y


def _circular(x: IwanOperator, y: IwanOperator | None = None, pairing: str | None = None
              ) -> tuple[CircularIwan]:
    if y is None:
        if pairing is not None:
            raise ParameterError(f"pairing {pairing!r} needs a second 1-D joint (the joint "
                                 "across); one joint's elements pair with themselves")
        return (circular(x),)
    return (anisotropic(x, y, DEFAULT_PAIRING if pairing is None else pairing),)


#: Coupling name (:data:`microslip.conventions.COUPLINGS`) -> the operators of a
#: two-directional joint built from the 1-D joint x
#: along its first direction and y (default x) along its second: ``circular`` one
#: :class:`CircularIwan` on both directions (:func:`circular` of x, or
#: :func:`anisotropic` (x, y, pairing)), ``decoupled`` one :class:`IwanOperator` per
#: direction, x and y (the paper's sum).
COUPLINGS: dict[str, Coupling] = dict(zip(COUPLING_NAMES, (_circular, _decoupled),
                                          strict=True))
