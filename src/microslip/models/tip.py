"""Tip-loaded microslip model (paper, Section 2.1, Eqs 2-10): its one kernel.

:func:`tip_step` is the whole recurrence of one increment of one case, a scalar ``@jit``
function. The batch engine (:func:`microslip.models.batch_kernels.tip_kernel`) inlines it per lane
of a chunk of cases; :func:`tip_backbone` calls it to record the virgin curve of one case
(:func:`microslip.first_loading`). There is no other copy of the arithmetic.
"""

from __future__ import annotations

from ._jit import jit
from .columns import backbone_columns

__all__ = ["tip_backbone", "tip_constants", "tip_flags", "tip_step", "tip_stored_energy"]


@jit(inline="always")
def tip_flags(poisson_code, length_update, reading):
    """Switches of the recurrence from the reading: (lu, keep_prev, nu_on).

    ``poisson_code`` from :data:`microslip.options.POISSON_CODES`; ``reading`` is ignored
    (the tip model has one reading).
    """
    lu = 1.0 if length_update else 0.0
    keep_prev = 1.0 if poisson_code == 0 else 0.0
    nu_on = 0.0 if poisson_code == 2 else 1.0
    return lu, keep_prev, nu_on


@jit(inline="always")
def tip_constants(length, width, thickness, modulus, poisson_ratio, friction, normal_force,
                  flags):
    """Per-case constants and the unloaded state of one case.

    Returns the constants ``L, 1/(mu F_N), nu/E, 1/(2E)`` followed by the state
    ``delta, 1/A = 0, 1/(w t)``, one flat tuple.
    """
    nu_on = flags[2]
    return (length, 1.0 / (friction * normal_force), nu_on * poisson_ratio / modulus,
            0.5 / modulus, 0.0, 1.0 / (width * thickness))


@jit(inline="always")
def tip_step(f, fp, state, c, flags):
    """Advance one case of the tip model by one force increment.

    Parameters
    ----------
    f, fp : float
        The new total tip force F_T(i) and the previous one F_T(i-1), N.
    state : tuple
        ``(delta_(i-1), 1/A_(i-1))``: displacement (mm) and inverse cross-section (1/mm^2).
    c : tuple
        Per-case constants from :func:`tip_constants`.
    flags : tuple
        Switches from :func:`tip_flags`.

    Returns
    -------
    tuple
        One flat tuple (a nested one defeats numba's parallel analysis of the batch
        kernels): the new state ``delta_i, 1/A_i`` (also the state of increment i + 1),
        then the slip length u_i (mm) and the cross-section factor of this increment
        g = w_i / w_(i-1) = t_i / t_(i-1).

    Notes
    -----
    With q = mu F_N / L (Eq. 2) the slip zone grows from the loaded end:

    1. Length update (Eq. 4): L_i = L + delta_(i-1); the slip length is
       u_i = F_i L_i / (mu F_N).
    2. Poisson update (Eqs 6-7), with f = dF_i = F_i - F_(i-1) (``consistent``) or
       f = F_i (``paper-literal``)::

           w_i = w_(i-1) - nu w_(i-1) f / (E w_(i-1) t_(i-1))
           t_i = t_(i-1) - nu t_(i-1) f / (E w_(i-1) t_(i-1))

       i.e. both scale by g = 1 - nu f / (E A_(i-1)) and 1/A_i = (1/A_(i-1)) / g^2.
    3. Stiffness of the slipping part (Eq. 9): k_i = 2 E w_i t_i / u_i.
    4. Displacement (Eq. 10): delta_i = F_i / k_i = F_i u_i / (2 E w_i t_i).

    With both updates off, delta = F^2 / (2 E A q), the rigid-foundation solution of
    Goodman & Klumpp, whatever the increment size.
    """
    d, ra = state
    ln, rfn, cnu, he = c
    lu, keep_prev = flags[0], flags[1]
    u = f * (ln + lu * d) * rfn
    g = 1.0 - cnu * (f - keep_prev * fp) * ra
    ra_new = ra / (g * g)
    dn = f * u * he * ra_new
    return dn, ra_new, u, g


@jit(inline="always")
def tip_stored_energy(force, d):
    """Elastic energy in the bar, F delta / 3 (linear fall of the axial force over u), N·mm."""
    return force * d / 3.0


@jit()
def tip_backbone(f0, n, length, width, thickness, modulus, poisson_ratio, friction,
                 normal_force, poisson_code, length_update, reading):
    """Record the first loading of one case from rest to ``f0`` in ``n`` equal increments.

    Returns ``force, displacement, stored`` of shape (n + 1,) and ``slip, width,
    thickness`` of shape (n + 1, 1): the columns of a :class:`~microslip.results.Backbone`.
    Force i is ``f0 * (i / n)``, as in the batch engine.
    """
    flags = tip_flags(poisson_code, length_update, reading)
    ln, rfn, cnu, he, d0, ra0 = tip_constants(length, width, thickness, modulus,
                                              poisson_ratio, friction, normal_force, flags)
    c = (ln, rfn, cnu, he)
    state = (d0, ra0)
    force, disp, stored, slip, w, t = backbone_columns(n, 1, width, thickness, 0.0)
    fr_prev = 0.0
    for i in range(1, n + 1):
        fr = i / n
        f = f0 * fr
        fp = f0 * fr_prev
        dn, ra, u, g = tip_step(f, fp, state, c, flags)
        state = (dn, ra)
        force[i] = f
        disp[i] = dn
        slip[i, 0] = u
        w[i, 0] = w[i - 1, 0] * g
        t[i, 0] = t[i - 1, 0] * g
        stored[i] = tip_stored_energy(f, dn)
        fr_prev = fr
    return force, disp, stored, slip, w, t
