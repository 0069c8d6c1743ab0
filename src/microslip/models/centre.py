"""Centre-loaded microslip model (paper, Section 2.2, Eqs 11-18): its one kernel.

:func:`centre_step` is the whole recurrence of one increment of one case, a scalar ``@jit``
function. The batch engine (:func:`microslip.models.batch_kernels.centre_kernel`) inlines it per
lane of a chunk of cases; :func:`centre_backbone` calls it to record the virgin curve of one
case (:func:`microslip.first_loading`). There is no other copy of the arithmetic.
"""

from __future__ import annotations

from ._jit import jit
from .columns import backbone_columns

__all__ = ["centre_backbone", "centre_constants", "centre_flags", "centre_step",
           "centre_stored_energy"]


@jit(inline="always")
def centre_flags(poisson_code, length_update, reading):
    """Switches of the recurrence: (lu, t_sign, f_share, c_sign, len_share, u_share, nu_on).

    ``reading`` 0 is the physical reading (F/2 per half, half lengths L/2 -/+ delta_d), 1 the
    paper's (Eq. 11 as printed: full F per domain, lengths L + delta_d, u = F L' / (4 mu F_N)).
    """
    lu = 1.0 if length_update else 0.0
    nu_on = 0.0 if poisson_code == 2 else 1.0
    t_sign = 1.0 if poisson_code == 1 else -1.0  # Eq. 15 as printed: tension domain thickens
    if reading == 0:
        return lu, t_sign, 0.5, -1.0, 0.5, 1.0, nu_on
    return lu, t_sign, 1.0, 1.0, 1.0, 0.25, nu_on


@jit(inline="always")
def centre_constants(length, width, thickness, modulus, poisson_ratio, friction, normal_force,
                     flags):
    """Per-case constants ``l_d, u_share/(mu F_N), nu, 1/(2E), A`` followed by the unloaded
    state ``delta_t, delta_c, e_t, e_c = 0``, one flat tuple."""
    len_share, u_share, nu_on = flags[4], flags[5], flags[6]
    return (len_share * length, u_share / (friction * normal_force), nu_on * poisson_ratio,
            0.5 / modulus, width * thickness, 0.0, 0.0, 0.0, 0.0)


@jit(inline="always")
def centre_step(f, fp, state, c, flags):
    """Advance one case of the centre model by one force increment.

    Parameters
    ----------
    f, fp : float
        The new total centre force F_T(i) and the previous one, N (``fp`` is unused: the
        centre model's Poisson update works from the previous strain).
    state : tuple
        ``(delta_t, delta_c, e_t, e_c)`` of increment i - 1: domain displacements (mm) and
        mean strains e_d = delta_d / u_d.
    c, flags : tuple
        From :func:`centre_constants` and :func:`centre_flags`.

    Returns
    -------
    tuple
        One flat tuple (a nested one defeats numba's parallel analysis of the batch
        kernels): the state of increment i ``delta_t, delta_c, e_t, e_c``, then the
        displacement of the loaded section delta (Eq. 18, mm), the slip lengths u_t, u_c
        (mm) and the cross-section factors w_t / w, t_t / t, w_c / w = t_c / t.

    Notes
    -----
    The bar is split at mid-length into a tension and a compression domain that act in
    parallel (Section 2.2). Per domain d (sign s_d = +1 tension, -1 compression):

    1. Domain force and slip length (Eqs 11, 17), ``physical`` reading: F_d = F/2 and
       u_d = F_d / q_d with q_d = (mu F_N / 2) / l_d on the half length
       l_d = L/2 + s_d delta_d(i-1) (length update) or L/2, i.e. u_d = F l_d / (mu F_N).
       ``paper`` reading: F_d = F and Eq. 11 as printed,
       u_d = F (L + delta_d(i-1)) / (4 mu F_N).
    2. Poisson update (Eqs 12-15) from the previous mean strain e_d = delta_d(i-1) / u_d(i-1)
       = F_d / (2 E A_d)::

           w_d = w (1 - s_d nu e_d),  t_d = t (1 - s_d nu e_d)    (consistent)

       ``paper-literal`` keeps the printed ``+`` of Eq. 15 for t of the tension domain.
    3. Stiffness (Eq. 16) k_d = 2 E w_d t_d / u_d and displacement (Eq. 17)
       delta_d = F_d / k_d.
    4. Loaded section (Eq. 18): delta = (k_t delta_t + k_c delta_c) / (k_t + k_c)
       = 2 F_d u_t u_c / (2 E (A_t u_c + A_c u_t)), the two domains as parallel springs.

    One division per increment: r = 1 / (A_t A_c S) with S = u_t A_c + u_c A_t gives
    1/A_t = A_c S r, 1/A_c = A_t S r and 1/S = A_t A_c r.

    With both updates off, both readings give delta = F^2 / (8 E A q), the exact result
    for a centre-loaded bar on a rigid Coulomb foundation.
    """
    dt, dc, et, ec = state
    lh, rfn, nu, he, a0 = c
    lu, t_sign, f_share, c_sign = flags[0], flags[1], flags[2], flags[3]
    fd = f_share * f
    ut = f * (lh + lu * dt) * rfn
    uc = f * (lh + c_sign * lu * dc) * rfn
    gt = 1.0 - nu * et
    ht = 1.0 + t_sign * nu * et
    gc = 1.0 + nu * ec
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
    return dt, dc, et, ec, dn, ut, uc, gt, ht, gc


@jit(inline="always")
def centre_stored_energy(force, dt, dc):
    """Elastic energy in both halves: each carries F/2 over its slip length, whatever the
    reading, (F/2)(delta_t + delta_c) / 3, N·mm."""
    return 0.5 * force * (dt + dc) / 3.0


@jit()
def centre_backbone(f0, n, length, width, thickness, modulus, poisson_ratio, friction,
                    normal_force, poisson_code, length_update, reading):
    """Record the first loading of one case from rest to ``f0`` in ``n`` equal increments.

    Returns ``force, displacement, stored`` of shape (n + 1,) and ``slip, width,
    thickness`` of shape (n + 1, 2) (tension, compression).
    """
    flags = centre_flags(poisson_code, length_update, reading)
    cs = centre_constants(length, width, thickness, modulus, poisson_ratio, friction,
                          normal_force, flags)
    c = (cs[0], cs[1], cs[2], cs[3], cs[4])
    state = (cs[5], cs[6], cs[7], cs[8])
    force, disp, stored, slip, w, t = backbone_columns(n, 2, width, thickness, 0.0)
    fr_prev = 0.0
    for i in range(1, n + 1):
        fr = i / n
        f = f0 * fr
        dt, dc, et, ec, dn, ut, uc, gt, ht, gc = centre_step(f, f0 * fr_prev, state, c, flags)
        state = (dt, dc, et, ec)
        force[i] = f
        disp[i] = dn
        slip[i, 0], slip[i, 1] = ut, uc
        w[i, 0], w[i, 1] = width * gt, width * gc
        t[i, 0], t[i, 1] = thickness * ht, thickness * gc
        stored[i] = centre_stored_energy(f, dt, dc)
        fr_prev = fr
    return force, disp, stored, slip, w, t
