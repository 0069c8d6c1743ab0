"""Rate-independent hysteresis operators on a joint's displacement history.

A :class:`HystereticOperator` maps the relative displacement of a joint (mm) to its force
(N). Harmonic balance needs the closed periodic response and its Jacobian
(:meth:`~HystereticOperator.periodic_force`); time integration and non-periodic loadings
need :meth:`IwanOperator.force_history`. Every operator here is an :class:`IwanOperator`,
a parallel set of Jenkins elements: :func:`jenkins` is one element, the 4-parameter Iwan
element and the microslip models are distributions of them
(:mod:`microslip.dynamics.distributions`).

Units: displacement mm, force N, stiffness N/mm.
"""

from __future__ import annotations

from functools import cached_property
from typing import Protocol, runtime_checkable

import numpy as np
from numpy.typing import NDArray

from ..errors import ParameterError
from ..named import readonly, result
from ..params import check_positive
from .kernels import history_kernel, periodic_harmonics_kernel, periodic_kernel

__all__ = ["HystereticOperator", "IwanHistory", "IwanOperator", "jenkins"]


@runtime_checkable
class HystereticOperator(Protocol):
    """What harmonic balance and the describing function need of a joint's force law."""

    @property
    def name(self) -> str:
        """Short label (``jenkins``, ``iwan``, ``tip``, ...)."""
        ...

    @property
    def initial_stiffness(self) -> float:
        """Slope of the force at zero displacement from the virgin state, N/mm."""
        ...

    def periodic_force(self, x: NDArray[np.float64]
                       ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """Steady-state force ``f`` (N, shape (N,)) at the N samples of one period of ``x``
        (mm), the closed periodic response, and ``J[i, j] = d f_i / d x_j`` (N/mm, (N, N))."""
        ...

    def backbone_force(self, a: NDArray[np.float64]) -> NDArray[np.float64]:
        """Virgin-curve force F(a), N, at displacements ``a`` (mm); odd in ``a``."""
        ...


@result
class IwanHistory:
    """The force along a displacement history and the elements' final state.

    Attributes
    ----------
    force : ndarray, shape (N,)
        Force at each sample, N.
    state : ndarray, shape (n_elements,)
        Slider positions after the last sample, mm; pass as ``state`` to continue.
    """

    force: np.ndarray
    state: np.ndarray


@result
class IwanOperator:
    """A parallel set of Jenkins elements (a discrete Iwan model).

    Parameters
    ----------
    name : str
        Label used in output.
    stiffness : ndarray, shape (n,)
        Spring stiffness k_i of each element, N/mm, >= 0 (at least one > 0).
    slip : ndarray, shape (n,)
        Slip displacement phi_i of each element, mm, > 0; its slip force is k_i phi_i.

    Notes
    -----
    Virgin curve (REFERENCES.md, Iwan representation, discrete form):
    ``F(a) = sum_i k_i min(a, phi_i)`` for a >= 0, odd in a. The operator satisfies Masing's
    rule and the extended memory rules for every history (Iwan 1966), because each element
    does.

    Examples
    --------
    >>> op = jenkins(stiffness=100.0, slip_force=5.0)
    >>> float(op.backbone_force(np.array([0.02, 1.0]))[1])
    5.0
    >>> op.initial_stiffness
    100.0
    """

    name: str
    stiffness: np.ndarray
    slip: np.ndarray

    def __post_init__(self) -> None:
        k = np.ascontiguousarray(self.stiffness, dtype=np.float64)
        phi = np.ascontiguousarray(self.slip, dtype=np.float64)
        if k.ndim != 1 or k.shape != phi.shape or k.size == 0:
            raise ParameterError(f"stiffness and slip must be 1-D of one length >= 1, got "
                                 f"shapes {k.shape} and {phi.shape}")
        if not (np.all(np.isfinite(k)) and np.all(k >= 0.0) and k.sum() > 0.0):
            raise ParameterError("element stiffnesses must be finite, >= 0 N/mm and not all 0")
        if not (np.all(np.isfinite(phi)) and np.all(phi > 0.0)):
            raise ParameterError("element slip displacements must be finite and > 0 mm")
        object.__setattr__(self, "stiffness", readonly(k))
        object.__setattr__(self, "slip", readonly(phi))

    @property
    def initial_stiffness(self) -> float:
        """sum_i k_i, N/mm."""
        return float(self.stiffness.sum())

    @property
    def slip_force(self) -> float:
        """Macroslip force sum_i k_i phi_i, N (every element slipping)."""
        return float(self.stiffness @ self.slip)

    def backbone_force(self, a: NDArray[np.float64]) -> NDArray[np.float64]:
        a = np.asarray(a, dtype=np.float64)
        mag = np.minimum(np.abs(a)[..., None], self.slip) @ self.stiffness
        return np.asarray(np.sign(a) * mag)

    @cached_property
    def ascending(self) -> tuple[NDArray[np.float64], NDArray[np.float64],
                                  NDArray[np.float64]]:
        """phi ascending (mm) and the running sums of k and k phi over it (from 0; N/mm,
        N), the periodic kernel's view of the elements."""
        order = np.argsort(self.slip, kind="stable")
        k, phi = self.stiffness[order], self.slip[order]
        ck = np.concatenate([[0.0], np.cumsum(k)])
        ckp = np.concatenate([[0.0], np.cumsum(k * phi)])
        return np.ascontiguousarray(phi), ck, ckp

    def periodic_force(self, x: NDArray[np.float64]
                       ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        return self.periodic_force_projected(x, np.eye(np.size(x)))

    def periodic_force_projected(self, x: NDArray[np.float64], basis: NDArray[np.float64]
                                 ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """The closed periodic force ``f`` (N) of :meth:`periodic_force` and ``J @ basis``
        (shape (N, m)) without forming J: what harmonic balance needs, at a cost linear in
        the samples (``basis`` maps m coefficients to the N samples)."""
        x = _samples(x)
        basis = np.ascontiguousarray(basis, dtype=np.float64)
        if basis.ndim != 2 or basis.shape[0] != x.size:
            raise ParameterError(f"basis must have shape ({x.size}, m), got {basis.shape}")
        f = np.zeros(x.size)
        jb = np.zeros(basis.shape)
        periodic_kernel(x, *self.ascending, int(np.argmax(np.abs(x))), basis, f, jb)
        return f, jb

    def periodic_harmonics(self, u: NDArray[np.float64], synth: NDArray[np.float64],
                           analysis: NDArray[np.float64]
                           ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """Fourier coefficients of the closed periodic force (N, (m,)) and their derivative
        in the displacement's coefficients ``u`` (mm, (m,)), N/mm, (m, m), in one compiled
        call: ``analysis @ f(synth @ u)`` and ``analysis @ J @ synth`` (``synth`` (N, m)
        coefficients -> samples, ``analysis`` (m, N) samples -> coefficients)."""
        force = np.zeros(u.size)
        dforce = np.zeros((u.size, u.size))
        periodic_harmonics_kernel(u, synth, analysis, *self.ascending, force, dforce)
        return force, dforce

    def force_history(self, x: NDArray[np.float64],
                      state: NDArray[np.float64] | None = None) -> IwanHistory:
        """Force along an arbitrary displacement history ``x`` (mm).

        ``state`` is the elements' slider positions (mm) before the first sample, default
        the virgin state (all zero, at zero force); the path from the state to ``x[0]`` is
        taken as monotonic.
        """
        x = _samples(x)
        z = (np.zeros(self.stiffness.size) if state is None
             else np.array(state, dtype=np.float64, copy=True))
        if z.shape != self.stiffness.shape:
            raise ParameterError(f"state must have shape {self.stiffness.shape}, got {z.shape}")
        f = np.zeros(x.size)
        history_kernel(x, self.stiffness, self.slip, z, f)
        return IwanHistory(force=f, state=z)


def jenkins(stiffness: float, slip_force: float) -> IwanOperator:
    """One Jenkins element: spring ``stiffness`` (N/mm) in series with a Coulomb slider that
    slips at ``slip_force`` (N)."""
    k = check_positive("joint stiffness", stiffness, "N/mm")
    fs = check_positive("slip force", slip_force, "N")
    return IwanOperator("jenkins", np.array([k]), np.array([fs / k]))


def _samples(x: NDArray[np.float64]) -> NDArray[np.float64]:
    x = np.ascontiguousarray(x, dtype=np.float64)
    if x.ndim != 1 or x.size == 0:
        raise ParameterError(f"displacement samples must be a non-empty 1-D array, got {x.shape}")
    if not np.all(np.isfinite(x)):
        raise ParameterError("displacement samples must be finite (mm)")
    return x


