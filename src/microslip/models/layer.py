"""The shear-layer bar's compiled physics: pressure laws, slip front, one point of the curve.

This is the one definition of the exact solution of :mod:`microslip.models.interface` (a bar
on an elastic-perfectly-plastic shear layer under a pressure law, see that module's notes):
the NumPy API there (:class:`~microslip.models.interface.PressureLaw`, ``virgin_curve``,
``masing_dissipation``), the single loop (:func:`microslip.first_loading` on a
:class:`~microslip.models.contact.Contact`) and the batch engine's layer kernels all call
the scalar ``@jit`` functions below.

A pressure law is ``(code, data)``: :data:`LAW_UNIFORM` (data unused), :data:`LAW_POWER`
(``data[0] = c, b, n, w`` of p = c (1 + b |2 xi - 1|^n), w = n when n is a whole number
up to :data:`WHOLE_EXPONENTS`, else 0) or :data:`LAW_TABLE` (rows x, p,
slope, P, PP of a piecewise-linear shape at its nodes), ``data`` a 2-D float64 array.

A loaded domain is the flat tuple of :func:`domain_constants`. :func:`front` solves
F(a) = f for the slip front by Newton's method inside a bracket that every evaluation
narrows (bisection when a step leaves it), warm-started from the previous increment's front:
two or three evaluations per increment instead of the 64 of plain bisection, and the same
root to rounding.
"""

from __future__ import annotations

import math

import numpy as np

from ._jit import jit

__all__ = ["LAW_POWER", "LAW_TABLE", "LAW_UNIFORM", "domain_constants", "domain_curve",
           "domain_force", "domain_law", "domain_point", "domain_total", "front", "law_eval",
           "law_values", "layer_k", "split_curve", "split_point"]

LAW_UNIFORM, LAW_POWER, LAW_TABLE = 0, 1, 2
#: Whole exponents of a power law up to this are evaluated by products instead of ``pow``.
WHOLE_EXPONENTS = 8

#: Newton steps of the slip front (and of the centre split) end below this fraction of the
#: domain's length (force): the next step would change nothing in double precision.
STEP_TOL = 1e-14
#: ... or when the next step, predicted from the last two, is below this fraction.
PREDICTED_TOL = 1e-16
#: Iterations after which the front search falls back to plain bisection (kinks of a table).
NEWTON_ITERATIONS = 40
MAX_ITERATIONS = 200


@jit()
def layer_k(width, thickness, modulus, poisson_ratio, stick_slope, shear_lag):
    """Layer stiffness per unit length, N/mm^2: the contact's stick slope (N/mm^3) over the
    width in series with the body's shear lag t / (3 G w) (``shear_lag`` 0 or 1); inf when
    both are rigid."""
    compliance = 1.0 / (stick_slope * width)
    if shear_lag:
        shear_modulus = modulus / (2.0 * (1.0 + poisson_ratio))
        compliance += thickness / (3.0 * shear_modulus * width)
    return math.inf if compliance == 0.0 else 1.0 / compliance


@jit(inline="always")
def _segment(x, xi):
    """Index j of the table interval holding xi (np.searchsorted(x, xi, 'right') - 1, clipped
    to the first and last intervals)."""
    lo = 0
    hi = x.shape[0]
    while lo < hi:
        mid = (lo + hi) // 2
        if x[mid] <= xi:
            lo = mid + 1
        else:
            hi = mid
    return min(max(lo - 1, 0), x.shape[0] - 2)


@jit(inline="always")
def law_eval(code, data, xi):
    """The law at xi: p (mean 1), dp/dxi (0 at a kink's apex), P = integral_0^xi p and
    PP = integral_0^xi P; a power law costs one ``pow``."""
    if code == LAW_UNIFORM:
        return 1.0, 0.0, xi + 0.0, 0.5 * xi * xi
    if code == LAW_POWER:
        c, b, n, whole = data[0, 0], data[0, 1], data[0, 2], int(data[0, 3])
        # with z = 2 xi - 1: integral_-1^z |z|^n dz = (1 + sgn z |z|^(n+1)) / (n+1)
        z = 2.0 * xi - 1.0
        az = abs(z)
        sgn = 1.0 if z > 0.0 else (-1.0 if z < 0.0 else 0.0)
        if whole > 0:  # a whole exponent: products, not pow (4 x faster)
            pw = az
            for _ in range(whole - 1):
                pw *= az
        else:
            pw = az ** n
        slope = 0.0 if z == 0.0 else 2.0 * c * b * n * (pw / az) * sgn
        big_p = c * (xi + 0.5 * b * (1.0 + sgn * (pw * az)) / (n + 1.0))
        inner = (xi + 0.5 * (pw * az * az - 1.0) / (n + 2.0)) / (n + 1.0)
        return c * (1.0 + b * pw), slope, big_p, c * (0.5 * xi * xi + 0.5 * b * inner)
    j = _segment(data[0], xi)
    e = xi - data[0, j]
    p, s = data[1, j], data[2, j]
    # e * e * e, not e ** 3: numba compiles a whole power to these products, Python calls
    # pow(); written out, the plain and the compiled kernel agree bit for bit
    return (p + s * e, s, data[3, j] + p * e + s * (e * e) / 2,
            data[4, j] + data[3, j] * e + p * (e * e) / 2 + s * (e * e * e) / 6)


@jit()
def law_values(which, code, data, xi):
    """p (``which`` 0), P (2) or PP (3) at every xi of a 1-D array: the NumPy face of the
    law (:class:`~microslip.models.interface.PressureLaw`)."""
    out = np.empty(xi.shape[0])
    for i in range(xi.shape[0]):
        out[i] = law_eval(code, data, xi[i])[which]
    return out


@jit()
def domain_constants(length, axial, k, limit, span, xi0, direction, code, data):
    """The flat tuple of one loaded domain (see ``interface.Domain`` for the arguments):
    ``length, axial, k, lam, limit, span, xi0, direction, P(xi0), PP(xi0), limit / span,
    total (its macroslip force), onset (F at a = 0), stuck stiffness``."""
    lam = math.sqrt(k / axial) if math.isfinite(k) else math.inf
    p_0, _, p0, pp0 = law_eval(code, data, xi0)
    qs = limit / span
    total = limit * direction * (law_eval(code, data, xi0 + direction * length / span)[2] - p0)
    if math.isfinite(lam):
        onset = qs * p_0 / lam * math.tanh(lam * length)
        stiff = axial * lam * math.tanh(lam * length)
    else:
        onset = 0.0
        stiff = math.inf
    return (length, axial, k, lam, limit, span, xi0, direction, p0, pp0, qs, total, onset,
            stiff)


@jit(inline="always")
def domain_total(dom):
    """The domain's macroslip force, N."""
    return dom[11]


@jit(inline="always")
def domain_law(dom, code, data, s):
    """At distance s from the loaded section: q (N/mm), dq/ds (N/mm^2), Q = integral_0^s q
    (N) and R = integral_0^s Q (N mm); one evaluation of the law."""
    limit, span, xi0, direction, p0, pp0, qs = (dom[4], dom[5], dom[6], dom[7], dom[8],
                                                dom[9], dom[10])
    xi = xi0 + direction * s / span
    p, dp, big_p, big_pp = law_eval(code, data, xi)
    return (qs * p, qs * dp * direction / span, limit * direction * (big_p - p0),
            limit * span * (big_pp - pp0 - p0 * (xi - xi0)))


@jit(inline="always")
def domain_force(dom, code, data, a):
    """F(a) = Q(a) + (q(a)/lambda) tanh(lambda (L - a)), the load that puts the slip front
    at a, and dF/da."""
    length, lam = dom[0], dom[3]
    q, dq, big_q, _ = domain_law(dom, code, data, a)
    if not math.isfinite(lam):
        return big_q, q
    t = math.tanh(lam * (length - a))
    return big_q + q / lam * t, q * t * t + dq * t / lam


@jit(inline="always")
def front(dom, code, data, f, guess):
    """The slip front a in (0, L] under the force f > onset, and dF/da near it.

    Newton from ``guess`` inside the bracket [lo, hi] that every evaluation narrows (F is
    increasing); a step outside the bracket, or any step after NEWTON_ITERATIONS, bisects.
    Ends after a step below STEP_TOL of the length, or after a Newton step whose successor,
    predicted from the last two (quadratic convergence), is below PREDICTED_TOL of it.
    """
    length = dom[0]
    lo = 0.0
    hi = length
    a = min(max(guess, 0.0), length)
    slope = 1.0
    tol = STEP_TOL * length
    pred = PREDICTED_TOL * length
    last = 0.0  # the previous Newton step (0: none)
    for it in range(MAX_ITERATIONS):
        force, slope = domain_force(dom, code, data, a)
        if force < f:
            lo = a
        else:
            hi = a
        new = a + (f - force) / slope if 0.0 < slope < math.inf else math.nan
        newton = lo <= new <= hi and it < NEWTON_ITERATIONS
        if not newton:
            new = 0.5 * (lo + hi)
        step = abs(new - a)
        done = step <= tol or hi - lo <= 0.0 or (newton and step * step * step
                                                  <= pred * last * last)
        last = step if newton else 0.0
        a = new
        if done:
            break
    return a, slope


@jit(inline="always")
def domain_point(dom, code, data, f, guess):
    """(a, d, dd/dF) of the virgin curve at force f: slip front (0 while stuck), displacement
    of the loaded section (mm) and the curve's compliance (mm/N, for the centre split)."""
    axial, k, onset, stiff = dom[1], dom[2], dom[12], dom[13]
    if f <= onset:
        return 0.0, f / stiff, 1.0 / stiff
    a, slope = front(dom, code, data, f, guess)
    q, dq, big_q, big_r = domain_law(dom, code, data, a)
    rigid = math.isinf(k)
    layer = 0.0 if rigid else q / k
    d = layer + (f * a - big_r) / axial
    dq_k = 0.0 if rigid else dq / k
    return a, d, a / axial + (dq_k + (f - big_q) / axial) / slope


@jit()
def split_point(dom1, dom2, code, data, f, guess1, guess2, share):
    """Two domains in parallel under f with an asymmetric law: the share F_1 of the first at
    which both move the loaded section equally, by bracketed Newton from ``share`` (the
    compliances of :func:`domain_point` as slopes). Returns ``a_1, a_2, d, F_1``.
    """
    lo = max(0.0, f - domain_total(dom2))
    hi = min(f, domain_total(dom1))
    s = min(max(share, lo), hi)
    a1, d1, c1 = domain_point(dom1, code, data, s, guess1)
    a2, d2, c2 = domain_point(dom2, code, data, f - s, guess2)
    tol = STEP_TOL * f
    for it in range(MAX_ITERATIONS):
        g = d1 - d2
        if g < 0.0:
            lo = s
        else:
            hi = s
        slope = c1 + c2
        new = s - g / slope if 0.0 < slope < math.inf else math.nan
        if not (lo <= new <= hi) or it >= NEWTON_ITERATIONS:
            new = 0.5 * (lo + hi)
        done = abs(new - s) <= tol or hi - lo <= 0.0
        s = new
        a1, d1, c1 = domain_point(dom1, code, data, s, a1)
        a2, d2, c2 = domain_point(dom2, code, data, f - s, a2)
        if done:
            break
    return a1, a2, d1, s


@jit()
def domain_curve(dom, code, data, force):
    """(a, d) of one domain's virgin curve at every force of a 1-D array, each front search
    started from the extrapolation of the two before, as the models' steps do (so that the
    same forces give the same numbers bit for bit)."""
    n = force.shape[0]
    a = np.empty(n)
    d = np.empty(n)
    last = change = 0.0
    for i in range(n):
        a[i], d[i], _ = domain_point(dom, code, data, force[i], last + change)
        change = a[i] - last
        last = a[i]
    return a, d


@jit()
def split_curve(dom1, dom2, code, data, force):
    """(a_1, a_2, d) of two domains in parallel at every force (:func:`split_point`, started
    as :func:`domain_curve`)."""
    n = force.shape[0]
    a1 = np.empty(n)
    a2 = np.empty(n)
    d = np.empty(n)
    g1 = g2 = share = c1 = c2 = cs = 0.0
    for i in range(n):
        a1[i], a2[i], d[i], new = split_point(dom1, dom2, code, data, force[i], g1 + c1,
                                              g2 + c2,
                                              share + cs if share > 0.0 else force[i] / 2.0)
        c1, c2, cs = a1[i] - g1, a2[i] - g2, new - share
        g1, g2, share = a1[i], a2[i], new
    return a1, a2, d
