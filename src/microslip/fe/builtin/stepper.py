"""One load increment of the frictional FE (:mod:`.solve`, :mod:`.meshrun`): semi-smooth
Newton on r(u) = f - K u - C^T tau(u) = 0 with the consistent friction tangent and a
backtracking line search (:class:`_Stepper`), the increment cut into sub-increments where
Newton fails (:func:`load_increment`), and the tipping check of unilateral normal contact
(:func:`runaway_reason`). Units: N, mm, N·mm.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
import scipy.sparse as sp
from numpy.typing import NDArray

from .contact import FrictionResponse, friction_dissipation, return_map
from .linalg import Backend
from .model import NewtonOptions
from .normal import PenaltyNormal

__all__ = ["Increment", "load_increment", "runaway_reason"]

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.int64]
BoolArray = NDArray[np.bool_]


class _Stepper:
    """Semi-smooth Newton with backtracking line search, one increment at a time.

    With ``reuse`` the last factorisation is kept while it still fits: it is reused (a chord
    step) as long as the set of slipping nodes is the one it was built with and the previous
    step cut the residual at least by ``1 / reuse_ratio``; the first step of an increment
    reuses the last factorisation of the increment before (a tangent predictor). Any other
    step refactorises the consistent tangent. The residual test alone decides convergence,
    so reuse changes the path to the solution, not the solution.
    """

    def __init__(self, k: sp.csr_matrix, backend: Backend, cdofs: IntArray, kc: FloatArray,
                 limit: FloatArray, newton: NewtonOptions, force_scale: float,
                 normal: PenaltyNormal | None = None, friction: float | None = None) -> None:
        self.k, self.backend, self.cdofs, self.kc, self.limit = k, backend, cdofs, kc, limit
        self.newton = newton
        self.normal = normal
        #: mu, when the limits follow the normal forces (lagged, see :mod:`.normal`)
        self.friction = friction
        self.tol = newton.rtol * force_scale
        self.factorisations = 0
        self.fac: Any = None
        self.fac_set: BoolArray | None = None
        #: the last solve met a tangent singular even when stiffened (:meth:`_factor`)
        self.singular = False
        self._u: FloatArray | None = None
        self._ku: FloatArray | None = None

    def _residual(self, f: FloatArray, ku: FloatArray, u: FloatArray, slip: FloatArray
                  ) -> tuple[FloatArray, FrictionResponse]:
        resp = return_map(u[self.cdofs], slip, self.kc, self.limit)
        r = f - ku
        r[self.cdofs[:, 0]] -= resp.force[:, 0]
        r[self.cdofs[:, 1]] -= resp.force[:, 1]
        if self.normal is not None:
            r[self.normal.dofs] += self.normal.forces(u)
        return r, resp

    def _state(self, resp: FrictionResponse, u: FloatArray) -> BoolArray:
        """What a factorisation depends on: the slipping nodes (and the closed ones)."""
        if self.normal is None:
            return resp.slipping
        return np.concatenate([resp.slipping, self.normal.closed(u)])

    def _relimit(self, u: FloatArray) -> bool:
        """Set the limits to mu N_i(u) (penalty normal contact); True if they changed by more
        than the tolerance."""
        if self.normal is None or self.friction is None:
            return False
        new = self.friction * self.normal.forces(u)
        changed = bool(np.max(np.abs(new - self.limit)) > self.tol)
        self.limit = new
        return changed

    def _factor(self, resp: FrictionResponse, u: FloatArray) -> bool:
        """Factor the consistent tangent at ``u``; False (``singular`` set) when it stays
        singular even with its null directions stiffened: no static equilibrium nearby (the
        body tips over on its unilateral contact)."""
        tangent = (resp.tangent if self.normal is None else
                   np.column_stack([resp.tangent, self.normal.tangent(u)]))
        try:
            self.fac = self.backend.factor(tangent)
        except np.linalg.LinAlgError:
            # Singular tangent (every slipping node free along its slip): stiffen the null
            # directions a little; the residual test keeps the answer exact.
            d = tangent.copy()
            d[:, 0] += 1e-6 * self.kc
            d[:, 2] += 1e-6 * self.kc
            try:
                self.fac = self.backend.factor(d)
            except np.linalg.LinAlgError:  # lifted off too: nothing holds the body
                self.fac, self.fac_set, self.singular = None, None, True
                return False
        self.fac_set = self._state(resp, u)
        self.factorisations += 1
        return True

    def solve(self, u: FloatArray, slip: FloatArray, f: FloatArray
              ) -> tuple[bool, int, FloatArray, FrictionResponse]:
        """Solve r(u) = 0 from the start ``u`` with the slip ``slip`` of the last increment."""
        nw = self.newton
        self.singular = False
        # K u of the start is kept from the last solve when the start is its answer.
        ku = self._ku if (u is self._u and self._ku is not None) else np.asarray(self.k @ u)
        u = u.copy()
        r, resp = self._residual(f, ku, u, slip)
        rn = float(np.max(np.abs(r)))
        fresh = False
        ratio = 0.0
        for it in range(1, nw.max_iterations + 1):
            if rn <= self.tol and self._relimit(u):
                r, resp = self._residual(f, ku, u, slip)
                rn = float(np.max(np.abs(r)))
            if rn <= self.tol:
                self._u, self._ku = u, ku
                return True, it - 1, u, resp
            reuse = (nw.reuse and self.fac is not None and ratio <= nw.reuse_ratio
                     and (it == 1 or not nw.same_set or (
                         self.fac_set is not None
                         and bool(np.array_equal(self._state(resp, u), self.fac_set)))))
            if not reuse and not self._factor(resp, u):
                return False, it - 1, u, resp
            fresh = not reuse
            du = self.fac.solve(r)
            kdu = np.asarray(self.k @ du)
            alpha = 1.0
            for _ in range(nw.max_halvings):
                u_try = u + alpha * du
                ku_try = ku + alpha * kdu
                r_try, resp_try = self._residual(f, ku_try, u_try, slip)
                rn_try = float(np.max(np.abs(r_try)))
                if rn_try <= (1.0 - nw.armijo * alpha) * rn or not fresh:
                    break  # accepted; or a stale tangent: refactorise, don't shorten
                alpha *= 0.5
            if not fresh and rn_try > (1.0 - nw.armijo) * rn:
                ratio = np.inf  # reject the chord step, refactorise at the same point
                continue
            ratio = rn_try / rn
            u, ku, r, resp, rn = u_try, ku_try, r_try, resp_try, rn_try
        return rn <= self.tol, nw.max_iterations, u, resp


@dataclass(frozen=True, eq=False)
class Increment:
    """The outcome of :func:`load_increment`: converged, Newton iterations (of every
    sub-increment), friction work (N·mm), the last contact response and the new state."""

    converged: bool
    iterations: int
    work: float
    response: FrictionResponse
    u: FloatArray
    slip: FloatArray


def load_increment(stepper: _Stepper, clamp: FloatArray, vectors: Sequence[FloatArray],
                   old: Sequence[float], new: Sequence[float], u0: FloatArray,
                   s0: FloatArray, max_cuts: int) -> Increment:
    """One increment of the loads ``f = clamp + sum_j F_j p_j`` from the forces ``old`` to
    ``new`` (N, one per unit load vector p_j), from the state ``(u0, s0)``.

    If Newton fails, the straight load segment is cut into 2, 4, ... ``max_cuts`` equal
    sub-increments, each time from ``(u0, s0)`` again.
    """
    cuts = 1
    total_its = 0
    while True:
        u, slip, work, ok, resp = u0, s0, 0.0, True, None
        for k in range(1, cuts + 1):
            a = k / cuts
            f = clamp
            for f0, f1, p in zip(old, new, vectors, strict=True):
                f = f + (f0 + a * (f1 - f0)) * p
            ok, it, u_new, resp = stepper.solve(u, slip, f)
            total_its += it
            if not ok:
                break
            work += friction_dissipation(resp.force, slip, resp.slip)
            u, slip = u_new, resp.slip
        if ok and resp is not None:
            return Increment(True, total_its, work, resp, u, slip)
        cuts *= 2
        if cuts > max_cuts:
            assert resp is not None
            return Increment(False, total_its, 0.0, resp, u0, s0)


def runaway_reason(normal: PenaltyNormal | None, u: FloatArray, size: float) -> str | None:
    """Why the state ``u`` is no static equilibrium, or None: with unilateral normal contact
    (``normal``) a body whose load moment exceeds the clamping's tips over, and the
    displacements run away (here: beyond 1 % of ``size``, the body's largest size, mm)."""
    if normal is None or float(np.max(np.abs(u))) <= 0.01 * size:
        return None
    return ("has no static equilibrium: the displacements exceed 1 % of the body's size "
            "(the block tips over on its unilateral contact)")
