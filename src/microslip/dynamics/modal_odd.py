"""The extended periodic motion concept on the odd harmonics only: the same curve as
:func:`~.modal.epmc` for joints whose force is odd (Iwan and circular Jenkins elements to the
ground or between DOFs, no static load), at a fraction of its cost on many DOFs.

A joint force with ``f(-u) = -f(u)`` and a rate-independent hysteresis has a steady state
with half-wave symmetry, ``u(t + T/2) = -u(t)``, when the motion has it: the balance's even
harmonics (the static one included) then vanish identically, and Newton on the odd
harmonics alone (``x = S y``, residual ``S^T r``, Jacobian ``S^T J S``) finds the same
solution as on every harmonic. The dense solve, the cost on a reduced model with many
contact DOFs, shrinks from ``(n (2H + 1))^3`` to about ``(n (H + 1))^3``, some 6x fewer
operations for H = 7. Not for joints whose force is not odd (the 3-D contact element's
normal lift-off, :mod:`.operators3d`), which :func:`epmc_odd` refuses.

Units: as :mod:`.modal`.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..blas import single_threaded_blas
from ..errors import ParameterError
from .continuation import newton
from .hb import DEFAULT_HB_SAMPLES, HarmonicBalance
from .modal import TOLERANCE, ModalCurve, _amplitudes, stuck_mode
from .operators3d import Contact3D
from .structure import Structure

__all__ = ["epmc_odd"]

Array = NDArray[np.float64]


def epmc_odd(structure: Structure, amplitude: ArrayLike, harmonics: int,
             samples: int = DEFAULT_HB_SAMPLES, mode: int = 0) -> ModalCurve:
    """:func:`~.modal.epmc` restricted to the odd harmonics 1, 3, ..., <= ``harmonics``
    (the same curve for odd joint forces; see the module's notes)."""
    if any(isinstance(link.operator, Contact3D) for link in structure.joints):
        raise ParameterError("the odd-harmonic EPMC needs odd joint forces; the 3-D contact "
                             "element's normal lift-off is not: use epmc")
    with single_threaded_blas():
        return _epmc_odd(structure, _amplitudes(amplitude), harmonics, samples, mode)


def _epmc_odd(structure: Structure, a: Array, harmonics: int, samples: int, mode: int
              ) -> ModalCurve:
    hb = HarmonicBalance(structure, harmonics, samples)
    h = 2 * harmonics + 1
    n = hb.size
    odd = np.array([c for k in range(1, harmonics + 1, 2) for c in (2 * k - 1, 2 * k)])
    keep = (np.arange(structure.dofs)[:, None] * h + odd[None, :]).ravel()
    m_odd = keep.size
    phi, m, _, c = stuck_mode(structure, mode)
    omega0 = float(np.sqrt(phi @ structure.stuck_stiffness() @ phi / m))
    full = np.zeros(n)
    guess = np.zeros(m_odd + 2)
    first = np.zeros((structure.dofs, h))
    first[:, 1] = phi
    guess[:m_odd] = first.ravel()[keep]
    guess[m_odd], guess[m_odd + 1] = omega0, c / m
    rows = np.zeros((2, m_odd + 2))
    out = np.zeros((2, structure.dofs, h))
    out[0, :, 1] = structure.output
    out[1, :, 2] = structure.output
    rows[:, :m_odd] = out.reshape(2, -1)[:, keep]
    load = np.zeros(n)
    freq = np.empty(a.size)
    zeta = np.empty(a.size)
    previous = 1.0
    for i, ai in enumerate(a):
        def fun(y: Array, ai: float = ai) -> tuple[Array, Array]:
            full[:] = 0.0
            full[keep] = y[:m_odd]
            res = hb.residual(full, float(y[m_odd]), load, float(y[m_odd + 1]))
            r = np.concatenate([res.r[keep], rows @ y - (ai, 0.0)])
            jac = np.vstack([np.column_stack([res.dx[np.ix_(keep, keep)], res.dw[keep],
                                              res.dxi[keep]]), rows])
            return r, jac

        guess[:m_odd] *= ai / previous
        scale = np.concatenate([np.full(m_odd, ai), [omega0, omega0]])
        y, ok, _ = newton(fun, guess, scale, TOLERANCE, max_iter=50)
        if not ok:
            raise ParameterError(f"the extended periodic motion concept did not converge at "
                                 f"amplitude {ai:.6g} mm")
        freq[i] = y[m_odd] / (2.0 * np.pi)
        zeta[i] = y[m_odd + 1] / (2.0 * y[m_odd])
        guess, previous = y, ai
    return ModalCurve(method="epmc", amplitude=a, frequency=freq, damping_ratio=zeta,
                      harmonics=harmonics, samples=samples)
