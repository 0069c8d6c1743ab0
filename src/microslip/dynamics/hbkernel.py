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
                   kmat: np.ndarray, mmat: np.ndarray, cmat: np.ndarray, si: float,
                   o2: np.ndarray, pair: np.ndarray, dc: np.ndarray,
                   weights: np.ndarray, phi: np.ndarray, ck: np.ndarray, ckp: np.ndarray,
                   offsets: np.ndarray, synth: np.ndarray, analysis: np.ndarray,
                   r: np.ndarray, jac: np.ndarray, dxi: np.ndarray) -> None:
    """Residual ``r`` (N, (n,)), ``jac`` = [dr/dx | dr/dw] (N/mm and N·s, (n, n + 1)) and
    ``dxi`` = dr/dxi (N·s, (n,)) at coefficients ``x`` (mm), written into the given arrays;
    ``jac``'s first n columns must be zero on entry (only the harmonic blocks are written,
    so that ``jac`` may be a Fortran-ordered view that LAPACK factors without a copy).

    ``kmat``, ``mmat``, ``cmat``: the structure's (dofs, dofs) K, M, C (SI), ``si`` the
    SI-to-mm factor; a DOF's h coefficients (``synth.shape[1]``) have the orders squared
    ``o2`` (h,), and d/dtheta maps coefficient ``pair[a]`` into ``a`` by the factor
    ``dc[a]`` (``pair[a] = -1``: none, the static c_0). The (n, n) matrices ``K kron I``,
    ``M kron k^2``, ``C kron d/dtheta`` and ``M kron d/dtheta`` of
    :class:`~.hb.HarmonicBalance` are never formed: each row visits only the two columns of
    every DOF that its harmonic's 2 x 2 block reaches (the others are zero). ``weights``
    (joints, dofs) the 1-D Iwan joints' participations, joint j's elements
    ``phi[offsets[j]:offsets[j + 1]]`` ascending (mm) with running sums ``ck``, ``ckp`` of k
    and k phi at ``[offsets[j] + j, offsets[j + 1] + j]`` (:func:`~.kernels.periodic_kernel`).

    Notes
    -----
    ``r = (K - w^2 M k^2 + w (C - xi M) d/dtheta) x - P + sum_j B_j F_j(B_j^T x)``,
    ``B_j = w_j kron I_h``; dr/dx the bracket plus ``B_j dF_j/dU B_j^T``. Each entry of the
    bracket is computed as ``si * (A[d, e] * b[a, b])`` of the Kronecker products and
    summed in ascending column order, as over the formed matrices (the same numbers).
    """
    n = x.size
    h = synth.shape[1]
    dofs_all = kmat.shape[0]
    w2 = omega * omega
    wxi = omega * xi
    cols = np.empty(2, dtype=np.int64)
    for d in range(dofs_all):
        for a in range(h):
            i = d * h + a
            p = pair[a]
            if p < 0:
                nc = 1
                cols[0] = a
            elif p < a:
                nc = 2
                cols[0], cols[1] = p, a
            else:
                nc = 2
                cols[0], cols[1] = a, p
            ri = -load[i]
            mi = 0.0
            ci = 0.0
            mci = 0.0
            for e in range(dofs_all):
                kde = kmat[d, e]
                mde = mmat[d, e]
                cde = cmat[d, e]
                for t in range(nc):
                    b = cols[t]
                    if b == a:
                        kk = si * kde
                        mm = si * (mde * o2[a])
                        cc = 0.0
                        mc = 0.0
                    else:
                        kk = 0.0
                        mm = 0.0
                        cc = si * (cde * dc[a])
                        mc = si * (mde * dc[a])
                    val = kk - w2 * mm + omega * cc - wxi * mc
                    j = e * h + b
                    jac[i, j] = val
                    xj = x[j]
                    ri += val * xj
                    mi += mm * xj
                    ci += cc * xj
                    mci += mc * xj
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


@njit(cache=True, fastmath=False, nogil=True)
def _augmented(y: np.ndarray, y_pred: np.ndarray, row: np.ndarray, load: np.ndarray,
               kmat: np.ndarray, mmat: np.ndarray, cmat: np.ndarray, si: float,
               o2: np.ndarray, pair: np.ndarray, dc: np.ndarray, weights: np.ndarray,
               phi: np.ndarray, ck: np.ndarray, ckp: np.ndarray,
               offsets: np.ndarray, synth: np.ndarray, analysis: np.ndarray,
               r: np.ndarray, jac: np.ndarray, dxi: np.ndarray) -> None:
    """``[R(y); row . (y - y_pred)]`` and its Jacobian ``[dR/dy; row]`` into ``r``, ``jac``
    (R the balance at ``y = [x, w]``, without negative damping)."""
    n = y.size - 1
    jac[:n, :n] = 0.0
    balance_kernel(y[:n], y[n], 0.0, load, kmat, mmat, cmat, si, o2, pair, dc, weights, phi,
                   ck, ckp, offsets, synth, analysis, r[:n], jac[:n], dxi)
    r[n] = row @ (y - y_pred)
    jac[n] = row


@njit(cache=True, fastmath=False, nogil=True)
def corrector_kernel(y_pred: np.ndarray, row: np.ndarray, scale: np.ndarray, tol: float,
                     max_iter: int, contraction: float, halvings: int, load: np.ndarray,
                     kmat: np.ndarray, mmat: np.ndarray, cmat: np.ndarray, si: float,
                     o2: np.ndarray, pair: np.ndarray, dc: np.ndarray, weights: np.ndarray,
                     phi: np.ndarray, ck: np.ndarray, ckp: np.ndarray,
                     offsets: np.ndarray, synth: np.ndarray, analysis: np.ndarray,
                     y_out: np.ndarray, jac_out: np.ndarray) -> bool:
    """Newton's method on the pseudo-arclength system ``[R(y); row . (y - y_pred)] = 0``
    from ``y_pred``, R the balance of :func:`balance_kernel` alone (no other joints):
    line for line :func:`~.continuation.newton` (same convergence estimate, halving and
    tolerance; its ``CONTRACTION`` and ``MAX_HALVINGS`` come in as ``contraction`` and
    ``halvings``, not as globals, which a cached compilation would freeze), compiled.
    Writes the solution into ``y_out`` and the augmented Jacobian at the last iterate
    evaluated into ``jac_out``; returns whether it converged. Raises
    ``np.linalg.LinAlgError`` on a singular Jacobian (the caller's non-convergence)."""
    m = y_pred.size
    y = y_pred.copy()
    r, jac, dxi = np.empty(m), np.empty((m, m)), np.empty(m - 1)
    r_new, jac_new = np.empty(m), np.empty((m, m))
    args = (load, kmat, mmat, cmat, si, o2, pair, dc, weights, phi, ck, ckp, offsets, synth,
            analysis)
    _augmented(y, y_pred, row, *args, r, jac, dxi)
    previous = 0.0
    for _ in range(max_iter):
        step = np.linalg.solve(jac, -r)
        size = np.max(np.abs(step / scale))
        theta = size / previous if previous > 0.0 else 1.0
        if size < tol or (theta < contraction and size * theta / (1.0 - theta) < tol):
            y_out[:] = y + step
            jac_out[:] = jac
            return bool(np.all(np.isfinite(y_out)))
        previous = size
        norm0 = r @ r
        lam = 1.0
        trial = y
        for _ in range(halvings):
            trial = y + lam * step
            _augmented(trial, y_pred, row, *args, r_new, jac_new, dxi)
            if r_new @ r_new <= norm0 or lam * size < tol:
                break
            lam *= 0.5
        y = trial
        r, r_new = r_new, r
        jac, jac_new = jac_new, jac
        if not np.all(np.isfinite(r)):
            break
    y_out[:] = y
    jac_out[:] = jac
    return False
