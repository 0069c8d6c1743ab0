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

import numpy as np
from numba import njit

__all__ = ["history_kernel", "periodic_harmonics_kernel", "periodic_kernel"]


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


#: Relative gap (of |x_s| + phi) below which a sample ties with a group's last slip sample:
#: the return mapping's test is then decided by round-off element by element, and taken so.
TIE = 16.0 * np.finfo(np.float64).eps


@njit(cache=True, fastmath=False, nogil=True)
def _slider(xs: float, sig: float, ph: float) -> float:
    """Slider position of an element that last slipped at ``xs`` in direction ``sig``
    (``sig`` 0: never, the virgin state at 0)."""
    return xs - sig * ph if sig != 0.0 else 0.0


@njit(cache=True, fastmath=False, nogil=True)
def _slips(xt: float, xs: float, sig: float, ph: float) -> bool:
    """The return mapping's test of :func:`history_kernel` at ``xt`` for such an element."""
    ze = _slider(xs, sig, ph)
    return xt - ze > ph or xt - ze < -ph


@njit(cache=True, fastmath=False, nogil=True)
def _run(ends: np.ndarray, srcs: np.ndarray, sigs: np.ndarray, count: int, end: int,
         src: int, sig: float) -> int:
    """Append the group ending at ``end`` (merged into the previous one if alike)."""
    if count > 0 and srcs[count - 1] == src and sigs[count - 1] == sig:
        ends[count - 1] = end
        return count
    ends[count], srcs[count], sigs[count] = end, src, sig
    return count + 1


@njit(cache=True, fastmath=False, nogil=True)
def _step(x: np.ndarray, t: int, phi: np.ndarray, end: np.ndarray, src: np.ndarray,
          sig: np.ndarray, depth: int, ends: np.ndarray, srcs: np.ndarray,
          sigs: np.ndarray) -> int:
    """The return mapping of every element at sample t on the stack of groups (see
    :func:`periodic_kernel`); returns the new depth. ``ends``, ``srcs``, ``sigs``: room for
    the new top groups."""
    xt = x[t]
    count = 0
    lo = 0
    while depth > 0:
        g = depth - 1
        hi, s, sg = end[g], src[g], sig[g]
        xs = x[s] if s >= 0 else 0.0
        depth -= 1
        if sg != 0.0 and abs(xt - xs) <= TIE * (abs(xs) + phi[hi - 1]):
            for e in range(lo, hi):  # a tie: round-off decides, element by element
                if _slips(xt, xs, sg, phi[e]):
                    way = 1.0 if xt > _slider(xs, sg, phi[e]) else -1.0
                    count = _run(ends, srcs, sigs, count, e + 1, t, way)
                else:
                    count = _run(ends, srcs, sigs, count, e + 1, s, sg)
            lo = hi
            if _slips(xt, xs, sg, phi[hi - 1]):
                continue
            break
        if _slips(xt, xs, sg, phi[hi - 1]):
            split = hi
        else:
            a, b = lo, hi - 1  # phi[b] sticks: the first element that sticks
            while a < b:
                mid = (a + b) // 2
                if _slips(xt, xs, sg, phi[mid]):
                    a = mid + 1
                else:
                    b = mid
            split = a
        if split > lo:
            way = 1.0 if xt > _slider(xs, sg, phi[lo]) else -1.0
            count = _run(ends, srcs, sigs, count, split, t, way)
        if split < hi:
            count = _run(ends, srcs, sigs, count, hi, s, sg)
            break
        lo = hi
    for i in range(count - 1, -1, -1):
        end[depth], src[depth], sig[depth] = ends[i], srcs[i], sigs[i]
        depth += 1
    return depth


@njit(cache=True, fastmath=False, nogil=True)
def periodic_kernel(x: np.ndarray, phi: np.ndarray, ck: np.ndarray, ckp: np.ndarray,
                    start: int, basis: np.ndarray, f: np.ndarray, jb: np.ndarray) -> None:
    """Closed periodic force ``f`` (N) and ``jb = J @ basis`` (N/mm per basis column), J the
    (N, N) Jacobian ``d f_t / d x_s``; both added into. ``phi`` (mm) ascending, ``ck`` and
    ``ckp`` the running sums of k and k phi over it (length n + 1, from 0).

    The history starts at sample ``start``, where ``|x|`` is largest, from the state reached
    by a monotonic virgin loading from zero to ``x[start]``: every element with
    ``phi < |x[start]|`` then sits at its slip limit, every other element is unstretched
    from zero. One pass through the period closes every element's loop.

    Notes
    -----
    The elements' stretch y(phi) is 1-Lipschitz in phi with ``|y| <= phi`` (true of the
    start state and kept by the return mapping ``y <- clip(y + dx, -phi, phi)``), so the
    elements that slip at a step are those of smallest phi, all in the direction of the step.
    The elements therefore form a stack of groups of consecutive phi, each with the sample
    ``s`` and direction ``sig`` of its last slip (slider at ``x_s - sig phi``) or virgin
    (slider at 0), the most recent on top; a step pops the groups that slip whole and splits
    the next by bisection (:func:`_step`; where x_t ties with x_s to round-off the test is
    made element by element, as :func:`history_kernel` makes it). A group's force is
    ``K (x_t - x_s) + sig KPhi`` (K, KPhi its sums of k and k phi). While it sticks its row
    of J has ``K`` on the diagonal and ``-K`` at column s; while it slips (s = t) it adds
    nothing. This is the element-by-element return mapping of :func:`history_kernel` (same
    tests, same slider positions) at a cost O(N (groups x columns + log n)), not O(N n).
    """
    n = x.size
    m = phi.size
    cols = basis.shape[1]
    # groups from the bottom (largest phi, index 0) up: elements [end[g + 1], end[g])
    end = np.empty(m + 1, dtype=np.int64)
    src = np.empty(m + 1, dtype=np.int64)
    sig = np.empty(m + 1)
    ends = np.empty(m + 1, dtype=np.int64)
    srcs = np.empty(m + 1, dtype=np.int64)
    sigs = np.empty(m + 1)
    xm = x[start]
    depth = 0
    cut = np.searchsorted(phi, abs(xm))  # elements with phi < |x[start]| slip to it
    if cut < m:
        end[0], src[0], sig[0] = m, -1, 0.0
        depth = 1
    if cut > 0:
        end[depth], src[depth], sig[depth] = cut, start, 1.0 if xm >= 0.0 else -1.0
        depth += 1
    for j in range(n):
        t = start + j
        if t >= n:
            t -= n
        xt = x[t]
        if j > 0:
            depth = _step(x, t, phi, end, src, sig, depth, ends, srcs, sigs)
        force = 0.0
        diag = 0.0
        lo = 0
        for g in range(depth - 1, -1, -1):
            kg = ck[end[g]] - ck[lo]
            s = src[g]
            if s < 0:
                force += kg * xt
            else:
                force += kg * (xt - x[s]) + sig[g] * (ckp[end[g]] - ckp[lo])
            if s != t:
                diag += kg
                if s >= 0 and kg != 0.0:
                    for c in range(cols):
                        jb[t, c] -= kg * basis[s, c]
            lo = end[g]
        f[t] += force
        for c in range(cols):
            jb[t, c] += diag * basis[t, c]


@njit(cache=True, fastmath=False, nogil=True)
def periodic_harmonics_kernel(u: np.ndarray, synth: np.ndarray, analysis: np.ndarray,
                              phi: np.ndarray, ck: np.ndarray, ckp: np.ndarray,
                              force: np.ndarray, dforce: np.ndarray) -> None:
    """The alternating frequency-time step of harmonic balance in one call: the closed
    periodic force's Fourier coefficients ``force`` (N, (m,)) and their derivative
    ``dforce`` (N/mm, (m, m)) in the displacement's coefficients ``u`` (mm, (m,)), both
    added into; ``synth`` (N, m) maps coefficients to the N samples, ``analysis`` (m, N)
    samples to coefficients; ``phi``, ``ck``, ``ckp`` as :func:`periodic_kernel`."""
    x = synth @ u
    if not np.all(np.isfinite(x)):
        force[:] = np.nan
        return
    f = np.zeros(x.size)
    jb = np.zeros(synth.shape)
    periodic_kernel(x, phi, ck, ckp, int(np.argmax(np.abs(x))), synth, f, jb)
    force += analysis @ f
    dforce += analysis @ jb
