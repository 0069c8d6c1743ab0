"""The clamping step of a curved contact face under ``fixed`` normal contact, on the body
condensed onto the contact nodes that may touch (issue 33: Hertz-Mindlin).

A curved face (a paraboloid: Hertz's contact) touches the rigid base in a small patch, and
``fixed`` normal contact finds that patch by an active set: the nodes that touch are held at
u_n = -g_0, those below the base are pressed back, those in tension released, pass after
pass (:func:`~.meshmodel.build_mesh_model`). Done on the whole body, every pass refactorises
the whole stiffness several times (the frictional clamping's Newton): on the 40k-DOF Hertz
block with SuperLU, more than ten minutes. Here

* the *candidates* are the contact nodes of the smallest gaps (at first those within 1.25
  times the Hertz radius of the face's fitted curvature, :func:`likely_contact`, at least
  :data:`MIN_CANDIDATES`); every other dof is the interior I, factorised once
  (banded Cholesky, or SuperLU with the symmetric minimum-degree ordering), and the body is
  condensed onto the candidates' three dofs, S = K_cc - K_cI K_II^-1 K_Ic (dense; with
  SuperLU, the trailing block of one more factorisation in K_II's order with the candidates
  last, :func:`_trailing_schur`, instead of a solve per candidate dof);
* the active-set passes and the frictional clamping run on S (dense Cholesky of a few
  hundred dofs);
* the interior is recovered, u_I = K_II^-1 (f_I - K_Ic u_c); a contact node outside the
  candidates below the base doubles the candidates and the step starts again (the interior
  refactorised);
* the tangential loading is condensed onto the x, y dofs of the nodes that press only
  (:class:`~.condense.Reduced` with ``active``): the open nodes carry no force under
  ``fixed`` normal contact (mu N_i = 0), so they are free surface, part of the interior. Its
  solver is the nested one: K_II's factor and the dense block of the released candidates.

Everything is exact up to rounding: the same equations as the passes on the whole body.
Units: N, mm.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
import scipy.linalg as sla
import scipy.sparse as sp
import scipy.sparse.linalg as spla
from numpy.typing import NDArray

from ...blas import single_threaded_blas
from ...errors import ParameterError
from .condense import DenseBackend, Reduced, _Interior
from .model import NewtonOptions
from .solve import clamping_step, contact_partition

__all__ = ["MIN_CANDIDATES", "CurvedClamp", "curved_clamping", "likely_contact"]

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.int64]
BoolArray = NDArray[np.bool_]

#: Fewest contact nodes condensed for the active set (the face's smallest gaps).
MIN_CANDIDATES = 64
#: Columns of K_II^-1 K_Ic solved at once (SuperLU; bounds the dense block's memory).
CHUNK = 256


class _Nested:
    """K_{i'i'}^-1 for the interior i' = I + r (r: condensed dofs eliminated again), with
    K_II's factor and the dense Schur block S_rr = K_rr - K_rI K_II^-1 K_Ir:
    y = K_II^-1 b_I, x_r = S_rr^-1 (b_r - K_rI y), x_I = y - K_II^-1 K_Ir x_r.
    ``at_i``, ``at_r``: positions of I's and r's dofs in the interior vector."""

    def __init__(self, inner: _Interior, k_ir: sp.csr_matrix, s_rr: FloatArray,
                 at_i: IntArray, at_r: IntArray) -> None:
        self.inner, self.k_ir, self.k_ri = inner, k_ir, k_ir.T.tocsr()
        self.at_i, self.at_r = at_i, at_r
        self.fac = sla.cho_factor(s_rr, lower=True) if s_rr.size else None
        self.band = inner.band
        self.lu = inner.lu

    def solve(self, rhs: FloatArray) -> FloatArray:
        b = np.asarray(rhs, dtype=float)
        y = self.inner.solve(b[self.at_i])
        out = np.empty_like(b)
        if self.fac is None:
            out[self.at_i] = y
            return out
        x_r = sla.cho_solve(self.fac, b[self.at_r] - np.asarray(self.k_ri @ y),
                            check_finite=False)
        out[self.at_i] = y - self.inner.solve(np.asarray(self.k_ir @ x_r))
        out[self.at_r] = x_r
        return out


@dataclass(frozen=True, eq=False)
class CurvedClamp:
    """What :func:`curved_clamping` gives :func:`~.meshmodel.build_mesh_model`: the final
    partition (``released``: the contact nodes off the base), the clamping step's answer on
    the free dofs, and the tangential loading's condensed body."""

    released: BoolArray
    free: IntArray
    index: IntArray
    stiffness: sp.csr_matrix
    contact_dofs: IntArray
    contact_stiffness: FloatArray
    clamp_load: FloatArray
    normal: FloatArray
    limit: FloatArray
    u: FloatArray
    slip: FloatArray
    iterations: int
    reduced: Reduced
    passes: int
    candidates: int


def _trailing_schur(k: sp.csr_matrix, keep: IntArray, interior: IntArray, inner: _Interior
                    ) -> FloatArray | None:
    """S from one more factorisation: the whole matrix ordered as K_II's factor (its
    minimum-degree permutation) with the kept dofs last, factorised in that order with
    diagonal pivots (K = L U), has S = L_kk U_kk (K_kI K_II^-1 K_Ik = L_kI U_Ik). On the
    30k-DOF Hertz test block with 1371 kept dofs: 16 s and 3e-15 from the solves'
    K_kI K_II^-1 K_Ik, which take 150 s. None if SuperLU permuted after all."""
    order = np.concatenate([interior[np.argsort(inner.lu.perm_c)], keep])
    a = k[order][:, order].tocsc()
    try:
        lu = spla.splu(a, permc_spec="NATURAL", diag_pivot_thresh=0.0,
                       options={"SymmetricMode": True})
    except RuntimeError:
        return None
    n = order.size
    if not (np.array_equal(lu.perm_c, np.arange(n)) and np.array_equal(lu.perm_r, np.arange(n))):
        return None
    m = interior.size
    low = lu.L.tocsc()[m:, m:].toarray()
    up = lu.U.tocsc()[m:, m:].toarray()
    del lu
    return np.asarray(low @ up)


def _condense(k: sp.csr_matrix, keep: IntArray, interior: IntArray, band_limit: int
              ) -> tuple[_Interior, FloatArray, sp.csr_matrix]:
    """K_II factorised, S = K_kk - K_kI K_II^-1 K_Ik (dense) and K_Ik."""
    k_ii = k[interior][:, interior].tocsr()
    k_ik = k[interior][:, keep].tocsr()
    inner = _Interior(k_ii, band_limit)
    if inner.band is not None:
        s = k[keep][:, keep].toarray() - inner.schur(k_ik)
    else:
        trailing = _trailing_schur(k, keep, interior, inner)
        if trailing is not None:
            s = trailing
        else:  # solves, a block of columns at a time
            s = k[keep][:, keep].toarray()
            for j in range(0, keep.size, CHUNK):
                cols = k_ik[:, j:j + CHUNK].toarray()
                s[:, j:j + CHUNK] -= np.asarray(k_ik.T @ inner.solve(cols))
    return inner, 0.5 * (s + s.T), k_ik


def likely_contact(xy: FloatArray, gap: FloatArray, e_star: float, force: float) -> int:
    """How many contact nodes (of the smallest gaps) Hertz's contact of the face would
    cover, with a margin: the gap fitted as r^2 / (2 R) about the touching nodes, a =
    (3 F R / (4 E*))^(1/3), the nodes within 1.25 a. A guess only (it sizes the first
    condensation; a node outside it that sinks enlarges it)."""
    touching = gap <= 0.0
    centre = xy[touching].mean(axis=0) if np.any(touching) else xy[np.argmin(gap)]
    r2 = np.sum((xy - centre) ** 2, axis=1)
    c = float(r2 @ gap) / float(r2 @ r2) if float(r2 @ r2) > 0.0 else 0.0
    if not (c > 0.0 and e_star > 0.0 and force > 0.0):
        return 0
    radius = 1.0 / (2.0 * c)
    a = (3.0 * force * radius / (4.0 * e_star)) ** (1.0 / 3.0)
    return int(np.count_nonzero(r2 <= (1.25 * a) ** 2))


def curved_clamping(k_all: sp.csr_matrix, contact: IntArray, area: FloatArray,
                    gap: FloatArray, supports: IntArray | None, full: FloatArray,
                    stick_slope: float, normal_slope: float, friction: float,
                    normal_force: float, newton: NewtonOptions, band_limit: int,
                    source: str, max_passes: int, guess: int = 0) -> CurvedClamp:
    """The clamping step of a curved face on the rigid base, ``fixed`` normal contact (see
    the module docstring). ``contact``: model nodes of the face (their areas ``area``, their
    gaps ``gap``, mm); ``full``: the preloads on every model dof; ``supports``: held dofs;
    ``guess``: how many nodes of the smallest gaps to condense first
    (:func:`likely_contact`; at least :data:`MIN_CANDIDATES`, else an eighth of the face)."""
    n_all = k_all.shape[0]
    n_c = contact.size
    base = np.ones(n_all, dtype=bool)
    if supports is not None:
        base[supports] = False
    by_gap = np.argsort(gap, kind="stable")
    count = min(n_c, max(MIN_CANDIDATES, guess if guess > 0 else n_c // 8))
    touching = gap <= 0.0
    count = max(count, int(np.count_nonzero(touching)))
    while True:
        cand = np.sort(by_gap[:count])
        cdof = (3 * contact[cand][:, None] + np.arange(3)).ravel()  # node-major x, y, z
        mask = base.copy()
        mask[cdof] = False
        interior = np.flatnonzero(mask).astype(np.int64)
        with single_threaded_blas():
            inner, s, k_ic = _condense(k_all, cdof, interior, band_limit)
        f_i = full[interior]
        w = inner.solve(f_i)
        f_c = full[cdof] - np.asarray(k_ic.T @ w)
        s_sp = sp.csr_matrix(s)
        g_c = gap[cand]
        released = g_c > 0.0
        local = np.arange(cand.size, dtype=np.int64)
        passes = 0
        for _ in range(max_passes):
            passes += 1
            free, index, _, k_rf, cdofs, kc, _ = contact_partition(
                s_sp, local, area[cand], stick_slope, normal_slope, False, released)
            k_d = s[np.ix_(free, free)]
            held = 3 * local[~released] + 2
            g_h = g_c[~released]
            clamp = f_c[free] + np.asarray(k_rf.T @ g_h)
            clamp_fixed = f_c[held] + s[np.ix_(held, held)] @ g_h
            backend = DenseBackend(k_d, cdofs[:, 0], cdofs[:, 1])
            normal, _, u, resp, iters = clamping_step(
                k_d, k_rf, backend, cdofs, kc, None, clamp, newton, friction, normal_force,
                clamp_fixed, released, settle_first=True)
            below = np.zeros(cand.size, dtype=bool)
            below[released] = u[index[3 * local[released] + 2]] + g_c[released] < 0.0
            new = (released | ((normal <= 0.0) & ~released)) & ~below
            if np.array_equal(new, released):
                break
            if np.all(new):
                raise ParameterError(f"{source}: the clamp pulls every contact node off the "
                                     "base: nothing holds the body")
            released = new
        else:
            raise ParameterError(f"{source}: the clamping step's contact state (which nodes "
                                 f"press, which lift off) did not settle in {max_passes} "
                                 "passes")
        u_c = np.zeros(cdof.size)
        u_c[free] = u
        u_c[held] = -g_h
        u_full = np.zeros(n_all)
        u_full[cdof] = u_c
        u_full[interior] = w - inner.solve(np.asarray(k_ic @ u_c))
        others = np.setdiff1d(np.arange(n_c), cand)
        sunk = u_full[3 * contact[others] + 2] + gap[others] < 0.0
        if not np.any(sunk):
            break
        if count >= n_c:  # cannot happen: every node a candidate has no outsider
            raise ParameterError(f"{source}: the clamping step's active set failed")
        # the nodes sunk so far, and as many again
        count = min(n_c, max(2 * count, 2 * int(np.searchsorted(
            np.sort(gap), float(np.max(gap[others][sunk])), side="right"))))

    # the whole model's partition and state
    rel_all = np.ones(n_c, dtype=bool)
    rel_all[cand[~released]] = False
    free_a, index_a, k_ff_a, k_rf_a, cdofs_a, kc_a, _ = contact_partition(
        k_all, contact, area, stick_slope, normal_slope, False, rel_all, supports)
    g_held = gap[~rel_all]
    clamp_a = full[free_a] + np.asarray(k_rf_a.T @ g_held)
    normal_a = np.zeros(n_c)
    normal_a[cand] = normal
    slip_a = u_full[3 * contact[:, None] + np.arange(2)].copy()  # open: slip follows u
    slip_a[cand] = resp.slip
    u_a = u_full[free_a]
    reduced = _tangential(s, cdof, interior, inner, k_ic, cand, released, index_a, free_a,
                          cdofs_a, clamp_a, u_a, k_ff_a)
    return CurvedClamp(rel_all, free_a, index_a, k_ff_a, cdofs_a, kc_a, clamp_a, normal_a,
                       friction * normal_a, u_a, slip_a, iters, reduced, passes, int(count))


def _tangential(s: FloatArray, cdof: IntArray, interior: IntArray, inner: _Interior,
                k_ic: sp.csr_matrix, cand: IntArray, released: BoolArray, index_a: IntArray,
                free_a: IntArray, cdofs_a: IntArray, clamp_a: FloatArray, u_a: FloatArray,
                k_ff_a: sp.csr_matrix) -> Reduced:
    """The tangential loading's body, condensed onto the x, y dofs of the pressing nodes."""
    n_cand = cand.size
    comp = np.tile(np.arange(3), n_cand)
    node = np.repeat(np.arange(n_cand), 3)
    is_free = ~((comp == 2) & ~released[node])  # held z of the pressing nodes: not unknowns
    is_keep = (comp < 2) & ~released[node]
    k_loc = np.flatnonzero(is_keep)
    r_loc = np.flatnonzero(is_free & ~is_keep)
    s_kk = s[np.ix_(k_loc, k_loc)]
    if r_loc.size:
        s_rr = s[np.ix_(r_loc, r_loc)]
        s_kr = s[np.ix_(k_loc, r_loc)]
        s_final = s_kk - s_kr @ sla.cho_solve(sla.cho_factor(s_rr, lower=True), s_kr.T)
    else:
        s_rr = np.zeros((0, 0))
        s_final = s_kk
    s_final = 0.5 * (s_final + s_final.T)
    # positions in the whole model's free vector
    keep = index_a[cdof[k_loc]]
    order = np.argsort(keep)
    keep = keep[order]
    s_final = s_final[np.ix_(order, order)]
    mask = np.ones(free_a.size, dtype=bool)
    mask[keep] = False
    interior_a = np.flatnonzero(mask).astype(np.int64)
    pos_int = np.full(free_a.size, -1, dtype=np.int64)
    pos_int[interior_a] = np.arange(interior_a.size)
    at_i = pos_int[index_a[interior]]
    at_r = pos_int[index_a[cdof[r_loc]]]
    k_ir = k_ic[:, r_loc].tocsr()
    solver = _Nested(inner, k_ir, s_rr, at_i, at_r)
    k = k_ff_a.tocsr()
    k_ic_a = k[interior_a][:, keep].tocsr()
    k_ci_a = k[keep][:, interior_a].tocsr()
    pos = np.full(free_a.size, -1, dtype=np.int64)
    pos[keep] = np.arange(keep.size)
    active = np.flatnonzero(pos[cdofs_a[:, 0]] >= 0).astype(np.int64)
    cd = np.stack([pos[cdofs_a[active, 0]], pos[cdofs_a[active, 1]]], axis=1)
    backend = DenseBackend(s_final, cd[:, 0], cd[:, 1])
    clamp_i = clamp_a[interior_a]
    clamp_r = clamp_a[keep] - np.asarray(k_ci_a @ solver.solve(clamp_i))
    return Reduced(keep, interior_a, s_final, backend, cd, None, clamp_r, u_a[keep].copy(),
                   k_ic_a, k_ci_a, solver, clamp_i, active)  # type: ignore[arg-type]


def describe(c: CurvedClamp) -> dict[str, Any]:
    """Plain summary of the active set's cost."""
    return {"passes": c.passes, "candidates": c.candidates,
            "pressing": int(np.count_nonzero(~c.released))}
