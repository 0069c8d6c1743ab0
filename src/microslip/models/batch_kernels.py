"""Compiled batch kernels of the tip and centre models (numba): many cases at once.

Each kernel runs the incremental recurrence of one model for a whole batch of parameter
sets and accumulates the Masing-loop energies on the fly, so it keeps a handful of numbers
per case instead of the n + 1 samples of a backbone (memory O(batch)).

The physics of one increment is not written here: each kernel inlines its model's scalar
step (:func:`microslip.models.tip.tip_step`, :func:`microslip.models.centre.centre_step`)
per lane, the same function :func:`microslip.first_loading` runs, and the energies come
from :func:`microslip.models.masing.masing_energies`, the same function :func:`microslip.damping`
uses. The kernels' ``py_func`` is the plain-Python loop of ``benchmarks/bench_batch.py``.

Layout: the cases are split into chunks of ``CHUNK`` (``prange`` spreads the chunks over the
threads). Inside a chunk the loop over increments is the outer loop and the loop over the
chunk's cases (the lanes) the inner one, so that consecutive operations belong to
independent cases: the sequential dependence of increment i on increment i - 1 never
stalls the pipeline, and the lane loop compiles to SIMD instructions. The state of a chunk
(a few arrays of ``CHUNK`` doubles) stays in the level-1 cache.

Shared parts: every kernel takes its chunk's common buffers from :func:`_chunk` and ends
with :func:`_write_out`, every lane keeps Q, d and the smallest factor by
:func:`_accumulate`; the tip and centre kernels also share the increment loop,
:func:`_load`, which takes the model's per-increment lane loop (``_tip_advance`` or
``_centre_advance``) as a function argument that numba inlines, so that each adds only
its per-lane constants and state. The two layer kernels keep their increment loops
written out (with :func:`_snapshot`): through :func:`_load` they ran 4 % (tip) and 10 %
(centre) slower, measured against the written-out loops in one process, alternately.

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
from numba import njit, prange

# the models' steps and the Masing sums, compiled (:mod:`.compiled`), inlined per lane
from .compiled import (
    centre_constants,
    centre_flags,
    centre_layer_setup,
    centre_layer_step,
    centre_step,
    centre_stored_energy,
    masing_energies,
    tip_constants,
    tip_flags,
    tip_layer_setup,
    tip_layer_step,
    tip_step,
    tip_stored_energy,
)

__all__ = ["BATCH_KERNELS", "CHUNK", "centre_kernel", "centre_layer_kernel", "tip_kernel",
           "tip_layer_kernel"]

#: Cases per chunk (one thread works on one chunk at a time; the state fits in L1).
CHUNK = 256


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
        w, u, eta = masing_energies(f0[k], d[k], q[k], q_k0[k], d_km1[k], d_k0[k], fr_km1,
                                    fr_k0, stored[k], kind)
        out_d0[j] = d[k]
        out_w[j] = w
        out_u[j] = u
        out_eta[j] = eta
        out_section[j] = gmin[k]


@njit(cache=True, fastmath=False, inline="always")
def _chunk(c, amplitude):
    """Chunk ``c`` of the batch: its first case ``lo``, its size ``m`` and the buffers a
    kernel keeps per lane: f0 (empty, for the amplitudes), d, Q, the smallest section factor
    (1), and the state at increments k0 - 1 and k0 (d_(k0-1), d_k0, Q_k0)."""
    lo = c * CHUNK
    m = min(CHUNK, amplitude.shape[0] - lo)
    return (lo, m, np.empty(m), np.zeros(m), np.zeros(m), np.ones(m), np.zeros(m), np.zeros(m),
            np.zeros(m))


@njit(cache=True, fastmath=False, inline="always")
def _load(n, k0, m, f0, d, q, gmin, d_km1, d_k0, q_k0, advance, lanes, fixed):
    """The first loading of a chunk, increments outer: ``advance(m, fr, fr_prev, f0, d, q,
    gmin, lanes, fixed)`` runs the model's step on every lane (the inner loop) at the force
    fraction ``fr`` (previous ``fr_prev``) and keeps d, Q and the smallest factor by
    :func:`_accumulate`; the model's own per-lane arrays come in the tuple ``lanes``, its
    scalars (the flags) in ``fixed``.

    An ``advance`` takes its arrays out of ``lanes`` once per increment, not per lane (a
    tuple item is a new reference: taken per lane, its reference counting cost 25 % on the
    tip layer kernel when it ran through here); arrays and scalars travel in separate
    tuples (numba's array analysis fails on a tuple that mixes them); and an array the
    step writes is taken by index, ``lanes[i]``, never by unpacking: numba's alias
    analysis does not follow tuple unpacking, and the parallel pass would drop its stores
    as dead code (wrong numbers, no error).
    """
    fr_prev = 0.0
    for i in range(1, n + 1):
        fr = i / n
        advance(m, fr, fr_prev, f0, d, q, gmin, lanes, fixed)
        _snapshot(i, k0, m, d, q, d_km1, d_k0, q_k0)
        fr_prev = fr


@njit(cache=True, fastmath=False, inline="always")
def _accumulate(k, f, fp, dn, g, d, q, gmin):
    """Lane k moved to displacement ``dn`` under force f (previous fp) with section factor
    g: Q += (F_(i-1) + F_i)(d_i - d_(i-1)), d and the smallest factor."""
    gmin[k] = min(gmin[k], g)
    q[k] += (fp + f) * (dn - d[k])
    d[k] = dn


@njit(cache=True, fastmath=False, inline="always")
def _tip_advance(m, fr, fr_prev, f0, d, q, gmin, lanes, flags):
    """Every lane of :func:`tip_kernel` by one increment (:func:`~.tip.tip_step`)."""
    ln, rfn, cnu, he, _ = lanes  # read only
    ra = lanes[4]  # written: by index (see _load)
    for k in range(m):
        f = f0[k] * fr
        fp = f0[k] * fr_prev
        dn, ra_new, _, g = tip_step(f, fp, (d[k], ra[k]), (ln[k], rfn[k], cnu[k], he[k]),
                                    flags)
        ra[k] = ra_new
        _accumulate(k, f, fp, dn, g, d, q, gmin)


@njit(parallel=True, cache=True, fastmath=False, nogil=True)
def tip_kernel(amplitude, length, width, thickness, modulus, poisson_ratio, friction,
               normal_force, n, poisson_code, length_update, reading, kind,
               out_d0, out_w, out_u, out_eta, out_section):
    """Tip model (Eqs 2-10, :func:`~microslip.models.tip.tip_step`) and Masing energies for
    every case; results into ``out_*``.

    Parameters are 1-D float64 arrays of one length; ``n`` increments; ``poisson_code``,
    ``reading`` and ``kind`` from :data:`microslip.options.POISSON_CODES`,
    :data:`microslip.options.READING_CODES` and :data:`microslip.energy.STRAIN_ENERGY_CODES`;
    ``length_update`` 0 or 1. ``out_section`` receives the smallest cross-section factor
    g = w_i / w_(i-1) of any increment (<= 0 means the model broke down, as in
    :func:`microslip.first_loading`).
    """
    flags = tip_flags(poisson_code, length_update, reading)
    k0 = (n + 1) // 2
    for c in prange((amplitude.shape[0] + CHUNK - 1) // CHUNK):
        lo, m, f0, d, q, gmin, d_km1, d_k0, q_k0 = _chunk(c, amplitude)
        ln = np.empty(m)
        rfn = np.empty(m)
        cnu = np.empty(m)
        he = np.empty(m)
        ra = np.empty(m)
        for k in range(m):
            j = lo + k
            f0[k] = amplitude[j]
            ln[k], rfn[k], cnu[k], he[k], d[k], ra[k] = tip_constants(
                length[j], width[j], thickness[j], modulus[j], poisson_ratio[j],
                friction[j], normal_force[j], flags)
        _load(n, k0, m, f0, d, q, gmin, d_km1, d_k0, q_k0, _tip_advance,
              (ln, rfn, cnu, he, ra), flags)
        stored = np.empty(m)
        for k in range(m):
            stored[k] = tip_stored_energy(f0[k], d[k])
        _write_out(lo, m, n, k0, kind, f0, d, q, q_k0, d_km1, d_k0, stored, gmin,
                   out_d0, out_w, out_u, out_eta, out_section)


@njit(cache=True, fastmath=False, inline="always")
def _centre_advance(m, fr, fr_prev, f0, d, q, gmin, lanes, flags):
    """Every lane of :func:`centre_kernel` by one increment (:func:`~.centre.centre_step`)."""
    lh, rfn, nu, he, a0, _, _, _, _ = lanes  # read only
    dt = lanes[5]  # written: by index (see _load)
    dc = lanes[6]
    et = lanes[7]
    ec = lanes[8]
    for k in range(m):
        f = f0[k] * fr
        fp = f0[k] * fr_prev
        dt[k], dc[k], et[k], ec[k], dn, _, _, gt, ht, _ = centre_step(
            f, fp, (dt[k], dc[k], et[k], ec[k]), (lh[k], rfn[k], nu[k], he[k], a0[k]), flags)
        _accumulate(k, f, fp, dn, min(gt, ht), d, q, gmin)


@njit(parallel=True, cache=True, fastmath=False, nogil=True)
def centre_kernel(amplitude, length, width, thickness, modulus, poisson_ratio, friction,
                  normal_force, n, poisson_code, length_update, reading, kind,
                  out_d0, out_w, out_u, out_eta, out_section):
    """Centre model (Eqs 11-18, :func:`~microslip.models.centre.centre_step`) and Masing
    energies for every case; arguments as for :func:`tip_kernel` (``reading`` 0 physical,
    1 paper). ``out_section`` gets the smallest factor w_t / w or t_t / t."""
    flags = centre_flags(poisson_code, length_update, reading)
    k0 = (n + 1) // 2
    for c in prange((amplitude.shape[0] + CHUNK - 1) // CHUNK):
        lo, m, f0, d, q, gmin, d_km1, d_k0, q_k0 = _chunk(c, amplitude)
        lh = np.empty(m)
        rfn = np.empty(m)
        nu = np.empty(m)
        he = np.empty(m)
        a0 = np.empty(m)
        dt = np.zeros(m)
        dc = np.zeros(m)
        et = np.zeros(m)
        ec = np.zeros(m)
        for k in range(m):
            j = lo + k
            f0[k] = amplitude[j]
            lh[k], rfn[k], nu[k], he[k], a0[k], dt[k], dc[k], et[k], ec[k] = centre_constants(
                length[j], width[j], thickness[j], modulus[j], poisson_ratio[j],
                friction[j], normal_force[j], flags)
        _load(n, k0, m, f0, d, q, gmin, d_km1, d_k0, q_k0, _centre_advance,
              (lh, rfn, nu, he, a0, dt, dc, et, ec), flags)
        stored = np.empty(m)
        for k in range(m):
            stored[k] = centre_stored_energy(f0[k], dt[k], dc[k])
        _write_out(lo, m, n, k0, kind, f0, d, q, q_k0, d_km1, d_k0, stored, gmin,
                   out_d0, out_w, out_u, out_eta, out_section)


@njit(parallel=True, cache=True, fastmath=False, nogil=True)
def tip_layer_kernel(amplitude, length, width, thickness, modulus, poisson_ratio, friction,
                     normal_force, n, poisson_code, length_update, reading, kind, stick_slope,
                     shear_lag, code, data, symmetric, out_d0, out_w, out_u, out_eta,
                     out_section):
    """Tip model on a contact (:func:`~microslip.models.layered.tip_layer_step`) and Masing
    energies for every case; arguments as for :func:`tip_kernel`, then the contact's
    :attr:`~microslip.models.contact.Contact.kernel_args` (one contact for the batch). The
    stored energy is NaN (strain energy ``stored`` is refused on a contact)."""
    k0 = (n + 1) // 2
    for c in prange((amplitude.shape[0] + CHUNK - 1) // CHUNK):
        lo, m, f0, d, q, gmin, d_km1, d_k0, q_k0 = _chunk(c, amplitude)
        st = np.empty((m, 6))
        cs = np.empty((m, 8))
        doms = np.empty((m, 14))
        stored = np.full(m, np.nan)
        flags = plain = (0.0, 0.0, 0.0)
        for k in range(m):
            j = lo + k
            f0[k] = amplitude[j]
            flags, plain, cc, cp, dom, state = tip_layer_setup(
                length[j], width[j], thickness[j], modulus[j], poisson_ratio[j], friction[j],
                normal_force[j], poisson_code, length_update, reading, stick_slope, shear_lag,
                code, data)
            for i in range(4):
                cs[k, i] = cc[i]
                cs[k, 4 + i] = cp[i]
            for i in range(14):
                doms[k, i] = dom[i]
            for i in range(6):
                st[k, i] = state[i]
        fr_prev = 0.0
        for i in range(1, n + 1):
            fr = i / n
            for k in range(m):
                f = f0[k] * fr
                fp = f0[k] * fr_prev
                dm = doms[k]
                dn, ra, dpn, rap, a, da, dd, _, g = tip_layer_step(
                    f, fp, (st[k, 0], st[k, 1], st[k, 2], st[k, 3], st[k, 4], st[k, 5]),
                    (cs[k, 0], cs[k, 1], cs[k, 2], cs[k, 3]),
                    (cs[k, 4], cs[k, 5], cs[k, 6], cs[k, 7]), flags, plain,
                    (dm[0], dm[1], dm[2], dm[3], dm[4], dm[5], dm[6], dm[7], dm[8], dm[9],
                     dm[10], dm[11], dm[12], dm[13]), code, data)
                st[k, 0], st[k, 1], st[k, 2], st[k, 3], st[k, 4], st[k, 5] = (dn, ra, dpn, rap,
                                                                              a, da)
                _accumulate(k, f, fp, dd, g, d, q, gmin)
            _snapshot(i, k0, m, d, q, d_km1, d_k0, q_k0)
            fr_prev = fr
        _write_out(lo, m, n, k0, kind, f0, d, q, q_k0, d_km1, d_k0, stored, gmin,
                   out_d0, out_w, out_u, out_eta, out_section)


@njit(parallel=True, cache=True, fastmath=False, nogil=True)
def centre_layer_kernel(amplitude, length, width, thickness, modulus, poisson_ratio,
                        friction, normal_force, n, poisson_code, length_update, reading, kind,
                        stick_slope, shear_lag, code, data, symmetric, out_d0, out_w, out_u,
                        out_eta, out_section):
    """Centre model (physical reading) on a contact
    (:func:`~microslip.models.layered.centre_layer_step`); arguments as for
    :func:`tip_layer_kernel`."""
    k0 = (n + 1) // 2
    for c in prange((amplitude.shape[0] + CHUNK - 1) // CHUNK):
        lo, m, f0, d, q, gmin, d_km1, d_k0, q_k0 = _chunk(c, amplitude)
        st = np.empty((m, 14))
        cs = np.empty((m, 10))
        doms = np.empty((m, 28))
        stored = np.full(m, np.nan)
        flags = plain = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0)
        for k in range(m):
            j = lo + k
            f0[k] = amplitude[j]
            flags, plain, cc, cp, dt, dc, state = centre_layer_setup(
                length[j], width[j], thickness[j], modulus[j], poisson_ratio[j], friction[j],
                normal_force[j], poisson_code, length_update, reading, stick_slope, shear_lag,
                code, data)
            for i in range(5):
                cs[k, i] = cc[i]
                cs[k, 5 + i] = cp[i]
            for i in range(14):
                doms[k, i] = dt[i]
                doms[k, 14 + i] = dc[i]
            for i in range(14):
                st[k, i] = state[i]
        fr_prev = 0.0
        for i in range(1, n + 1):
            fr = i / n
            for k in range(m):
                f = f0[k] * fr
                fp = f0[k] * fr_prev
                s = st[k]
                dm = doms[k]
                r = centre_layer_step(
                    f, fp, (s[0], s[1], s[2], s[3], s[4], s[5], s[6], s[7], s[8], s[9], s[10],
                            s[11], s[12], s[13]),
                    (cs[k, 0], cs[k, 1], cs[k, 2], cs[k, 3], cs[k, 4]),
                    (cs[k, 5], cs[k, 6], cs[k, 7], cs[k, 8], cs[k, 9]), flags, plain,
                    (dm[0], dm[1], dm[2], dm[3], dm[4], dm[5], dm[6], dm[7], dm[8], dm[9],
                     dm[10], dm[11], dm[12], dm[13]),
                    (dm[14], dm[15], dm[16], dm[17], dm[18], dm[19], dm[20], dm[21], dm[22],
                     dm[23], dm[24], dm[25], dm[26], dm[27]), code, data, symmetric, 0)
                for t in range(14):
                    s[t] = r[t]
                _accumulate(k, f, fp, r[14], min(r[17], r[18]), d, q, gmin)
            _snapshot(i, k0, m, d, q, d_km1, d_k0, q_k0)
            fr_prev = fr
        _write_out(lo, m, n, k0, kind, f0, d, q, q_k0, d_km1, d_k0, stored, gmin,
                   out_d0, out_w, out_u, out_eta, out_section)


#: Model name -> its batch kernels (rigid foundation, on a contact).
BATCH_KERNELS = {"tip": (tip_kernel, tip_layer_kernel),
                 "centre": (centre_kernel, centre_layer_kernel)}
