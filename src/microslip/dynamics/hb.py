"""Harmonic balance with the alternating frequency-time scheme (AFT).

Every degree of freedom is a truncated Fourier series in theta = w t,
``q(theta) = c_0 + sum_{k=1..H} (c_k cos(k theta) + s_k sin(k theta))``, stored per degree of
freedom as ``[c_0, c_1, s_1, ..., c_H, s_H]`` (mm; vector index ``dof * (2H + 1) + j``).
The joint forces are evaluated at N time samples of one period, their
Fourier coefficients taken back (both transforms as small precomputed matrices, the 1-D
Iwan operators in one compiled call), and their Jacobian follows from the
operator's analytic time-domain Jacobian by the same two transforms.

Units: the residual is in N (force harmonics), coefficients in mm, frequency in rad/s.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
from numpy.typing import NDArray

from ..errors import ParameterError
from .continuation import CONTRACTION, MAX_HALVINGS
from .hbkernel import balance_kernel, corrector_kernel
from .operators import HystereticOperator, IwanOperator
from .operators2d import CircularIwan
from .operators3d import Contact3D
from .structure import SI_PER_MM, JointLink, Structure

__all__ = [
    "DEFAULT_HARMONICS",
    "DEFAULT_HB_SAMPLES",
    "MAX_HARMONICS",
    "HarmonicBalance",
    "Residual",
    "check_balance",
    "from_time",
    "harmonic_columns",
    "to_time",
]

#: Time samples per period of the AFT scheme, unless given.
DEFAULT_HB_SAMPLES = 128
#: Harmonics of the balance unless a study says (a mesh's forced response:
#: :data:`microslip.meshdynamics.frfstudy.DEFAULT_MESH_HARMONICS`).
DEFAULT_HARMONICS = 7
#: Most harmonics of a balance; most time samples per period.
MAX_HARMONICS = 256
MAX_SAMPLES = 65536


def check_balance(harmonics: int, samples: int) -> tuple[int, int]:
    """(harmonics, samples) if harmonics is in [1, :data:`MAX_HARMONICS`] and samples in
    [2 harmonics + 2, :data:`MAX_SAMPLES`] (enough to resolve them); one line otherwise."""
    if not 1 <= harmonics <= MAX_HARMONICS:
        raise ParameterError(f"harmonics must be in [1, {MAX_HARMONICS}], got {harmonics}")
    low = 2 * harmonics + 2
    if not low <= samples <= MAX_SAMPLES:
        raise ParameterError(f"samples must be in [{low}, {MAX_SAMPLES}] for {harmonics} "
                             f"harmonics, got {samples}")
    return int(harmonics), int(samples)

Array = NDArray[np.float64]


def to_time(coeffs: Array, samples: int) -> Array:
    """Values at theta_j = 2 pi j / N (last axis) of the series with ``coeffs`` (last axis)."""
    h = (coeffs.shape[-1] - 1) // 2
    spec = np.zeros((*coeffs.shape[:-1], samples // 2 + 1), dtype=np.complex128)
    spec[..., 0] = coeffs[..., 0] * samples
    spec[..., 1:h + 1] = (coeffs[..., 1::2] - 1j * coeffs[..., 2::2]) * (samples / 2.0)
    return np.fft.irfft(spec, n=samples, axis=-1)


def from_time(values: Array, harmonics: int) -> Array:
    """Fourier coefficients ``[c_0, c_1, s_1, ...]`` (last axis) of periodic samples (last
    axis), by the rectangle rule (a real FFT)."""
    n = values.shape[-1]
    spec = np.fft.rfft(values, axis=-1)[..., :harmonics + 1]
    out = np.empty((*values.shape[:-1], 2 * harmonics + 1))
    out[..., 0] = spec[..., 0].real / n
    out[..., 1::2] = spec[..., 1:].real * (2.0 / n)
    out[..., 2::2] = spec[..., 1:].imag * (-2.0 / n)
    return out


class Residual:
    """The harmonic-balance residual (N) and its derivatives at one point.

    Attributes: ``r`` (n_eq,), ``jac`` (n_eq, n_eq + 1) = [dr/dX | dr/dw], of which ``dx``
    (n_eq, n_eq) = dr/dX (N/mm) and ``dw`` (n_eq,) = dr/dw (N·s) are views, ``dxi``
    (n_eq,) = dr/dxi (N·s), xi being the mass-proportional negative damping of the
    extended periodic motion concept.
    """

    __slots__ = ("dw", "dx", "dxi", "jac", "r")

    def __init__(self, r: Array, jac: Array, dxi: Array) -> None:
        self.r, self.jac, self.dxi = r, jac, dxi
        self.dx, self.dw = jac[:, :-1], jac[:, -1]


class HarmonicBalance:
    """Harmonic balance of a :class:`Structure` with H harmonics and N AFT samples.

    Notes
    -----
    Residual for harmonic k (forces in N, coefficients in mm, SI matrices times 1e-3):
    ``1e-3 [(K - k^2 w^2 M) c_k + k w (C - xi M) s_k] + F_c,k - P_c,k``,
    ``1e-3 [(K - k^2 w^2 M) s_k - k w (C - xi M) c_k] + F_s,k - P_s,k``,
    where F are the joint-force harmonics and P the excitation's. With ``u = w . q`` the
    joint displacement, ``dF/dU = P_N J E_N`` (E_N: coefficients -> samples, P_N: samples
    -> coefficients, J the operator's time-domain Jacobian), and the structure sees
    ``w F`` and ``w w^T dF/dU``.

    With ``odd`` the unknowns are the cos and sin of the odd harmonics 1, 3, ... only (per
    DOF ``[c_1, s_1, c_3, s_3, ...]``, :attr:`columns` of the full layout): the balance of a
    half-wave symmetric motion, ``q(theta + pi) = -q(theta)``, whose even harmonics vanish
    when every joint force is odd, ``f(-u) = -f(u)`` (:mod:`.modal_odd`). Its residual,
    Jacobian and AFT are those of the full balance restricted to the odd coefficients at an
    input with zero even ones, computed on the odd ones alone (the linear part never leaves
    the harmonic's 2 x 2 block, and the even harmonics of an odd force of a half-wave
    symmetric motion are zero), at about ((H + 1) / (2H + 1))^2 of the memory and a
    quarter to an eighth of the work of the full balance.
    """

    def __init__(self, structure: Structure, harmonics: int,
                 samples: int = DEFAULT_HB_SAMPLES, odd: bool = False) -> None:
        if not (isinstance(harmonics, int) and 1 <= harmonics <= 256):
            raise ParameterError(f"harmonics must be a whole number in [1, 256], got "
                                 f"{harmonics!r}")
        if not (isinstance(samples, int) and 2 * harmonics + 2 <= samples <= 1 << 16):
            raise ParameterError(f"samples must be a whole number in [{2 * harmonics + 2}, "
                                 f"65536] for {harmonics} harmonics, got {samples!r}")
        self.structure = structure
        self.harmonics = harmonics
        self.samples = samples
        self.odd = bool(odd)
        #: the full layout's columns ``[c_0, c_1, s_1, ..., c_H, s_H]`` this balance keeps per
        #: DOF, in order: all of them, or (``odd``) the cos/sin of harmonics 1, 3, 5, ...
        self.columns = harmonic_columns(harmonics, self.odd)
        h = self.width = int(self.columns.size)
        #: where c_1 sits in a DOF's coefficients (s_1 follows it)
        self.first = int(np.flatnonzero(self.columns == 1)[0])
        order = ((self.columns + 1) // 2).astype(np.float64)
        # d/dtheta on the coefficients couples c_k (row) to s_k (column) by k, s_k to c_k by -k:
        # each column's partner and that factor (-1 and 0 for c_0)
        cos = self.columns % 2 == 1
        self._pair = np.where(self.columns == 0, -1,
                              np.where(cos, np.arange(h) + 1, np.arange(h) - 1)).astype(np.int64)
        self._dc = np.where(cos, order, -order)
        self._o2 = order**2
        # the structure's matrices in SI; K, M k^2, C d/dtheta and M d/dtheta on the
        # coefficients are their Kronecker products, never formed (:mod:`.hbkernel`)
        self._kmat = np.ascontiguousarray(structure.stiffness, dtype=np.float64)
        self._mmat = np.ascontiguousarray(structure.mass, dtype=np.float64)
        self._cmat = np.ascontiguousarray(structure.damping, dtype=np.float64)
        self._linear = (self._kmat, self._mmat, self._cmat, float(SI_PER_MM), self._o2,
                        self._pair, self._dc)
        # the AFT's two transforms as matrices (small: a product beats an FFT call), on the
        # kept columns
        full = 2 * harmonics + 1
        self._synth = np.ascontiguousarray(to_time(np.eye(full), samples).T[:, self.columns])
        self._analysis = np.ascontiguousarray(
            from_time(np.eye(samples), harmonics).T[self.columns])
        # the 1-D Iwan joints go into the compiled residual (:mod:`.hbkernel`), any other
        # joint j is added in Python: its harmonics U = B_j^T x (direction-major), its force
        # enters as B_j F (B_j = W_j kron I_h, W_j the (n_dof, directions) participation),
        # kept only on the rows of the DOFs the joint touches
        compiled = [isinstance(link.operator, IwanOperator) and link.directions == 1
                    for link in structure.joints]
        self._compiled = _compiled_joints(
            [link for link, c in zip(structure.joints, compiled, strict=True) if c],
            structure.dofs)
        self._links = tuple(_condensed(link.operator, link.weights, h)
                            for link, c in zip(structure.joints, compiled, strict=True)
                            if not c)

    @property
    def size(self) -> int:
        """Number of unknown coefficients, n_dof times the kept columns per DOF (2H + 1,
        or 2 per odd harmonic)."""
        return self.structure.dofs * self.width

    def expand(self, x: Array) -> Array:
        """Coefficients ``x`` (last axis, this balance's layout) in the full layout
        ``[c_0, c_1, s_1, ..., c_H, s_H]`` per DOF, the columns not kept zero."""
        x = np.asarray(x, dtype=np.float64)
        dofs = self.structure.dofs
        out = np.zeros((*x.shape[:-1], dofs, 2 * self.harmonics + 1))
        out[..., self.columns] = x.reshape(*x.shape[:-1], dofs, self.width)
        return out.reshape(*x.shape[:-1], -1)

    def restrict(self, x: Array) -> Array:
        """Full-layout coefficients ``x`` (last axis) on this balance's columns."""
        x = np.asarray(x, dtype=np.float64)
        q = x.reshape(*x.shape[:-1], self.structure.dofs, 2 * self.harmonics + 1)
        return np.ascontiguousarray(q[..., self.columns]).reshape(*x.shape[:-1], -1)

    def excitation(self, shape: Array, force: float) -> Array:
        """Coefficient vector of the excitation ``shape * force * cos(w t)`` (N)."""
        p = np.zeros((self.structure.dofs, self.width))
        p[:, self.first] = np.asarray(shape, dtype=np.float64) * force
        return p.ravel()

    def stuck_guess(self, omega: float, load: Array) -> Array:
        """Coefficients (mm) of the linear response with every joint stuck."""
        dofs, h, s = self.structure.dofs, self.width, SI_PER_MM
        extra = np.zeros((dofs, dofs))
        for link in self.structure.joints:
            extra = extra + link.stuck_stiffness
        lin = np.zeros((dofs, h, dofs, h))
        for a in range(h):  # the blocks of (K - w^2 M k^2 + w C d/dtheta) kron I + extra
            lin[:, a, :, a] = (s * self._kmat - omega**2 * (s * (self._mmat * self._o2[a]))
                               + extra)
            b = self._pair[a]
            if b >= 0:
                lin[:, a, :, b] = omega * (s * (self._cmat * self._dc[a]))
        return np.asarray(np.linalg.solve(lin.reshape(self.size, self.size), load))

    def residual(self, x: Array, omega: float, load: Array, xi: float = 0.0,
                 out: Array | None = None) -> Residual:
        """Residual (N) and derivatives at coefficients ``x`` (mm), frequency ``omega``
        (rad/s), excitation coefficients ``load`` (N) and negative damping ``xi`` (1/s);
        ``out`` (n, n + 1), if given and zero, receives the Jacobian (a view into a larger
        system saves a copy of it; Fortran-ordered, LAPACK factors it without another)."""
        n = self.size
        r, dxi = np.empty(n), np.empty(n)
        jac = np.zeros((n, n + 1)) if out is None else out
        balance_kernel(np.ascontiguousarray(x, dtype=np.float64), float(omega), float(xi),
                       np.ascontiguousarray(load, dtype=np.float64), *self._linear,
                       *self._compiled, self._synth, self._analysis, r, jac, dxi)
        for operator, idx, b, block in self._links:
            force, dforce = self.joint_harmonics(operator, b.T @ x[idx])
            r[idx] += b @ force
            jac[block] += b @ dforce @ b.T
        return Residual(r, jac, dxi)

    def corrector(self, load: Array, max_iter: int
                  ) -> Callable[[Array, Array, Array, float], tuple[Array, bool, Array]] | None:
        """The compiled pseudo-arclength corrector of the balance in ``y = [x, w]`` under
        the excitation ``load`` (N), as :func:`~.continuation.arclength` takes it, or None
        if some joint is evaluated in Python (then :func:`~.continuation.newton` runs)."""
        if self._links:
            return None
        load = np.ascontiguousarray(load, dtype=np.float64)
        args = (*self._linear, *self._compiled, self._synth, self._analysis)

        def correct(y_pred: Array, row: Array, scale: Array, tol: float
                    ) -> tuple[Array, bool, Array]:
            y, jac = np.empty(y_pred.size), np.empty((y_pred.size, y_pred.size))
            try:
                ok = corrector_kernel(y_pred, row, scale, tol, max_iter, CONTRACTION,
                                      MAX_HALVINGS, load, *args, y, jac)
            except np.linalg.LinAlgError:  # a singular Jacobian: no convergence
                return y_pred, False, jac
            return y, bool(ok), jac

        return correct

    def joint_harmonics(self, operator: HystereticOperator | CircularIwan | Contact3D, u: Array
                        ) -> tuple[Array, Array]:
        """A joint's force harmonics (N, (d (2H + 1),)) and their derivative in its
        displacement harmonics ``u`` (mm, direction-major), N/mm; d its directions."""
        compiled = getattr(operator, "periodic_harmonics", None)
        if compiled is not None:  # the 1-D Iwan operators: one compiled AFT call
            return compiled(u, self._synth, self._analysis)
        h = self.width
        a = self._analysis
        d = getattr(operator, "directions", 1)
        if d >= 2:  # two-directional joints, and the 3-D contact element (operators3d)
            samples = self._synth @ u.reshape(d, h).T
            f, jb = operator.periodic_force_projected(samples, self._synth)  # type: ignore[union-attr]
            # jb[t, a, b, c] -> d F_a,i / d U_b,c
            df = np.einsum("it,tabc->aibc", a, jb)
            return (a @ f).T.ravel(), df.reshape(d * h, d * h)
        f, jac = operator.periodic_force(self._synth @ u)
        return a @ f, a @ jac @ self._synth

    def amplitudes(self, xs: Array) -> Array:
        """First-harmonic amplitudes (mm) of the output coordinate at the coefficient
        vectors ``xs`` (m, n) (:meth:`amplitude` without its gradient, all at once)."""
        q = xs.reshape(len(xs), self.structure.dofs, self.width)
        out, c = self.structure.output, self.first
        return np.asarray(np.hypot(q[:, :, c] @ out, q[:, :, c + 1] @ out))

    def amplitude(self, x: Array) -> tuple[float, Array]:
        """First-harmonic amplitude (mm) of the output coordinate and its gradient in x."""
        h, j = self.width, self.first
        out = self.structure.output
        q = x.reshape(self.structure.dofs, h)
        c, s = float(out @ q[:, j]), float(out @ q[:, j + 1])
        a = float(np.hypot(c, s))
        grad = np.zeros((self.structure.dofs, h))
        if a > 0.0:
            grad[:, j] = out * (c / a)
            grad[:, j + 1] = out * (s / a)
        return a, grad.ravel()


def harmonic_columns(harmonics: int, odd: bool = False) -> NDArray[np.int64]:
    """The columns of the full layout ``[c_0, c_1, s_1, ..., c_H, s_H]`` a balance keeps:
    all 2H + 1, or (``odd``) the cos and sin of the odd harmonics 1, 3, ..., <= H."""
    if not odd:
        return np.arange(2 * harmonics + 1, dtype=np.int64)
    return np.array([c for k in range(1, harmonics + 1, 2) for c in (2 * k - 1, 2 * k)],
                    dtype=np.int64)


def _compiled_joints(links: list[JointLink], dofs: int) -> tuple[Array, Array, Array, Array,
                                                                  NDArray[np.int64]]:
    """The 1-D Iwan joints ``links`` as :func:`~.hbkernel.balance_kernel` takes them:
    weights (joints, dofs), and every joint's ascending phi (mm) and running sums of k and
    k phi concatenated, with the offsets of the phi."""
    weights = np.zeros((len(links), dofs))
    phi, ck, ckp, offsets = [], [], [], [0]
    for j, link in enumerate(links):
        weights[j] = link.participation
        p, c, cp = link.operator.ascending  # type: ignore[union-attr]
        phi.append(p)
        ck.append(c)
        ckp.append(cp)
        offsets.append(offsets[-1] + p.size)
    def flat(parts: list[Array]) -> Array:
        return np.ascontiguousarray(np.concatenate(parts) if parts else np.zeros(0))
    return weights, flat(phi), flat(ck), flat(ckp), np.array(offsets, dtype=np.int64)


def _condensed(operator: HystereticOperator | CircularIwan | Contact3D, weights: Array, h: int
               ) -> tuple[HystereticOperator | CircularIwan | Contact3D, NDArray[np.int64], Array,
                          tuple[NDArray[np.int64], ...]]:
    """The joint, the coefficient indices of the DOFs it touches, B restricted to them, and
    the index of their block of the Jacobian."""
    dofs = np.flatnonzero(np.any(weights != 0.0, axis=1))
    idx = (dofs[:, None] * h + np.arange(h)).ravel().astype(np.int64)
    return (operator, idx, np.asarray(np.kron(weights[dofs], np.eye(h)), dtype=np.float64),
            np.ix_(idx, idx))
