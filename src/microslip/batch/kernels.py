"""Compiled batch kernels of the tip and centre models (numba).

Each kernel runs the incremental recurrence of one model for a whole batch of parameter
sets and accumulates the Masing-loop energies on the fly, so it keeps a handful of numbers
per case instead of the n + 1 samples of a backbone (memory O(batch)).

The same source is the plain-Python loop used by ``benchmarks/bench_batch.py`` (each
function's ``py_func`` when numba is present, the function itself when it is not).

Layout: the cases are split into chunks of ``CHUNK`` (``prange`` spreads the chunks over the
threads). Inside a chunk the loop over increments is the outer loop and the loop over the
chunk's cases (the lanes) the inner one, so that consecutive operations belong to
independent cases: the sequential dependence of increment i on increment i - 1 never
stalls the pipeline, and the lane loop compiles to SIMD instructions. The state of a chunk
(a few arrays of ``CHUNK`` doubles) stays in the level-1 cache.

Energies (paper Eqs 21-23, Masing loop at the backbone samples, see
:func:`microslip.hysteresis.masing_loop`), with Q = sum_k (F_(k-1) + F_k)(d_k - d_(k-1))
= 2 trapz(F, d) accumulated along the first loading:

- W_d = 4 (Q - F0 d0), the trapezoidal closed integral around the 2n + 1 loop points
  (= 4 F0 d0 - 8 trapz(d, F) by summation by parts);
- U secant = F0 d0 / 2, backbone = Q / 2, stored = F0 d0 / 3 (tip) or
  F0 (d_t + d_c) / 6 (centre);
- U branch: the ascending branch F = -F0 + 2 F_k, d = -d0 + 2 d_k from its zero crossing
  (between k0 - 1 and k0 = ceil(n/2), linear interpolation) to the peak:
  0.5 F(k0) (d(k0) - d_zero) + 2 (Q_n - Q_k0) - 2 F0 (d0 - d_k0).
"""

from __future__ import annotations

import numpy as np

from .sums import finish

try:
    from numba import njit, prange
except ImportError:  # pragma: no cover - exercised only without numba
    HAVE_NUMBA = False
    prange = range  # type: ignore[misc]

    def njit(*args, **kwargs):  # type: ignore[no-redef]
        """Stand-in decorator: the kernels stay plain Python functions."""
        def wrap(f):
            return f
        return wrap
else:
    HAVE_NUMBA = True

__all__ = ["CHUNK", "HAVE_NUMBA", "KIND_CODES", "POISSON_CODES", "centre_kernel", "tip_kernel"]

#: Cases per chunk (one thread works on one chunk at a time; the state fits in L1).
CHUNK = 256
#: Integer codes of the Poisson modes passed to the kernels.
POISSON_CODES = {"consistent": 0, "paper-literal": 1, "off": 2}
#: Integer codes of the strain-energy definitions passed to the kernels.
KIND_CODES = {"secant": 0, "backbone": 1, "branch": 2, "stored": 3}

#: W_d, U and eta from the accumulated sums: the fallback's function, compiled.
_finish = njit(cache=True, fastmath=False, inline="always")(finish)



@njit(cache=True, fastmath=False, inline="always")
def _snapshot(i, k0, m, d, q, d_km1, d_k0, q_k0):
    """Keep the state at increments k0 - 1 and k0 (the zero crossing of Eq. 22's branch)."""
    if i == k0 - 1:
        for k in range(m):
            d_km1[k] = d[k]
    elif i == k0:
        for k in range(m):
            d_k0[k] = d[k]
            q_k0[k] = q[k]


@njit(cache=True, fastmath=False, inline="always")
def _write_out(lo, m, n, k0, kind, f0, d, q, q_k0, d_km1, d_k0, stored, gmin,
               out_d0, out_w, out_u, out_eta, out_section):
    """W_d, U and eta of the chunk's cases into the output arrays from position ``lo``."""
    fr_km1 = (k0 - 1) / n
    fr_k0 = k0 / n
    for k in range(m):
        j = lo + k
        w, u, eta = _finish(f0[k], d[k], q[k], q_k0[k], d_km1[k], d_k0[k], fr_km1, fr_k0,
                            stored[k], kind)
        out_d0[j] = d[k]
        out_w[j] = w
        out_u[j] = u
        out_eta[j] = eta
        out_section[j] = gmin[k]


@njit(parallel=True, cache=True, fastmath=False, nogil=True)
def tip_kernel(amplitude, length, width, thickness, modulus, poisson_ratio, friction,
               normal_force, n, poisson_code, length_update, kind,
               out_d0, out_w, out_u, out_eta, out_section):
    """Tip model (Eqs 2-10) and Masing energies for every case; results into ``out_*``.

    Parameters are 1-D float64 arrays of one length; ``n`` increments; ``poisson_code`` and
    ``kind`` from :data:`POISSON_CODES` and :data:`KIND_CODES`; ``length_update`` 0 or 1.
    ``out_section`` receives the smallest cross-section factor w_i / w over the loading
    (<= 0 means the model broke down, as in :func:`microslip.first_loading`).

    Per increment and case (A = w t, r = 1/A):
    L_i = L + delta_(i-1) (or L), u_i = F_i L_i / (mu F_N), s = nu f / (E A_(i-1)) with
    f = F_i - F_(i-1) (consistent) or F_i (paper-literal) or nu = 0 (off),
    w_i / w_(i-1) = t_i / t_(i-1) = 1 - s, delta_i = F_i u_i / (2 E A_i).
    """
    ncase = amplitude.shape[0]
    nchunk = (ncase + CHUNK - 1) // CHUNK
    lu = 1.0 if length_update else 0.0
    keep_prev = 1.0 if poisson_code == 0 else 0.0
    nu_on = 0.0 if poisson_code == 2 else 1.0
    k0 = (n + 1) // 2
    for c in prange(nchunk):
        lo = c * CHUNK
        m = min(CHUNK, ncase - lo)
        f0 = np.empty(m)
        ln = np.empty(m)
        rfn = np.empty(m)
        cnu = np.empty(m)
        he = np.empty(m)
        d = np.zeros(m)
        ra = np.empty(m)
        q = np.zeros(m)
        gmin = np.ones(m)
        q_k0 = np.zeros(m)
        d_km1 = np.zeros(m)
        stored = np.empty(m)
        d_k0 = np.zeros(m)
        for k in range(m):
            j = lo + k
            f0[k] = amplitude[j]
            ln[k] = length[j]
            rfn[k] = 1.0 / (friction[j] * normal_force[j])
            cnu[k] = nu_on * poisson_ratio[j] / modulus[j]
            he[k] = 0.5 / modulus[j]
            ra[k] = 1.0 / (width[j] * thickness[j])
        fr_prev = 0.0
        for i in range(1, n + 1):
            fr = i / n
            for k in range(m):
                f = f0[k] * fr
                fp = f0[k] * fr_prev
                u = f * (ln[k] + lu * d[k]) * rfn[k]
                g = 1.0 - cnu[k] * (f - keep_prev * fp) * ra[k]
                gmin[k] = min(gmin[k], g)
                ra_new = ra[k] / (g * g)
                dn = f * u * he[k] * ra_new
                q[k] += (fp + f) * (dn - d[k])
                d[k] = dn
                ra[k] = ra_new
            _snapshot(i, k0, m, d, q, d_km1, d_k0, q_k0)
            fr_prev = fr
        for k in range(m):
            stored[k] = f0[k] * d[k] / 3.0
        _write_out(lo, m, n, k0, kind, f0, d, q, q_k0, d_km1, d_k0, stored, gmin,
                   out_d0, out_w, out_u, out_eta, out_section)


@njit(parallel=True, cache=True, fastmath=False, nogil=True)
def centre_kernel(amplitude, length, width, thickness, modulus, poisson_ratio, friction,
                  normal_force, n, poisson_code, length_update, reading, kind,
                  out_d0, out_w, out_u, out_eta, out_section):
    """Centre model (Eqs 11-18) and Masing energies for every case; results into ``out_*``.

    ``reading`` 0 is the physical reading (F/2 per half, half lengths L/2 -/+ delta_d),
    1 the paper's (Eq. 11 as printed, full F per domain, lengths L + delta_d); the other
    arguments as for :func:`tip_kernel`.

    Per increment and domain d (s_d = +1 tension, -1 compression), with the previous mean
    strain e_d = delta_d / u_d = F_d / (2 E A_d) of increment i - 1:
    w_d = w (1 - s_d nu e_d), t_d = t (1 - s_d nu e_d) (paper-literal: t_t = t (1 + nu e_t)),
    delta_d = F_d u_d / (2 E A_d) and the loaded section moves
    delta = 2 delta_t delta_c / (delta_t + delta_c) = 2 F_d u_t u_c / (2 E (A_t u_c + A_c u_t))
    (Eq. 18: the two domains as parallel springs). One division per increment:
    r = 1 / (A_t A_c S) with S = u_t A_c + u_c A_t gives 1/A_t = A_c S r, 1/A_c = A_t S r and
    1/S = A_t A_c r.
    """
    ncase = amplitude.shape[0]
    nchunk = (ncase + CHUNK - 1) // CHUNK
    lu = 1.0 if length_update else 0.0
    nu_on = 0.0 if poisson_code == 2 else 1.0
    t_sign = 1.0 if poisson_code == 1 else -1.0  # Eq. 15 as printed: tension domain thickens
    if reading == 0:
        f_share, len_share, u_share, c_sign = 0.5, 0.5, 1.0, -1.0
    else:
        f_share, len_share, u_share, c_sign = 1.0, 1.0, 0.25, 1.0
    k0 = (n + 1) // 2
    for c in prange(nchunk):
        lo = c * CHUNK
        m = min(CHUNK, ncase - lo)
        f0 = np.empty(m)
        lh = np.empty(m)
        rfn = np.empty(m)
        nu = np.empty(m)
        he = np.empty(m)
        a0 = np.empty(m)
        dt = np.zeros(m)
        dc = np.zeros(m)
        et = np.zeros(m)
        ec = np.zeros(m)
        d = np.zeros(m)
        q = np.zeros(m)
        gmin = np.ones(m)
        q_k0 = np.zeros(m)
        d_km1 = np.zeros(m)
        stored = np.empty(m)
        d_k0 = np.zeros(m)
        for k in range(m):
            j = lo + k
            f0[k] = amplitude[j]
            lh[k] = len_share * length[j]
            rfn[k] = u_share / (friction[j] * normal_force[j])
            nu[k] = nu_on * poisson_ratio[j]
            he[k] = 0.5 / modulus[j]
            a0[k] = width[j] * thickness[j]
        fr_prev = 0.0
        for i in range(1, n + 1):
            fr = i / n
            for k in range(m):
                f = f0[k] * fr
                fp = f0[k] * fr_prev
                fd = f_share * f
                ut = f * (lh[k] + lu * dt[k]) * rfn[k]
                uc = f * (lh[k] + c_sign * lu * dc[k]) * rfn[k]
                gt = 1.0 - nu[k] * et[k]
                ht = 1.0 + t_sign * nu[k] * et[k]
                gc = 1.0 + nu[k] * ec[k]
                gmin[k] = min(gmin[k], min(gt, ht))
                at = a0[k] * gt * ht
                ac = a0[k] * gc * gc
                s = ut * ac + uc * at
                r = 1.0 / (at * ac * s)
                x = fd * he[k]
                et[k] = x * ac * s * r
                ec[k] = x * at * s * r
                dt[k] = et[k] * ut
                dc[k] = ec[k] * uc
                dn = 2.0 * x * ut * uc * at * ac * r
                q[k] += (fp + f) * (dn - d[k])
                d[k] = dn
            _snapshot(i, k0, m, d, q, d_km1, d_k0, q_k0)
            fr_prev = fr
        for k in range(m):
            stored[k] = 0.5 * f0[k] * (dt[k] + dc[k]) / 3.0
        _write_out(lo, m, n, k0, kind, f0, d, q, q_k0, d_km1, d_k0, stored, gmin,
                   out_d0, out_w, out_u, out_eta, out_section)
