"""Compiled kernels of the two-directional Iwan operator: parallel 2-D Jenkins elements with
circular slip limits (radial return).

Element e: an isotropic spring ``k[e]`` (N/mm) in series with a slider at ``z`` (mm, a
2-vector) that slips when the stretch ``r = |u - z|`` exceeds ``phi[e]`` (mm); its slip force
is ``k[e] phi[e]`` (N) in any direction. Force of the set: ``sum_e k[e] (u - z_e)``.

Notes
-----
Radial return (the exact return mapping of a circular Coulomb limit): with
``n = (u - z) / r``, ``z <- u - phi n`` if ``r > phi``. Its derivatives, with
``D = (phi / r) (I - n n^T)``: ``dz_new = (I - D) du + D dz``. Along one axis ``n = +-e_x``
exactly and the step is the 1-D return mapping of :mod:`.kernels`, bit for bit.
"""

from __future__ import annotations

import math

import numpy as np

from .kernels import njit

__all__ = ["circular_periodic_kernel", "radial_return"]

#: Passes at most of the per-element fixed-point (Newton) iteration for the periodic state.
MAX_PASSES = 200

#: Cycles repeated as the history would before Newton's method takes over.
CYCLES = 60


@njit(cache=True, fastmath=False, nogil=True)
def radial_return(ux: float, uy: float, zx: float, zy: float, ph: float
                  ) -> tuple[float, float, float, float, bool]:
    """New slider position (zx, zy), normal (nx, ny) and whether the element slipped."""
    dx = ux - zx
    dy = uy - zy
    r = math.hypot(dx, dy)
    if r > ph:
        nx = dx / r
        ny = dy / r
        return ux - ph * nx, uy - ph * ny, nx, ny, True
    return zx, zy, 0.0, 0.0, False


@njit(cache=True, fastmath=False, nogil=True)
def _project(ux: float, uy: float, zx: float, zy: float, ph: float) -> tuple[float, float]:
    """Slider on the limit circle: u - phi (u - z) / |u - z| (the radial return of a
    slipping element, also at r = phi)."""
    dx = ux - zx
    dy = uy - zy
    r = math.hypot(dx, dy)
    return ux - ph * (dx / r), uy - ph * (dy / r)


@njit(cache=True, fastmath=False, nogil=True)
def _slip_map(ux: float, uy: float, zx: float, zy: float, ph: float) -> np.ndarray:
    """D = (phi / r) (I - n n^T) at a slipping step from (zx, zy) to u."""
    dx = ux - zx
    dy = uy - zy
    r = math.hypot(dx, dy)
    nx = dx / r
    ny = dy / r
    s = ph / r
    d = np.empty((2, 2))
    d[0, 0] = s * (1.0 - nx * nx)
    d[0, 1] = -s * nx * ny
    d[1, 0] = d[0, 1]
    d[1, 1] = s * (1.0 - ny * ny)
    return d


@njit(cache=True, fastmath=False, nogil=True)
def _advance(g: np.ndarray, d: np.ndarray, basis: np.ndarray, t: int, h: int) -> None:
    """g <- D g + (I - D) E_t in place; g is (2, 2h), E_t[a, b h + c] = delta_ab basis[t, c]."""
    cols = g.shape[1]
    for c in range(cols):
        g0 = g[0, c]
        g1 = g[1, c]
        g[0, c] = d[0, 0] * g0 + d[0, 1] * g1
        g[1, c] = d[1, 0] * g0 + d[1, 1] * g1
    for c in range(h):
        bt = basis[t, c]
        g[0, c] += (1.0 - d[0, 0]) * bt
        g[1, c] -= d[1, 0] * bt
        g[0, h + c] -= d[0, 1] * bt
        g[1, h + c] += (1.0 - d[1, 1]) * bt


@njit(cache=True, fastmath=False, nogil=True)
def _slips(r: float, ph: float, first: bool, virgin: bool) -> int:
    """0: the element sticks; 1: it slips (r > phi); 2: it sits where the virgin radial
    loading to the start sample left it, at its limit (counted as slipping there, as in the
    1-D kernel, with the virgin state's derivative)."""
    if r > ph:
        return 1
    if first and virgin and r >= ph * (1.0 - 1e-14):
        return 2
    return 0


@njit(cache=True, fastmath=False, nogil=True)
def _virgin_map(ux: float, uy: float, ph: float) -> np.ndarray:
    """D of the virgin radial loading z = u (1 - phi / |u|): dz = (I - D) du."""
    return _slip_map(ux, uy, 0.0, 0.0, ph)


@njit(cache=True, fastmath=False, nogil=True)
def _periodic_state(u: np.ndarray, ph: float, start: int, basis: np.ndarray,
                    z0: np.ndarray, dz0: np.ndarray, virgin: bool) -> bool:
    """The element's periodic slider position before sample ``start`` (``z0``, updated in
    place from the virgin state) and its derivative ``dz0`` (2, 2h) in the coefficients.

    One pass G through the period has ``P = dG/dz0`` (the product of the slipping steps'
    D) and ``Q = dG/dC`` (the recursion of :func:`_advance` from 0). The first
    :data:`CYCLES` passes repeat the cycle as the history would (``z0 <- G(z0)``,
    ``dz0 <- P dz0 + Q``): an element that shakes down to elastic cycling keeps the state
    and derivative its history gave it. Then Newton's method on ``z0 = G(z0)``, and at the
    fixed point ``dz0 = (I - P)^-1 Q``. Returns False if not converged.
    """
    n = u.shape[0]
    h = basis.shape[1]
    scale = ph + abs(u[start, 0]) + abs(u[start, 1])
    q = np.zeros((2, 2 * h))
    for cycle in range(MAX_PASSES):
        zx, zy = z0[0], z0[1]
        p00, p01, p10, p11 = 1.0, 0.0, 0.0, 1.0
        q[:, :] = 0.0
        for j in range(n):
            t = start + j
            if t >= n:
                t -= n
            ux, uy = u[t, 0], u[t, 1]
            kind = _slips(math.hypot(ux - zx, uy - zy), ph, j == 0, virgin)
            if kind == 2:  # the virgin state: depends on u[start] only
                p00, p01, p10, p11 = 0.0, 0.0, 0.0, 0.0
                q[:, :] = 0.0
                _advance(q, _virgin_map(ux, uy, ph), basis, t, h)
            elif kind == 1:
                d = _slip_map(ux, uy, zx, zy, ph)
                p00, p01, p10, p11 = (d[0, 0] * p00 + d[0, 1] * p10,
                                      d[0, 0] * p01 + d[0, 1] * p11,
                                      d[1, 0] * p00 + d[1, 1] * p10,
                                      d[1, 0] * p01 + d[1, 1] * p11)
                _advance(q, d, basis, t, h)
                zx, zy = _project(ux, uy, zx, zy, ph)
        rx, ry = zx - z0[0], zy - z0[1]
        a00, a01, a10, a11 = 1.0 - p00, -p01, -p10, 1.0 - p11
        det = a00 * a11 - a01 * a10
        done = abs(rx) + abs(ry) <= 1e-15 * scale
        if cycle < CYCLES or (done and abs(det) < 1e-12):
            for c in range(2 * h):  # dz0 <- P dz0 + Q, the history's derivative
                d0, d1 = dz0[0, c], dz0[1, c]
                dz0[0, c] = p00 * d0 + p01 * d1 + q[0, c]
                dz0[1, c] = p10 * d0 + p11 * d1 + q[1, c]
            z0[0], z0[1] = zx, zy
            if done:
                return True
            continue
        if done:
            for c in range(2 * h):
                dz0[0, c] = (a11 * q[0, c] - a01 * q[1, c]) / det
                dz0[1, c] = (-a10 * q[0, c] + a00 * q[1, c]) / det
            return True
        if abs(det) > 1e-8:
            z0[0] += (a11 * rx - a01 * ry) / det
            z0[1] += (-a10 * rx + a00 * ry) / det
        else:
            z0[0], z0[1] = zx, zy
    return False


@njit(cache=True, fastmath=False, nogil=True)
def circular_periodic_kernel(u: np.ndarray, k: np.ndarray, phi: np.ndarray, start: int,
                             basis: np.ndarray, f: np.ndarray, jb: np.ndarray) -> int:
    """Closed periodic force ``f`` (N, (N, 2)) of a set of circular Jenkins elements under
    the displacement samples ``u`` (mm, (N, 2)), and ``jb[t, a, b, c] = d f_t,a / d C_b,c``
    (N/mm) with ``u_b(t) = sum_c basis[t, c] C_b,c``; both added into. Returns the number
    of elements whose periodic state did not converge (0 on success).

    Notes
    -----
    Each element starts from the virgin radial loading to the sample ``start`` of largest
    |u| (the 1-D operator's start), then its periodic state is found by
    :func:`_periodic_state`. The force pass keeps ``G_e = dz_e/dC`` by the recursion
    ``G <- D G + (I - D) E_t`` at slipping samples and the sum ``S = sum_e k_e G_e``, so that
    ``jb[t] = (sum_e k_e) E_t - S`` costs O(columns) per sample plus O(columns) per slip.
    """
    n = u.shape[0]
    m = k.size
    h = basis.shape[1]
    um = math.hypot(u[start, 0], u[start, 1])
    z = np.zeros((m, 2))
    g = np.zeros((m, 2, 2 * h))
    failed = 0
    for e in range(m):
        if um > phi[e]:
            z[e, 0] = u[start, 0] - phi[e] * (u[start, 0] / um)
            z[e, 1] = u[start, 1] - phi[e] * (u[start, 1] / um)
        if not _periodic_state(u, phi[e], start, basis, z[e], g[e], um > phi[e]):
            failed += 1
    total = 0.0
    s = np.zeros((2, 2 * h))
    for e in range(m):
        total += k[e]
        for a in range(2):
            for c in range(2 * h):
                s[a, c] += k[e] * g[e, a, c]
    for j in range(n):
        t = start + j
        if t >= n:
            t -= n
        ux, uy = u[t, 0], u[t, 1]
        fx = 0.0
        fy = 0.0
        for e in range(m):
            zx, zy = z[e, 0], z[e, 1]
            kind = _slips(math.hypot(ux - zx, uy - zy), phi[e], j == 0, um > phi[e])
            if kind:
                ge = g[e]
                for a in range(2):
                    for c in range(2 * h):
                        s[a, c] -= k[e] * ge[a, c]
                if kind == 2:
                    ge[:, :] = 0.0
                    d = _virgin_map(ux, uy, phi[e])
                else:
                    d = _slip_map(ux, uy, zx, zy, phi[e])
                _advance(ge, d, basis, t, h)
                for a in range(2):
                    for c in range(2 * h):
                        s[a, c] += k[e] * ge[a, c]
                zx, zy = _project(ux, uy, zx, zy, phi[e])
                z[e, 0], z[e, 1] = zx, zy
            fx += k[e] * (ux - zx)
            fy += k[e] * (uy - zy)
        f[t, 0] += fx
        f[t, 1] += fy
        for c in range(h):
            bt = basis[t, c]
            jb[t, 0, 0, c] += total * bt - s[0, c]
            jb[t, 0, 1, c] -= s[0, h + c]
            jb[t, 1, 0, c] -= s[1, c]
            jb[t, 1, 1, c] += total * bt - s[1, h + c]
    return failed
