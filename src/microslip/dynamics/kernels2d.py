"""Compiled kernels of the two-directional Iwan operator: parallel 2-D Jenkins elements with
one circular Coulomb limit each, isotropic or anisotropic springs.

Element e: a spring ``K = diag(k[e], ky[e])`` (N/mm) in series with a slider at ``z`` (mm, a
2-vector); its force ``f = K (u - z)`` (N) stays within the circle ``|f| <= s``,
``s = k[e] phi[e]`` (``phi`` the slip displacement along x, mm), and the slider slips
along the force (associated flow, isotropic Coulomb friction). Force of the set:
``sum_e K_e (u - z_e)``.

Notes
-----
Return map from the trial stretch ``d = u - z`` (:func:`_slip`), written in
x-displacement units (forces over ``k``, ``rho = ky / k``): ``g = (d_x, rho d_y)``,
elastic if ``|g| <= phi``; else ``g_j / (1 + gamma r_j)`` (``r = (1, rho)``) with
gamma >= 0 the root of ``|g(gamma)| = phi`` and ``z_new = u - C d``,
``C = diag(c_j) = diag(1 / (1 + gamma r_j))``: the slip increment ``z_new - z = gamma g_new``
is parallel to the new force. Newton's method on ``phi / |g(gamma)| - 1`` (concave and
increasing in gamma) from ``gamma_0 = (|g| / phi - 1) / max(1, rho)`` (a lower bound of the
root) increases monotonically to it; for ``rho = 1`` gamma_0 is the root (radial return,
``C = (phi / r) I``). The new stretch is then set from its direction (d_x, (c_y / c_x) d_y)
scaled onto the circle, which for rho = 1 is the radial return's own arithmetic, bit for
bit (so a slider exactly at its limit decides stick or slip as before).

Tangent by implicit differentiation of ``|g_new| = phi``: ``dz_new = (I - D) du + D dz``
with ``D = C - (c o g)(r o c o g)^T / b``, ``b = sum_j r_j c_j g_j^2`` (o the elementwise
product), i.e. ``D_xx = c_x rho c_y g_y^2 / b``, ``D_yy = c_y c_x g_x^2 / b``,
``D_xy = -rho c_x c_y g_x g_y / b``, ``D_yx = -c_x c_y g_x g_y / b``; the force tangent
``K D`` is symmetric. For ``rho = 1`` it is ``D = (phi / r) (I - n n^T)``. Along one axis
``g`` has one component, D is 0 along it and the step is the 1-D return mapping of
:mod:`.kernels` (to round-off).

Periodic state of an element (:func:`_periodic_state`): passes through the period from the
virgin state, values only (the slider and the 2x2 ``P``, each slipping sample's D recorded),
as the history would, until a pass repeats to round-off; the derivative in the
coefficients is formed once at the end, from the recorded D (summed backwards, O(1) per
slip) or from the last pass alone at a fixed point found by Newton's method. An element
whose passes decay geometrically too slowly to repeat within :data:`CYCLES` goes to
Newton's method as soon as that shows (it would have gone after CYCLES passes, to the same
fixed point).
"""

from __future__ import annotations

import math

import numpy as np

from ..contactlaw import get_contact_law
from .kernels import njit

__all__ = ["circular_periodic_kernel", "return_map"]

#: The elements' contact law (:mod:`microslip.contactlaw`), compiled for these kernels.
_law = njit(cache=True, fastmath=False, nogil=True)(get_contact_law("coulomb").return_map)

#: Passes at most of the per-element fixed-point (Newton) iteration for the periodic state.
MAX_PASSES = 200

#: Cycles repeated as the history would before Newton's method takes over (sooner for an
#: element whose passes plainly decay too slowly to repeat within them).
CYCLES = 60

#: Newton iterations at most for the return map's gamma (monotone, quadratic: a few).
MAX_NEWTON = 100


@njit(cache=True, fastmath=False, nogil=True)
def _skew(dx: float, dy: float, rho: float, ph: float) -> float:
    """``q = c_y / c_x = (1 + gamma) / (1 + gamma rho)`` of a slipping step from the trial
    stretch (dx, dy) (``|(dx, rho dy)| > phi``): the new stretch is parallel to
    (dx, q dy). 1 exactly if rho = 1."""
    gamma = (math.hypot(dx, rho * dy) / ph - 1.0) / max(1.0, rho)
    for _ in range(MAX_NEWTON):
        cx = 1.0 / (1.0 + gamma)
        cy = 1.0 / (1.0 + gamma * rho)
        gx = cx * dx
        gy = cy * rho * dy
        norm = math.hypot(gx, gy)
        step = (norm - ph) * norm * norm / (ph * (cx * gx * gx + rho * cy * gy * gy))
        if not step > 1e-15 * gamma:  # converged (or round-off: step <= 0)
            break
        gamma += step
    return (1.0 + gamma) / (1.0 + gamma * rho)


@njit(cache=True, fastmath=False, nogil=True)
def _slip(ux: float, uy: float, zx: float, zy: float, rho: float, ph: float
          ) -> tuple[float, float, float, float, float, float]:
    """New slider (zx, zy) of a slipping step, the direction (nx, ny) of the new stretch
    ``phi n`` (``|(n_x, rho n_y)| = 1``: the force on the circle) and (c_x, c_y).

    The contact law (:mod:`microslip.contactlaw`, in x-displacement units: force over k,
    limit phi) projects the trial force over k, skewed by the anisotropic spring to
    ``(d_x, rho q d_y)``, radially onto the circle; for rho = 1 (q = 1) that is the law's
    radial return of the element itself, ``z = u - phi (u - z) / |u - z|``."""
    dx = ux - zx
    dy = uy - zy
    q = _skew(dx, dy, rho, ph)
    wy = q * dy
    fx, fy, _, _, _, _, _, nx, _, _ = _law(dx, rho * wy, 0.0, 0.0, 1.0, ph)
    norm = math.hypot(dx, rho * wy)
    cx = ph / norm
    return ux - fx, uy - fy / rho, nx, wy / norm, cx, q * cx


@njit(cache=True, fastmath=False, nogil=True)
def return_map(ux: float, uy: float, zx: float, zy: float, rho: float, ph: float
               ) -> tuple[float, float]:
    """New slider position (zx, zy), mm, of an element (``rho = ky / k``, slip displacement
    ``ph`` along x, mm) moved to ``u`` (mm) from ``z``."""
    if math.hypot(ux - zx, rho * (uy - zy)) > ph:
        zx, zy, _, _, _, _ = _slip(ux, uy, zx, zy, rho, ph)
    return zx, zy


@njit(cache=True, fastmath=False, nogil=True)
def _slip_map(ux: float, uy: float, zx: float, zy: float, rho: float, ph: float
              ) -> tuple[float, float, float, float, float, float]:
    """The new slider position and D (d00, d01, d10, d11) at a slipping step from (zx, zy)
    to u."""
    zx, zy, nx, ny, cx, cy = _slip(ux, uy, zx, zy, rho, ph)
    gx = nx  # the force over k phi
    gy = rho * ny
    b = cx * gx * gx + rho * cy * gy * gy
    return (zx, zy, cx * rho * cy * gy * gy / b, -rho * cx * cy * gx * gy / b,
            -cx * cy * gx * gy / b, cy * cx * gx * gx / b)


@njit(cache=True, fastmath=False, nogil=True)
def _advance(g: np.ndarray, d00: float, d01: float, d10: float, d11: float,
             basis: np.ndarray, t: int, h: int) -> None:
    """g <- D g + (I - D) E_t in place; g is (2, 2h), E_t[a, b h + c] = delta_ab basis[t, c]."""
    cols = g.shape[1]
    for c in range(cols):
        g0 = g[0, c]
        g1 = g[1, c]
        g[0, c] = d00 * g0 + d01 * g1
        g[1, c] = d10 * g0 + d11 * g1
    for c in range(h):
        bt = basis[t, c]
        g[0, c] += (1.0 - d00) * bt
        g[1, c] -= d10 * bt
        g[0, h + c] -= d01 * bt
        g[1, h + c] += (1.0 - d11) * bt


@njit(cache=True, fastmath=False, nogil=True)
def _slips(r: float, ph: float, first: bool, virgin: bool) -> int:
    """0: the element sticks; 1: it slips (trial ``r = |(d_x, rho d_y)|`` > phi); 2: it
    sits where the virgin loading to the start sample left it, at its limit (counted as
    slipping there, as in the 1-D kernel, with the virgin state's derivative)."""
    if r > ph:
        return 1
    if first and virgin and r >= ph * (1.0 - 1e-14):
        return 2
    return 0


@njit(cache=True, fastmath=False, nogil=True)
def _pass(u: np.ndarray, rho: float, ph: float, start: int, virgin: bool, zx: float,
          zy: float, ev_t: np.ndarray, ev_d: np.ndarray, count: int
          ) -> tuple[float, float, float, float, float, float, int]:
    """One pass G through the period from the slider (zx, zy), values only: the end slider,
    ``P = dG/dz0`` (p00, p01, p10, p11, the product of the slipping steps' D) and the new
    event count. Each slipping sample t is recorded from ``count`` on: ``ev_t`` = t (or
    ``-1 - t`` for the virgin state, which restarts the derivative), ``ev_d`` = its D."""
    n = u.shape[0]
    p00, p01, p10, p11 = 1.0, 0.0, 0.0, 1.0
    for j in range(n):
        t = start + j
        if t >= n:
            t -= n
        ux, uy = u[t, 0], u[t, 1]
        kind = _slips(math.hypot(ux - zx, rho * (uy - zy)), ph, j == 0, virgin)
        if kind == 0:
            continue
        if kind == 2:  # the virgin state: depends on u[start] only
            d00, d01, d10, d11 = _slip_map(ux, uy, 0.0, 0.0, rho, ph)[2:]
            p00, p01, p10, p11 = 0.0, 0.0, 0.0, 0.0
            ev_t[count] = -1 - t
        else:
            zx, zy, d00, d01, d10, d11 = _slip_map(ux, uy, zx, zy, rho, ph)
            p00, p01, p10, p11 = (d00 * p00 + d01 * p10, d00 * p01 + d01 * p11,
                                  d10 * p00 + d11 * p10, d10 * p01 + d11 * p11)
            ev_t[count] = t
        ev_d[count, 0], ev_d[count, 1], ev_d[count, 2], ev_d[count, 3] = d00, d01, d10, d11
        count += 1
    return zx, zy, p00, p01, p10, p11, count


@njit(cache=True, fastmath=False, nogil=True)
def _history_derivative(ev_t: np.ndarray, ev_d: np.ndarray, count: int, basis: np.ndarray,
                        w: np.ndarray, dz0: np.ndarray) -> None:
    """``dz0`` (2, 2h) = the recursion ``dz <- D dz + (I - D) E_t`` from ``dz = 0`` over the
    events [0, count), summed backwards: ``dz0 = sum_events M (I - D) E_t`` with ``M`` the
    product of the later events' D (2x2, O(1) per event), gathered per sample into ``w``
    (N, 2, 2, scratch) and expanded over the basis once; a virgin-state event ends the sum."""
    n = basis.shape[0]
    h = basis.shape[1]
    w[:, :, :] = 0.0
    m00, m01, m10, m11 = 1.0, 0.0, 0.0, 1.0
    for i in range(count - 1, -1, -1):
        t = ev_t[i]
        reset = t < 0
        if reset:
            t = -1 - t
        d00, d01, d10, d11 = ev_d[i, 0], ev_d[i, 1], ev_d[i, 2], ev_d[i, 3]
        w[t, 0, 0] += m00 * (1.0 - d00) - m01 * d10
        w[t, 0, 1] += m01 * (1.0 - d11) - m00 * d01
        w[t, 1, 0] += m10 * (1.0 - d00) - m11 * d10
        w[t, 1, 1] += m11 * (1.0 - d11) - m10 * d01
        if reset:
            break
        m00, m01, m10, m11 = (m00 * d00 + m01 * d10, m00 * d01 + m01 * d11,
                              m10 * d00 + m11 * d10, m10 * d01 + m11 * d11)
    dz0[:, :] = 0.0
    for t in range(n):
        w00, w01, w10, w11 = w[t, 0, 0], w[t, 0, 1], w[t, 1, 0], w[t, 1, 1]
        if w00 == 0.0 and w01 == 0.0 and w10 == 0.0 and w11 == 0.0:
            continue
        for c in range(h):
            bt = basis[t, c]
            dz0[0, c] += w00 * bt
            dz0[0, h + c] += w01 * bt
            dz0[1, c] += w10 * bt
            dz0[1, h + c] += w11 * bt


@njit(cache=True, fastmath=False, nogil=True)
def _periodic_state(u: np.ndarray, rho: float, ph: float, start: int, basis: np.ndarray,
                    z0: np.ndarray, dz0: np.ndarray, virgin: bool, ev_t: np.ndarray,
                    ev_d: np.ndarray, w: np.ndarray) -> bool:
    """The element's periodic slider position before sample ``start`` (``z0``, updated in
    place from the virgin state) and its derivative ``dz0`` (2, 2h) in the coefficients
    (filled). ``ev_t``, ``ev_d``: room for ``(CYCLES + 1) N`` slip events; ``w``: (N, 2, 2).

    One pass G through the period (:func:`_pass`) has ``P = dG/dz0`` (the product of the
    slipping steps' D) and ``Q = dG/dC`` (the recursion of :func:`_advance` from 0). The
    first :data:`CYCLES` passes repeat the cycle as the history would, values only
    (``z0 <- G(z0)``), recording the slip events, until a pass returns to its start to
    round-off: an element that does so (or shakes down to elastic cycling) keeps the state
    its history gave it and the history's derivative (``dz0 <- P dz0 + Q`` pass by pass
    from 0, :func:`_history_derivative` on the recorded events). Otherwise Newton's method
    on ``z0 = G(z0)``, and at the fixed point ``dz0 = (I - P)^-1 Q``, Q from that pass's
    events alone (the history is forgotten); where ``I - P`` is singular there (shakedown
    reached late), the history's derivative carried through that pass. Returns False if
    not converged.

    Newton's method starts early (:func:`_solve`) once the residuals ``|G(z0) - z0|`` of
    three passes decay geometrically (two ratios q < 1 within 10 %), ``|I - P|`` is not
    small (1e-8) and ``q`` to the passes left would still leave the residual 1e3 times above
    the repeat tolerance: the history would not have repeated, and Newton's method reaches
    the same fixed point (to round-off) with the same derivative. Should such an element
    end singular (shakedown) or not converge, it is redone with the full history.
    """
    zx, zy = z0[0], z0[1]
    status = _solve(u, rho, ph, start, basis, z0, dz0, virgin, ev_t, ev_d, w, True)
    if status == 2:  # cut short but the history was wanted: the history in full
        z0[0], z0[1] = zx, zy
        status = _solve(u, rho, ph, start, basis, z0, dz0, virgin, ev_t, ev_d, w, False)
    return status == 1


@njit(cache=True, fastmath=False, nogil=True)
def _solve(u: np.ndarray, rho: float, ph: float, start: int, basis: np.ndarray,
           z0: np.ndarray, dz0: np.ndarray, virgin: bool, ev_t: np.ndarray, ev_d: np.ndarray,
           w: np.ndarray, early: bool) -> int:
    """:func:`_periodic_state`, the history cut short if ``early``. Returns 1 on success,
    0 if not converged, 2 if cut short and the history turned out to be wanted."""
    h = basis.shape[1]
    scale = ph / min(1.0, rho) + abs(u[start, 0]) + abs(u[start, 1])  # slips along y: ph / rho
    hist = 0  # events recorded by the history passes
    newton = False
    res0 = 0.0
    ratio0 = 0.0
    for cycle in range(MAX_PASSES):
        zx, zy, p00, p01, p10, p11, count = _pass(u, rho, ph, start, virgin, z0[0], z0[1],
                                                  ev_t, ev_d, hist)
        rx, ry = zx - z0[0], zy - z0[1]
        a00, a01, a10, a11 = 1.0 - p00, -p01, -p10, 1.0 - p11
        det = a00 * a11 - a01 * a10
        res = abs(rx) + abs(ry)
        done = res <= 1e-15 * scale
        if (cycle < CYCLES and not newton) or (done and abs(det) < 1e-12):
            z0[0], z0[1] = zx, zy
            hist = count
            if done:
                if newton:
                    return 2
                _history_derivative(ev_t, ev_d, count, basis, w, dz0)
                return 1
            ratio = res / res0 if res0 > 0.0 else 0.0
            if (early and abs(det) > 1e-8 and 0.0 < ratio < 1.0
                    and abs(ratio - ratio0) <= 0.1 * ratio
                    and res * ratio ** (CYCLES - 1 - cycle) > 1e3 * 1e-15 * scale):
                newton = True  # it will not repeat within CYCLES: Newton's method now
            res0 = res
            ratio0 = ratio
            continue
        if done:
            q = np.zeros((2, 2 * h))
            for i in range(hist, count):
                t = ev_t[i]
                if t < 0:  # the virgin state restarts Q
                    t = -1 - t
                    q[:, :] = 0.0
                _advance(q, ev_d[i, 0], ev_d[i, 1], ev_d[i, 2], ev_d[i, 3], basis, t, h)
            for c in range(2 * h):
                dz0[0, c] = (a11 * q[0, c] - a01 * q[1, c]) / det
                dz0[1, c] = (-a10 * q[0, c] + a00 * q[1, c]) / det
            return 1
        if abs(det) > 1e-8:
            z0[0] += (a11 * rx - a01 * ry) / det
            z0[1] += (-a10 * rx + a00 * ry) / det
        else:
            z0[0], z0[1] = zx, zy
    return 2 if newton else 0


@njit(cache=True, fastmath=False, nogil=True)
def circular_periodic_kernel(u: np.ndarray, k: np.ndarray, ky: np.ndarray, phi: np.ndarray,
                             start: int, basis: np.ndarray, f: np.ndarray, jb: np.ndarray
                             ) -> int:
    """Closed periodic force ``f`` (N, (N, 2)) of a set of 2-D Jenkins elements (stiffness
    ``k`` along x and ``ky`` along y, N/mm, slip displacement ``phi`` along x, mm) under the
    displacement samples ``u`` (mm, (N, 2)), and ``jb[t, a, b, c] = d f_t,a / d C_b,c``
    (N/mm) with ``u_b(t) = sum_c basis[t, c] C_b,c``; both added into. Returns the number
    of elements whose periodic state did not converge (0 on success).

    Notes
    -----
    Each element starts from the virgin loading to the sample ``start`` of largest |u| (the
    1-D operator's start; one return-map step from z = 0, radial for an isotropic element),
    then its periodic state is found by :func:`_periodic_state`. The force pass keeps
    ``G_e = dz_e/dC`` by the recursion ``G <- D G + (I - D) E_t`` at slipping samples and
    the sums ``S_a = sum_e K_e,a G_e,a`` (row a weighted by the stiffness along a), so that
    ``jb[t]_ab = (sum_e K_e,a) delta_ab E_t - S_a,b`` costs O(columns) per sample plus
    O(columns) per slip. Elements of zero stiffness carry no force and are skipped.
    """
    n = u.shape[0]
    m = k.size
    h = basis.shape[1]
    ux0, uy0 = u[start, 0], u[start, 1]
    z = np.zeros((m, 2))
    g = np.zeros((m, 2, 2 * h))
    rho = np.zeros(m)
    virgin = np.zeros(m, dtype=np.bool_)
    ev_t = np.empty((CYCLES + 1) * n, dtype=np.int64)
    ev_d = np.empty(((CYCLES + 1) * n, 4))
    w = np.empty((n, 2, 2))
    failed = 0
    for e in range(m):
        if k[e] == 0.0:
            continue
        rho[e] = ky[e] / k[e]
        virgin[e] = math.hypot(ux0, rho[e] * uy0) > phi[e]
        if virgin[e]:
            z[e, 0], z[e, 1] = return_map(ux0, uy0, 0.0, 0.0, rho[e], phi[e])
        if not _periodic_state(u, rho[e], phi[e], start, basis, z[e], g[e], virgin[e], ev_t,
                               ev_d, w):
            failed += 1
    tx = 0.0
    ty = 0.0
    s = np.zeros((2, 2 * h))
    for e in range(m):
        tx += k[e]
        ty += ky[e]
        for c in range(2 * h):
            s[0, c] += k[e] * g[e, 0, c]
            s[1, c] += ky[e] * g[e, 1, c]
    for j in range(n):
        t = start + j
        if t >= n:
            t -= n
        ux, uy = u[t, 0], u[t, 1]
        fx = 0.0
        fy = 0.0
        for e in range(m):
            if k[e] == 0.0:
                continue
            zx, zy = z[e, 0], z[e, 1]
            kind = _slips(math.hypot(ux - zx, rho[e] * (uy - zy)), phi[e], j == 0, virgin[e])
            if kind:
                ge = g[e]
                for c in range(2 * h):
                    s[0, c] -= k[e] * ge[0, c]
                    s[1, c] -= ky[e] * ge[1, c]
                if kind == 2:
                    ge[:, :] = 0.0
                    d00, d01, d10, d11 = _slip_map(ux, uy, 0.0, 0.0, rho[e], phi[e])[2:]
                else:
                    zx, zy, d00, d01, d10, d11 = _slip_map(ux, uy, zx, zy, rho[e], phi[e])
                    z[e, 0], z[e, 1] = zx, zy
                _advance(ge, d00, d01, d10, d11, basis, t, h)
                for c in range(2 * h):
                    s[0, c] += k[e] * ge[0, c]
                    s[1, c] += ky[e] * ge[1, c]
            fx += k[e] * (ux - zx)
            fy += ky[e] * (uy - zy)
        f[t, 0] += fx
        f[t, 1] += fy
        for c in range(h):
            bt = basis[t, c]
            jb[t, 0, 0, c] += tx * bt - s[0, c]
            jb[t, 0, 1, c] -= s[0, h + c]
            jb[t, 1, 0, c] -= s[1, c]
            jb[t, 1, 1, c] += ty * bt - s[1, h + c]
    return failed
