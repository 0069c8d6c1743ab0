"""Compiled kernels of the Iwan operator: parallel Jenkins elements on a displacement history.

Each element e has a spring of stiffness ``k[e]`` (N/mm) in series with a Coulomb slider
that slips when the spring stretch ``x - z`` reaches ``phi[e]`` (mm); its slip force is
``k[e] phi[e]`` (N). The state of an element is its slider position ``z`` (mm). The force of
the set is ``sum_e k[e] (x - z[e])``.

Notes
-----
One step of element e to displacement x (the return mapping of a Jenkins element):
``z <- x - phi`` if ``x - z > phi``, ``z <- x + phi`` if ``x - z < -phi``, else unchanged.
A parallel set of such elements obeys Masing's rule and its extended memory rules (Iwan
1966) for every history, so the operator needs no explicit memory stack.
"""

from __future__ import annotations

from typing import Any

import numpy as np

try:
    from numba import njit
except ImportError:  # pragma: no cover - exercised only without numba
    HAVE_NUMBA = False

    def njit(*args: Any, **kwargs: Any) -> Any:  # type: ignore[no-redef]
        """Stand-in decorator: the kernels stay plain (slow) Python functions."""
        return lambda f: f
else:
    HAVE_NUMBA = True

__all__ = ["HAVE_NUMBA", "history_kernel", "periodic_kernel", "periodic_projected_kernel"]


@njit(cache=True, fastmath=False, nogil=True)
def history_kernel(x: np.ndarray, k: np.ndarray, phi: np.ndarray, z: np.ndarray,
                   f: np.ndarray) -> None:
    """Force ``f`` (N, added into) along the history ``x`` (mm); ``z`` updated in place."""
    n = x.size
    for e in range(k.size):
        ke = k[e]
        ph = phi[e]
        ze = z[e]
        for t in range(n):
            xt = x[t]
            if xt - ze > ph:
                ze = xt - ph
            elif xt - ze < -ph:
                ze = xt + ph
            f[t] += ke * (xt - ze)
        z[e] = ze


@njit(cache=True, fastmath=False, nogil=True)
def periodic_kernel(x: np.ndarray, k: np.ndarray, phi: np.ndarray, start: int,
                    f: np.ndarray, jac: np.ndarray) -> None:
    """Closed periodic force ``f`` (N) and Jacobian ``jac`` (N/mm), both added into.

    The history starts at sample ``start``, where ``|x|`` is largest, from the state reached
    by a monotonic virgin loading from zero to ``x[start]``: every element with
    ``phi < |x[start]|`` then sits at its slip limit, every other element is unstretched
    from zero. One pass through the period closes every element's loop.

    Notes
    -----
    The slider position of an element is either 0, or ``x[s] -+ phi`` with ``s`` the sample
    of its last slip (``start`` for the virgin loading). While it sticks the force is
    ``k (x_t - x_s +- phi)``, so ``d f_t / d x_t = k`` and ``d f_t / d x_s = -k``; while it
    slips the force is ``+-k phi`` and does not depend on ``x``.
    """
    n = x.size
    xm = x[start]
    sgn = 1.0 if xm >= 0.0 else -1.0
    for e in range(k.size):
        ke = k[e]
        ph = phi[e]
        if abs(xm) > ph:
            ze = xm - sgn * ph
            src = start
        else:
            ze = 0.0
            src = -1
        for j in range(n):
            t = start + j
            if t >= n:
                t -= n
            xt = x[t]
            if xt - ze > ph:
                ze = xt - ph
                src = t
            elif xt - ze < -ph:
                ze = xt + ph
                src = t
            f[t] += ke * (xt - ze)
            if src != t:
                jac[t, t] += ke
                if src >= 0:
                    jac[t, src] -= ke


@njit(cache=True, fastmath=False, nogil=True)
def periodic_projected_kernel(x: np.ndarray, k: np.ndarray, phi: np.ndarray, start: int,
                              basis: np.ndarray, f: np.ndarray, jb: np.ndarray) -> None:
    """Closed periodic force ``f`` (N) and ``jb = J @ basis`` (N/mm per basis column), both
    added into, without forming the (N, N) Jacobian J of :func:`periodic_kernel`.

    Notes
    -----
    Same return mapping and start as :func:`periodic_kernel`, samples outermost: row t of
    J is ``k_t`` (the stiffness of the elements sticking at t) on the diagonal and
    ``-k_e`` at the last slip sample ``s_e`` of every sticking element, so
    ``jb[t] = k_t basis[t] - sum_s w_ts basis[s]`` with the weights gathered per row over
    the distinct samples s. Cost O(N (n_elements + distinct s x columns)).
    """
    n = x.size
    m = k.size
    cols = basis.shape[1]
    xm = x[start]
    sgn = 1.0 if xm >= 0.0 else -1.0
    z = np.empty(m)
    src = np.empty(m, dtype=np.int64)
    for e in range(m):
        if abs(xm) > phi[e]:
            z[e] = xm - sgn * phi[e]
            src[e] = start
        else:
            z[e] = 0.0
            src[e] = -1
    weight = np.zeros(n)
    touched = np.empty(n, dtype=np.int64)
    for j in range(n):
        t = start + j
        if t >= n:
            t -= n
        xt = x[t]
        diag = 0.0
        force = 0.0
        count = 0
        for e in range(m):
            ze = z[e]
            ph = phi[e]
            if xt - ze > ph:
                ze = xt - ph
                src[e] = t
                z[e] = ze
            elif xt - ze < -ph:
                ze = xt + ph
                src[e] = t
                z[e] = ze
            ke = k[e]
            force += ke * (xt - ze)
            s = src[e]
            if s != t:
                diag += ke
                if s >= 0 and ke != 0.0:
                    if weight[s] == 0.0:
                        touched[count] = s
                        count += 1
                    weight[s] += ke
        f[t] += force
        for c in range(cols):
            jb[t, c] += diag * basis[t, c]
        for i in range(count):
            s = touched[i]
            w = weight[s]
            for c in range(cols):
                jb[t, c] -= w * basis[s, c]
            weight[s] = 0.0
