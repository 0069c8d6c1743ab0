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

__all__ = ["DEFAULT_HB_SAMPLES", "HarmonicBalance", "Residual", "from_time", "to_time"]

#: Time samples per period of the AFT scheme, unless given.
DEFAULT_HB_SAMPLES = 128

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
    """

    def __init__(self, structure: Structure, harmonics: int,
                 samples: int = DEFAULT_HB_SAMPLES) -> None:
        if not (isinstance(harmonics, int) and 1 <= harmonics <= 256):
            raise ParameterError(f"harmonics must be a whole number in [1, 256], got "
                                 f"{harmonics!r}")
        if not (isinstance(samples, int) and 2 * harmonics + 2 <= samples <= 1 << 16):
            raise ParameterError(f"samples must be a whole number in [{2 * harmonics + 2}, "
                                 f"65536] for {harmonics} harmonics, got {samples!r}")
        self.structure = structure
        self.harmonics = harmonics
        self.samples = samples
        h = 2 * harmonics + 1
        order = np.zeros(h)
        order[1::2] = order[2::2] = np.arange(1, harmonics + 1)
        dc = np.zeros((h, h))  # d/dtheta on the coefficients
        for k in range(1, harmonics + 1):
            dc[2 * k - 1, 2 * k] = k
            dc[2 * k, 2 * k - 1] = -k
        s = SI_PER_MM
        self._k = s * np.kron(structure.stiffness, np.eye(h))
        self._m = s * np.kron(structure.mass, np.diag(order**2))
        self._c = s * np.kron(structure.damping, dc)
        self._mc = s * np.kron(structure.mass, dc)
        # the AFT's two transforms as matrices (small: a product beats an FFT call)
        self._synth = np.ascontiguousarray(to_time(np.eye(h), samples).T)  # (N, h)
        self._analysis = np.ascontiguousarray(from_time(np.eye(samples), harmonics).T)
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
        """Number of unknown coefficients, n_dof (2H + 1)."""
        return self.structure.dofs * (2 * self.harmonics + 1)

    def excitation(self, shape: Array, force: float) -> Array:
        """Coefficient vector of the excitation ``shape * force * cos(w t)`` (N)."""
        p = np.zeros((self.structure.dofs, 2 * self.harmonics + 1))
        p[:, 1] = np.asarray(shape, dtype=np.float64) * force
        return p.ravel()

    def stuck_guess(self, omega: float, load: Array) -> Array:
        """Coefficients (mm) of the linear response with every joint stuck."""
        extra = np.zeros((self.size, self.size))
        h = 2 * self.harmonics + 1
        for link in self.structure.joints:
            extra += np.kron(link.stuck_stiffness, np.eye(h))
        lin = self._k - omega**2 * self._m + omega * self._c + extra
        return np.asarray(np.linalg.solve(lin, load))

    def residual(self, x: Array, omega: float, load: Array, xi: float = 0.0) -> Residual:
        """Residual (N) and derivatives at coefficients ``x`` (mm), frequency ``omega``
        (rad/s), excitation coefficients ``load`` (N) and negative damping ``xi`` (1/s)."""
        n = self.size
        r, jac, dxi = np.empty(n), np.empty((n, n + 1)), np.empty(n)
        balance_kernel(np.ascontiguousarray(x, dtype=np.float64), float(omega), float(xi),
                       np.ascontiguousarray(load, dtype=np.float64), self._k, self._m,
                       self._c, self._mc, *self._compiled, self._synth, self._analysis,
                       r, jac, dxi)
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
        args = (self._k, self._m, self._c, self._mc, *self._compiled, self._synth,
                self._analysis)

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
        h = 2 * self.harmonics + 1
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
        q = xs.reshape(len(xs), self.structure.dofs, 2 * self.harmonics + 1)
        out = self.structure.output
        return np.asarray(np.hypot(q[:, :, 1] @ out, q[:, :, 2] @ out))

    def amplitude(self, x: Array) -> tuple[float, Array]:
        """First-harmonic amplitude (mm) of the output coordinate and its gradient in x."""
        h = 2 * self.harmonics + 1
        out = self.structure.output
        q = x.reshape(self.structure.dofs, h)
        c, s = float(out @ q[:, 1]), float(out @ q[:, 2])
        a = float(np.hypot(c, s))
        grad = np.zeros((self.structure.dofs, h))
        if a > 0.0:
            grad[:, 1] = out * (c / a)
            grad[:, 2] = out * (s / a)
        return a, grad.ravel()


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
