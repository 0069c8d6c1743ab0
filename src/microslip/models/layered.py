"""The tip and centre models on a contact (shear layer + pressure law): one compiled step each.

:func:`tip_layer_step` and :func:`centre_layer_step` advance one case by one force increment:
the model's own recurrence twice (:func:`~microslip.models.tip.tip_step` or
:func:`~microslip.models.centre.centre_step`, with the options' Poisson and length
corrections and with both off) and the exact shear-layer curve at the new force
(:func:`~microslip.models.layer.domain_point`, warm-started from the previous front). The
displacement is the layer's times the factor the corrections apply to the rigid bar,
d_corrected / d_uncorrected (``models/contact.py`` explains why), and likewise the slip length.

The single loop (:func:`tip_layer_backbone`, :func:`centre_layer_backbone`, run by
:func:`microslip.first_loading` on a contact) and the batch engine
(:func:`microslip.models.batch_kernels.tip_layer_kernel`, ``centre_layer_kernel``) call these
steps, so they agree bit for bit.

A contact reaches the kernels as ``stick_slope`` (N/mm^3, inf: rigid), ``shear_lag`` (0/1),
the law's ``code`` and ``data`` (:mod:`microslip.models.layer`) and ``symmetric`` (0/1: the
centre load splits F/2 per half without a search).
"""

from __future__ import annotations

import numpy as np

from ..options import POISSON_CODES
from ._jit import jit
from .centre import centre_constants, centre_flags, centre_step
from .columns import backbone_columns
from .layer import domain_constants, domain_point, layer_k, split_point
from .tip import tip_constants, tip_flags, tip_step

__all__ = ["centre_layer_backbone", "centre_layer_setup", "centre_layer_step",
           "tip_layer_backbone", "tip_layer_setup", "tip_layer_step"]

#: The uncorrected recurrence (the rigid bar the layer's curve replaces): Poisson update off.
POISSON_OFF = POISSON_CODES["off"]


@jit(inline="always")
def tip_layer_setup(length, width, thickness, modulus, poisson_ratio, friction, normal_force,
                    poisson_code, length_update, reading, stick_slope, shear_lag, code, data):
    """Per-case flags, constants and unloaded state of the tip model on a layer:
    ``flags, plain_flags, c, plain_c, dom, state`` (state: d, 1/A, d_plain, 1/A_plain, the
    slip front a and its last change)."""
    flags = tip_flags(poisson_code, length_update, reading)
    plain = tip_flags(POISSON_OFF, 0, reading)
    ln, rfn, cnu, he, d0, ra0 = tip_constants(length, width, thickness, modulus,
                                              poisson_ratio, friction, normal_force, flags)
    pl = tip_constants(length, width, thickness, modulus, poisson_ratio, friction,
                       normal_force, plain)
    k = layer_k(width, thickness, modulus, poisson_ratio, stick_slope, shear_lag)
    dom = domain_constants(length, modulus * (width * thickness), k, friction * normal_force,
                           length, 1.0, -1.0, code, data)
    return (flags, plain, (ln, rfn, cnu, he), (pl[0], pl[1], pl[2], pl[3]), dom,
            (d0, ra0, pl[4], pl[5], 0.0, 0.0))


@jit(inline="always")
def tip_layer_step(f, fp, state, c, cp, flags, plain, dom, code, data):
    """One increment of the tip model on a layer.

    Returns the new state ``d, 1/A, d_plain, 1/A_plain, a, da`` (the rigid recurrences' own
    state, the slip front and its change, whose extrapolation starts the next front's
    search), then the displacement of the loaded section (mm), the slip
    length (mm) and the cross-section factor g of the corrected recurrence.
    """
    d, ra, dp, rap, a, da = state
    dn, ra_new, u, g = tip_step(f, fp, (d, ra), c, flags)
    dpn, rap_new, up, _ = tip_step(f, fp, (dp, rap), cp, plain)
    a_new, dl, _ = domain_point(dom, code, data, f, a + da)
    disp = dl * (dn / dpn) if dpn > 0.0 else dl
    slip = a_new * (u / up) if up > 0.0 else a_new
    return dn, ra_new, dpn, rap_new, a_new, a_new - a, disp, slip, g


@jit()
def tip_layer_backbone(f0, n, length, width, thickness, modulus, poisson_ratio, friction,
                       normal_force, poisson_code, length_update, reading, stick_slope,
                       shear_lag, code, data, symmetric):
    """The first loading of one case on a layer, the columns of a Backbone (as
    :func:`~microslip.models.tip.tip_backbone`; the stored energy is NaN: the layer's
    elastic energy is not the bar's)."""
    flags, plain, c, cp, dom, state = tip_layer_setup(
        length, width, thickness, modulus, poisson_ratio, friction, normal_force,
        poisson_code, length_update, reading, stick_slope, shear_lag, code, data)
    force, disp, stored, slip, w, t = backbone_columns(n, 1, width, thickness, np.nan)
    fr_prev = 0.0
    for i in range(1, n + 1):
        fr = i / n
        f = f0 * fr
        dn, ra, dpn, rap, a, da, dd, u, g = tip_layer_step(f, f0 * fr_prev, state, c, cp,
                                                           flags, plain, dom, code, data)
        state = (dn, ra, dpn, rap, a, da)
        force[i] = f
        disp[i] = dd
        slip[i, 0] = u
        w[i, 0] = w[i - 1, 0] * g
        t[i, 0] = t[i - 1, 0] * g
        fr_prev = fr
    return force, disp, stored, slip, w, t


@jit(inline="always")
def centre_layer_setup(length, width, thickness, modulus, poisson_ratio, friction,
                       normal_force, poisson_code, length_update, reading, stick_slope,
                       shear_lag, code, data):
    """Per-case flags, constants and unloaded state of the centre model on a layer:
    ``flags, plain_flags, c, plain_c, tension, compression, state`` (state: the corrected and
    the plain recurrences' four numbers each, the two fronts, the tension half's share, and
    the last changes of these three)."""
    flags = centre_flags(poisson_code, length_update, reading)
    plain = centre_flags(POISSON_OFF, 0, reading)
    cs = centre_constants(length, width, thickness, modulus, poisson_ratio, friction,
                          normal_force, flags)
    ps = centre_constants(length, width, thickness, modulus, poisson_ratio, friction,
                          normal_force, plain)
    k = layer_k(width, thickness, modulus, poisson_ratio, stick_slope, shear_lag)
    axial = modulus * (width * thickness)
    half = 0.5 * length
    limit = friction * normal_force
    tension = domain_constants(half, axial, k, limit, length, 0.5, 1.0, code, data)
    compression = domain_constants(half, axial, k, limit, length, 0.5, -1.0, code, data)
    return (flags, plain, (cs[0], cs[1], cs[2], cs[3], cs[4]),
            (ps[0], ps[1], ps[2], ps[3], ps[4]), tension, compression,
            (cs[5], cs[6], cs[7], cs[8], ps[5], ps[6], ps[7], ps[8], 0.0, 0.0, 0.0, 0.0, 0.0,
             0.0))


@jit(inline="always")
def centre_layer_step(f, fp, state, c, cp, flags, plain, tension, compression, code, data,
                      symmetric, both):
    """One increment of the centre model (physical reading) on a layer.

    A symmetric law gives each half F/2 (``both`` 0 skips the compression half, whose slip
    length alone it changes); otherwise the share is found by equal displacement
    (:func:`~microslip.models.layer.split_point`); each search starts from the extrapolation
    of the last two increments. Returns the new state (fourteen numbers, see
    :func:`centre_layer_setup`), the displacement (mm), the slip lengths of the tension
    and compression halves (mm) and the cross-section factors w_t/w, t_t/t, w_c/w.
    """
    dt, dc, et, ec, dtp, dcp, etp, ecp, at0, ac0, share0, dat, dac, dsh = state
    dt, dc, et, ec, dn, ut, uc, gt, ht, gc = centre_step(f, fp, (dt, dc, et, ec), c, flags)
    dtp, dcp, etp, ecp, dpn, utp, ucp, _, _, _ = centre_step(f, fp, (dtp, dcp, etp, ecp), cp,
                                                             plain)
    ac = ac0
    if symmetric:
        half = f / 2.0
        at, dl, _ = domain_point(tension, code, data, half, at0 + dat)
        if both:
            ac = domain_point(compression, code, data, half, ac0 + dac)[0]
        share = half
    else:
        at, ac, dl, share = split_point(tension, compression, code, data, f, at0 + dat,
                                        ac0 + dac,
                                        share0 + dsh if share0 > 0.0 else f / 2.0)
    disp = dl * (dn / dpn) if dpn > 0.0 else dl
    st = at * (ut / utp) if utp > 0.0 else at
    sc = ac * (uc / ucp) if ucp > 0.0 else ac
    return (dt, dc, et, ec, dtp, dcp, etp, ecp, at, ac, share, at - at0, ac - ac0,
            share - share0, disp, st, sc, gt, ht, gc)


@jit()
def centre_layer_backbone(f0, n, length, width, thickness, modulus, poisson_ratio, friction,
                          normal_force, poisson_code, length_update, reading, stick_slope,
                          shear_lag, code, data, symmetric):
    """The first loading of one case on a layer (as :func:`tip_layer_backbone`; slip, width
    and thickness of shape (n + 1, 2): tension, compression)."""
    flags, plain, c, cp, tension, compression, state = centre_layer_setup(
        length, width, thickness, modulus, poisson_ratio, friction, normal_force,
        poisson_code, length_update, reading, stick_slope, shear_lag, code, data)
    force, disp, stored, slip, w, t = backbone_columns(n, 2, width, thickness, np.nan)
    fr_prev = 0.0
    for i in range(1, n + 1):
        fr = i / n
        f = f0 * fr
        r = centre_layer_step(f, f0 * fr_prev, state, c, cp, flags, plain, tension,
                              compression, code, data, symmetric, 1)
        state = (r[0], r[1], r[2], r[3], r[4], r[5], r[6], r[7], r[8], r[9], r[10], r[11],
                 r[12], r[13])
        force[i] = f
        disp[i] = r[14]
        slip[i, 0], slip[i, 1] = r[15], r[16]
        w[i, 0], w[i, 1] = width * r[17], width * r[19]
        t[i, 0], t[i, 1] = thickness * r[18], thickness * r[19]
        fr_prev = fr
    return force, disp, stored, slip, w, t
