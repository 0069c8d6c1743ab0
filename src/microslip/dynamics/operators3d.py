"""The 3-D contact element of a contact node with ``penalty`` normal contact: a normal
penalty spring with lift-off and a 2-D Jenkins element whose circular Coulomb limit mu N(t)
follows the normal force (issue 23, item 3).

Node's displacement from the clamped state ``u = (u_1, u_2, u_n)`` (mm; u_n along the
body's inward normal, positive away from the base), preload N_0 (N, the clamping step's
normal force):

* normal: ``N(t) = max(0, N_0 - k_n u_n)``; the restoring force on the node is
  ``f_n = N_c - N`` with ``N_c = max(0, N_0)`` the clamped normal force: ``min(k_n u_n, N_0)``
  for a closed node (the penalty spring, lost at lift-off);
* open state: a node the clamping step left lifted off has a *signed* preload
  ``N_0 = -k_n g_0 <= 0`` (g_0 its gap, mm); it carries nothing (``f = 0``, its slider
  follows it) until ``k_n u_n`` closes the gap, then presses with ``N(t)`` as any node;
* tangential: slider w (2-D), the contact law of :mod:`microslip.contactlaw` with the
  limit mu N: trial ``f* = k_t (u_t - w)``; ``|f*| <= mu N``: stick, ``f_t = f*``; else
  slip along f*, ``f_t = mu N f* / |f*|``, ``w = u_t - f_t / k_t``; lifted off (N = 0):
  ``f_t = 0``, ``w = u_t``.

The same element as the built-in FE's contact node (:mod:`microslip.fe.builtin.contact`,
:mod:`~microslip.fe.builtin.normal`: stick slope x area, k_n A_i) and as the 3-D friction
elements of tmdsimpy and pyHarm (a penalty normal with a slider whose limit follows the
normal load; REFERENCES.md). Its periodic steady state for harmonic balance (AFT) is the
slider history after repeating the period until it closes, with the Jacobian of the force
samples with respect to the displacement's harmonic coefficients propagated through the
same steps (exact for the return map, checked against finite differences).

The clamping step leaves a tangential stick force t0 in many nodes (up to half of mu N_0 on
the cantilever at nu = 0.33); with a constant normal force it shakes down in the first slip,
but with N(t) varying it does not, so the element starts its cycles from it
(``stick_force``) and returns the force counted from it.

Units: displacement mm, force N, stiffness N/mm.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit
from numpy.typing import NDArray

from ..contactlaw import get_contact_law
from ..errors import ParameterError
from ..named import result
from ..params import check_positive

__all__ = ["Contact3D"]

Array = NDArray[np.float64]

#: The tangential law (:mod:`microslip.contactlaw`), compiled for the element's kernel.
_law = njit(cache=True, nogil=True)(get_contact_law("coulomb").return_map)

#: Periods repeated at most until the slider's state at the period's start repeats; a
#: slider that walks (normal and tangential motion out of phase can ratchet it, or its 2-D
#: memory fades slowly) gives the last of them, as a fixed-count AFT does.
MAX_PERIODS = 20
#: The state repeats when it moves by less than this times the slip displacement mu N0/k_t.
CLOSED = 1e-12


@njit(cache=True, nogil=True)
def _periodic(u: Array, basis: Array, kt: float, kn: float, n0: float, mu: float,
              t0: Array, f: Array, jb: Array) -> int:  # pragma: no cover - compiled
    """Force samples f (N, 3) and d f_t,a / d C_b,c (N, 3, 3, m) of the closed cycle, the
    tangential force counted from the clamped stick force t0 (2,); returns the periods run
    (-1: the state did not repeat; the last period is given)."""
    n, m = basis.shape
    w = np.zeros(2)
    w[0], w[1] = -t0[0] / kt, -t0[1] / kt  # the clamped slider: k_t (0 - w) = t0
    dw = np.zeros((2, 3, m))
    tol = CLOSED * mu * abs(n0) / kt
    nc = max(n0, 0.0)  # the clamped normal force (0: open after clamping)
    for period in range(MAX_PERIODS):
        w_start = w.copy()
        for t in range(n):
            un = u[t, 2]
            normal = n0 - kn * un
            f[t, :] = 0.0
            jb[t] = 0.0
            if normal <= 0.0:  # lifted off
                f[t, 2] = nc
                w[0], w[1] = u[t, 0], u[t, 1]
                dw[:] = 0.0
                for a in range(2):
                    for c in range(m):
                        dw[a, a, c] = basis[t, c]
                continue
            f[t, 2] = nc - normal  # k_n u_n when closed after clamping
            for c in range(m):
                jb[t, 2, 2, c] = kn * basis[t, c]
            # the law at the trial force, then its derivative through the chain rule
            fx, fy, wx, wy, txx, txy, tyy, e0, e1, slipping = _law(
                u[t, 0], u[t, 1], w[0], w[1], kt, mu * normal)
            f[t, 0], f[t, 1] = fx, fy
            for b in range(3):
                for c in range(m):
                    # dg = d(u_t - w) in the coefficients; df = T dg + slipping n dlimit
                    dg0 = -dw[0, b, c]
                    dg1 = -dw[1, b, c]
                    if b == 0:
                        dg0 += basis[t, c]
                    elif b == 1:
                        dg1 += basis[t, c]
                    dlimit = -mu * kn * basis[t, c] * slipping if b == 2 else 0.0
                    jb[t, 0, b, c] = txx * dg0 + txy * dg1 + dlimit * e0
                    jb[t, 1, b, c] = txy * dg0 + tyy * dg1 + dlimit * e1
            if slipping == 0.0:
                continue
            # slip: w = u_t - f_t / k_t
            w[0], w[1] = wx, wy
            for b in range(3):
                for c in range(m):
                    dw[0, b, c] = -jb[t, 0, b, c] / kt
                    dw[1, b, c] = -jb[t, 1, b, c] / kt
            dw[0, 0, :] += basis[t, :]
            dw[1, 1, :] += basis[t, :]
        if period > 0 and abs(w[0] - w_start[0]) <= tol and abs(w[1] - w_start[1]) <= tol:
            _from_clamped(f, t0)
            return period + 1
    _from_clamped(f, t0)
    return -1


@njit(cache=True, nogil=True)
def _from_clamped(f: Array, t0: Array) -> None:  # pragma: no cover - compiled
    """The tangential forces as changes from the clamped stick force (the structure's
    equations are about the clamped equilibrium, which t0 is part of)."""
    for t in range(f.shape[0]):
        f[t, 0] -= t0[0]
        f[t, 1] -= t0[1]


@result
class Contact3D:
    """A contact node's 3-D element: normal penalty with lift-off, circular Coulomb limit
    mu N(t) on a tangential Jenkins slider.

    Parameters
    ----------
    tangential_stiffness : float
        k_t = lambda A_i, N/mm.
    normal_stiffness : float
        k_n = k_n A_i, N/mm.
    preload : float
        N_0, N: the clamping step's normal force (> 0, closed), or minus the normal stiffness
        times the gap of a node the clamping lifted off (<= 0, open: no stuck stiffness, no
        force until the gap closes).
    friction : float
        mu.
    stick_force : tuple of 2 floats
        The tangential force (N, along the node's e1, e2) the clamping step leaves in the
        slider, |t0| <= mu N_0 (default none). With a varying normal force it does not shake
        down (the limit mu N(t) moves under it), so the cycles start from it; the force the
        element returns is counted from it.
    """

    tangential_stiffness: float
    normal_stiffness: float
    preload: float
    friction: float
    stick_force: tuple[float, float] = (0.0, 0.0)

    def __post_init__(self) -> None:
        check_positive("tangential stiffness", self.tangential_stiffness, "N/mm")
        check_positive("normal stiffness", self.normal_stiffness, "N/mm")
        if not (isinstance(self.preload, (int, float, np.floating, np.integer))
                and math.isfinite(float(self.preload))):
            raise ParameterError(f"preload must be a finite number (N; <= 0: open), got "
                                 f"{self.preload!r}")
        check_positive("friction", self.friction)
        t0 = np.asarray(self.stick_force, dtype=float)
        if t0.shape != (2,) or not np.all(np.isfinite(t0)):
            raise ParameterError(f"stick force must be two finite numbers (N), got "
                                 f"{self.stick_force!r}")
        limit = self.friction * max(float(self.preload), 0.0)
        if float(np.hypot(*t0)) > limit * (1.0 + 1e-9):
            raise ParameterError(f"stick force {float(np.hypot(*t0)):.6g} N exceeds the "
                                 f"friction limit mu N_0 = {limit:.6g} N")
        object.__setattr__(self, "stick_force", (float(t0[0]), float(t0[1])))

    #: Relative displacement components the element takes (tangential 1, 2 and normal).
    directions = 3

    @property
    def closed(self) -> bool:
        """Pressed on the base in the clamped state (preload > 0)."""
        return bool(self.preload > 0.0)

    @property
    def stuck_stiffness(self) -> Array:
        """diag(k_t, k_t, k_n), N/mm: the slope from the clamped state; zero when open."""
        if not self.closed:
            return np.zeros((3, 3))
        k = self.tangential_stiffness
        return np.diag([k, k, self.normal_stiffness])

    def periodic_force_projected(self, u: Array, basis: Array) -> tuple[Array, Array]:
        """Closed periodic force (N, (N, 3)) at the displacement samples ``u`` (mm, (N, 3))
        and ``jb[t, a, b, c] = d f_t,a / d C_b,c`` (N/mm, (N, 3, 3, m)) for
        ``u[:, b] = basis @ C_b`` (``basis`` (N, m))."""
        u = np.ascontiguousarray(u, dtype=np.float64)
        basis = np.ascontiguousarray(basis, dtype=np.float64)
        if u.ndim != 2 or u.shape[1] != 3 or u.shape[0] == 0 or not np.all(np.isfinite(u)):
            raise ParameterError(f"3-D displacement samples must be finite of shape (N, 3), "
                                 f"got {u.shape}")
        if basis.ndim != 2 or basis.shape[0] != u.shape[0]:
            raise ParameterError(f"basis must have shape ({u.shape[0]}, m), got {basis.shape}")
        f = np.zeros(u.shape)
        jb = np.zeros((u.shape[0], 3, 3, basis.shape[1]))
        _periodic(u, basis, float(self.tangential_stiffness), float(self.normal_stiffness),
                  float(self.preload), float(self.friction),
                  np.asarray(self.stick_force, dtype=np.float64), f, jb)
        return f, jb

    def periodic_force(self, u: Array) -> Array:
        """Closed periodic force (N, (N, 3)) at the displacement samples ``u`` (mm, (N, 3))."""
        return self.periodic_force_projected(u, np.zeros((np.shape(u)[0], 1)))[0]
