"""The harmonic-balance residual and its Jacobian in one compiled call.

:class:`~.hb.HarmonicBalance` evaluates its residual here: the linear structure's dynamic
stiffness and every 1-D Iwan joint (its compiled AFT step,
:func:`~.kernels.periodic_harmonics_kernel`) in one call, without intermediate numpy
arrays; joints of any other kind (two-directional, user operators) are added afterwards by
:mod:`.hb` in Python. Layout and units as :mod:`.hb`: coefficients mm, residual N,
frequency rad/s.
"""

from __future__ import annotations

import numpy as np

from .kernels import njit, periodic_harmonics_kernel

__all__ = ["balance_kernel"]


@njit(cache=True, fastmath=False, nogil=True)
def balance_kernel(x: np.ndarray, omega: float, xi: float, load: np.ndarray,
                   kk: np.ndarray, mm: np.ndarray, cc: np.ndarray, mc: np.ndarray,
                   weights: np.ndarray, phi: np.ndarray, ck: np.ndarray, ckp: np.ndarray,
                   offsets: np.ndarray, synth: np.ndarray, analysis: np.ndarray,
                   r: np.ndarray, jac: np.ndarray, dxi: np.ndarray) -> None:
    """Residual ``r`` (N, (n,)), ``jac`` = [dr/dx | dr/dw] (N/mm and N·s, (n, n + 1)) and
    ``dxi`` = dr/dxi (N·s, (n,)) at coefficients ``x`` (mm), written into the given arrays.

    ``kk``, ``mm``, ``cc``, ``mc``: the (n, n) matrices ``K``, ``M k^2``, ``C d/dtheta`` and
    ``M d/dtheta`` of :class:`~.hb.HarmonicBalance` (N/mm); ``weights`` (joints, dofs) the
    1-D Iwan joints' participations, joint j's elements ``phi[offsets[j]:offsets[j + 1]]``
    ascending (mm) with running sums ``ck``, ``ckp`` of k and k phi at
    ``[offsets[j] + j, offsets[j + 1] + j]`` (:func:`~.kernels.periodic_kernel`).

    Notes
    -----
    ``r = (K - w^2 M k^2 + w (C - xi M) d/dtheta) x - P + sum_j B_j F_j(B_j^T x)``,
    ``B_j = w_j kron I_h``; dr/dx the bracket plus ``B_j dF_j/dU B_j^T``.
    """
    n = x.size
    h = synth.shape[1]
    w2 = omega * omega
    wxi = omega * xi
    for i in range(n):
        ri = -load[i]
        mi = 0.0
        ci = 0.0
        mci = 0.0
        for j in range(n):
            a = kk[i, j] - w2 * mm[i, j] + omega * cc[i, j] - wxi * mc[i, j]
            jac[i, j] = a
            xj = x[j]
            ri += a * xj
            mi += mm[i, j] * xj
            ci += cc[i, j] * xj
            mci += mc[i, j] * xj
        r[i] = ri
        jac[i, n] = -2.0 * omega * mi + ci - xi * mci
        dxi[i] = -omega * mci
    dofs = weights.shape[1]
    u = np.empty(h)
    force = np.empty(h)
    dforce = np.empty((h, h))
    for jt in range(weights.shape[0]):
        w = weights[jt]
        u[:] = 0.0
        for d in range(dofs):
            if w[d] != 0.0:
                for c in range(h):
                    u[c] += w[d] * x[d * h + c]
        force[:] = 0.0
        dforce[:, :] = 0.0
        lo, hi = offsets[jt], offsets[jt + 1]
        periodic_harmonics_kernel(u, synth, analysis, phi[lo:hi], ck[lo + jt:hi + jt + 1],
                                  ckp[lo + jt:hi + jt + 1], force, dforce)
        for d in range(dofs):
            wd = w[d]
            if wd == 0.0:
                continue
            for a in range(h):
                r[d * h + a] += wd * force[a]
            for e in range(dofs):
                we = wd * w[e]
                if we == 0.0:
                    continue
                for a in range(h):
                    for b in range(h):
                        jac[d * h + a, e * h + b] += we * dforce[a, b]
