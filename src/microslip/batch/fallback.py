"""Pure-numpy batch kernels: the same arithmetic as :mod:`.kernels`, vectorised over cases.

Used when numba is not installed. The loop over increments runs in Python and every
operation acts on a block of cases at once, so the cost per case-increment is a few numpy
operations on a block that stays in cache. The formulas and their order are those of the
compiled kernels (IEEE arithmetic without fast-math on both sides), so the two agree to
the last bit on the same machine.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from .sums import finish

__all__ = ["BLOCK", "centre_numpy", "tip_numpy"]

#: Cases per block of the vectorised loop.
BLOCK = 8192

Arr = NDArray[np.float64]


def tip_numpy(amplitude: Arr, length: Arr, width: Arr, thickness: Arr, modulus: Arr,
              poisson_ratio: Arr, friction: Arr, normal_force: Arr, n: int, poisson_code: int,
              length_update: int, kind: int, out_d0: Arr, out_w: Arr, out_u: Arr,
              out_eta: Arr, out_section: Arr) -> None:
    """Same contract as :func:`microslip.batch.kernels.tip_kernel`."""
    lu = 1.0 if length_update else 0.0
    keep_prev = 1.0 if poisson_code == 0 else 0.0
    nu_on = 0.0 if poisson_code == 2 else 1.0
    k0 = (n + 1) // 2
    for lo in range(0, amplitude.shape[0], BLOCK):
        sl = slice(lo, lo + BLOCK)
        f0 = amplitude[sl]
        ln = length[sl]
        rfn = 1.0 / (friction[sl] * normal_force[sl])
        cnu = nu_on * poisson_ratio[sl] / modulus[sl]
        he = 0.5 / modulus[sl]
        ra = 1.0 / (width[sl] * thickness[sl])
        d = np.zeros_like(f0)
        q = np.zeros_like(f0)
        gmin = np.ones_like(f0)
        q_k0 = np.zeros_like(f0)
        d_km1 = np.zeros_like(f0)
        d_k0 = np.zeros_like(f0)
        fr_prev = 0.0
        for i in range(1, n + 1):
            fr = i / n
            f = f0 * fr
            fp = f0 * fr_prev
            u = f * (ln + lu * d) * rfn
            g = 1.0 - cnu * (f - keep_prev * fp) * ra
            np.minimum(gmin, g, out=gmin)
            ra = ra / (g * g)
            dn = f * u * he * ra
            q += (fp + f) * (dn - d)
            d = dn
            if i == k0 - 1:
                d_km1 = d
            elif i == k0:
                d_k0 = d
                q_k0 = q.copy()
            fr_prev = fr
        stored = f0 * d / 3.0
        w, u_e, eta = finish(f0, d, q, q_k0, d_km1, d_k0, (k0 - 1) / n, k0 / n, stored, kind)
        out_d0[sl], out_w[sl], out_u[sl], out_eta[sl], out_section[sl] = d, w, u_e, eta, gmin


def centre_numpy(amplitude: Arr, length: Arr, width: Arr, thickness: Arr, modulus: Arr,
                 poisson_ratio: Arr, friction: Arr, normal_force: Arr, n: int,
                 poisson_code: int, length_update: int, reading: int, kind: int,
                 out_d0: Arr, out_w: Arr, out_u: Arr, out_eta: Arr, out_section: Arr) -> None:
    """Same contract as :func:`microslip.batch.kernels.centre_kernel`."""
    lu = 1.0 if length_update else 0.0
    nu_on = 0.0 if poisson_code == 2 else 1.0
    t_sign = 1.0 if poisson_code == 1 else -1.0
    if reading == 0:
        f_share, len_share, u_share, c_sign = 0.5, 0.5, 1.0, -1.0
    else:
        f_share, len_share, u_share, c_sign = 1.0, 1.0, 0.25, 1.0
    k0 = (n + 1) // 2
    for lo in range(0, amplitude.shape[0], BLOCK):
        sl = slice(lo, lo + BLOCK)
        f0 = amplitude[sl]
        lh = len_share * length[sl]
        rfn = u_share / (friction[sl] * normal_force[sl])
        nu = nu_on * poisson_ratio[sl]
        he = 0.5 / modulus[sl]
        a0 = width[sl] * thickness[sl]
        z = np.zeros_like(f0)
        dt, dc, et, ec, d, q = z, z, z, z, z, z
        gmin = np.ones_like(f0)
        q_k0, d_km1, d_k0 = z, z, z
        fr_prev = 0.0
        for i in range(1, n + 1):
            fr = i / n
            f = f0 * fr
            fp = f0 * fr_prev
            fd = f_share * f
            ut = f * (lh + lu * dt) * rfn
            uc = f * (lh + c_sign * lu * dc) * rfn
            gt = 1.0 - nu * et
            ht = 1.0 + t_sign * nu * et
            gc = 1.0 + nu * ec
            gmin = np.minimum(gmin, np.minimum(gt, ht))
            at = a0 * gt * ht
            ac = a0 * gc * gc
            s = ut * ac + uc * at
            r = 1.0 / (at * ac * s)
            x = fd * he
            et = x * ac * s * r
            ec = x * at * s * r
            dt = et * ut
            dc = ec * uc
            dn = 2.0 * x * ut * uc * at * ac * r
            q = q + (fp + f) * (dn - d)
            d = dn
            if i == k0 - 1:
                d_km1 = d
            elif i == k0:
                d_k0 = d
                q_k0 = q
            fr_prev = fr
        stored = 0.5 * f0 * (dt + dc) / 3.0
        w, u_e, eta = finish(f0, d, q, q_k0, d_km1, d_k0, (k0 - 1) / n, k0 / n, stored, kind)
        out_d0[sl], out_w[sl], out_u[sl], out_eta[sl], out_section[sl] = d, w, u_e, eta, gmin
