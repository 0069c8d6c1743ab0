"""Static condensation of the elastic body onto its contact dofs (own-mesh solver, issue 22).

Only the contact nodes are nonlinear (friction, the penalty normal contact); the body is
linear. With the free dofs split into contact dofs c and the rest i,

    S = K_cc - K_ci K_ii^-1 K_ic,     f_r = f_c - K_ci K_ii^-1 f_i,

the tangential loading solves r_c(u_c) = f_r - S u_c - C^T tau(u_c) = 0 with the same
semi-smooth Newton (:class:`~microslip.fe.builtin.stepper._Stepper`) on a dense system of the
contact dofs only: every factorisation and solve then costs what the contact costs, not the
body. K_ii is factorised once (banded Cholesky; the contact nodes numbered last, so that
K_ii^-1 K_ic needs only the trailing rows: S = K_cc - W^T W with W = L^-1 K_ic); SuperLU when
the band is wide. A load's work-conjugate displacement p . u is linear in u_c and the loads,
p . u = a . u_c + b . f_i with b = K_ii^-1 p_i and a = p_c - K_ci b; the interior displacements
u_i = K_ii^-1 (f_i - K_ic u_c) are recovered only for a recorded field. Exact up to rounding.
Units: N, mm.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np
import scipy.linalg as sla
import scipy.sparse as sp
import scipy.sparse.linalg as spla
from numpy.typing import NDArray

from ...errors import ParameterError
from .linalg import _TBTRS, NOT_DEFINITE, SYMMETRIC_ORDERING
from .normal import PenaltyNormal

__all__ = ["DenseBackend", "Reduced", "condense"]

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.int64]


class _DenseFactor:
    def __init__(self, c: Any) -> None:
        self.c = c

    def solve(self, rhs: FloatArray) -> FloatArray:
        return np.asarray(sla.cho_solve(self.c, rhs, check_finite=False))


class DenseBackend:
    """Cholesky (LAPACK dpotrf) of the dense condensed tangent S + C(D)."""

    name = "condensed"

    def __init__(self, s: FloatArray, cx: IntArray, cy: IntArray,
                 cz: IntArray | None = None) -> None:
        self.s, self.cx, self.cy, self.cz = s, cx, cy, cz

    def factor(self, d: FloatArray) -> _DenseFactor:
        a = self.s.copy()
        cx, cy = self.cx, self.cy
        a[cx, cx] += d[:, 0]
        a[cx, cy] += d[:, 1]
        a[cy, cx] += d[:, 1]
        a[cy, cy] += d[:, 2]
        if d.shape[1] > 3 and self.cz is not None:
            a[self.cz, self.cz] += d[:, 3]
        # a is this factorisation's own copy: factorise it in place (one copy of S fewer)
        return _DenseFactor(sla.cho_factor(a, lower=True, overwrite_a=True,
                                           check_finite=False))


class _Interior:
    """K_ii factorised once: banded Cholesky when the band is narrow, SuperLU otherwise (with
    the minimum-degree ordering of K + K^T and SuperLU's symmetric mode, about twice as fast
    as its default COLAMD on a 40k-DOF hexahedral body)."""

    def __init__(self, k_ii: sp.csr_matrix, band_limit: int) -> None:
        coo = sp.tril(k_ii, format="coo")
        kd = int(np.max(coo.row - coo.col)) if coo.nnz else 0
        self.band: FloatArray | None = None
        self.lu: Any = None
        if kd <= band_limit:
            ab = np.zeros((kd + 1, k_ii.shape[0]), order="F")
            ab[coo.row - coo.col, coo.col] = coo.data
            try:
                self.band = np.asarray(sla.cholesky_banded(ab, lower=True, check_finite=False))
            except np.linalg.LinAlgError:
                raise ParameterError(NOT_DEFINITE) from None
        else:
            try:
                self.lu = spla.splu(k_ii.tocsc(), permc_spec=SYMMETRIC_ORDERING,
                                    options={"SymmetricMode": True})
            except RuntimeError:
                raise ParameterError("the stiffness is singular with the contact held: the "
                                     "contact does not hold the body") from None

    def solve(self, rhs: FloatArray) -> FloatArray:
        if self.band is not None:
            return np.asarray(sla.cho_solve_banded((self.band, True), rhs, check_finite=False))
        return np.asarray(self.lu.solve(rhs))

    def schur(self, k_ic: sp.csr_matrix) -> FloatArray:
        """K_ci K_ii^-1 K_ic (dense)."""
        if self.band is None:
            return np.asarray(k_ic.T @ self.lu.solve(k_ic.toarray()))
        rows = np.flatnonzero(np.diff(k_ic.indptr))
        r0 = int(rows[0]) if rows.size else k_ic.shape[0]
        b = np.asfortranarray(k_ic[r0:].toarray())
        w, info = _TBTRS(self.band[:, r0:], b, uplo="L", trans="N")
        if info:
            raise ParameterError(NOT_DEFINITE)
        return np.asarray(w.T @ w)


@dataclass(frozen=True, eq=False)
class Reduced:
    """The body condensed onto its contact dofs (see the module docstring).

    Attributes
    ----------
    keep : ndarray of int
        Free-dof positions of the contact dofs (x, y and, with penalty normal contact, z of
        each contact node), increasing.
    interior : ndarray of int
        Free-dof positions of the other dofs.
    stiffness : ndarray, shape (m, m)
        S, N/mm.
    backend : DenseBackend
    contact_dofs : ndarray of int, shape (n_c, 2)
        Positions of the contact x and y dofs in the reduced vector.
    normal : PenaltyNormal or None
        The penalty springs on the reduced z dofs.
    clamp_load : ndarray, shape (m,)
        Reduced clamping forces, N.
    u0 : ndarray, shape (m,)
        Reduced displacements after clamping, mm.
    active : ndarray of int or None
        The contact nodes (rows of the model's contact arrays) whose dofs are kept, in the
        order of ``contact_dofs``; None: every contact node. The others carry no force (open
        under ``fixed`` normal contact, :mod:`.curved`): they are part of the interior.
    """

    keep: IntArray = field(repr=False)
    interior: IntArray = field(repr=False)
    stiffness: FloatArray = field(repr=False)
    backend: DenseBackend = field(repr=False)
    contact_dofs: IntArray = field(repr=False)
    normal: PenaltyNormal | None
    clamp_load: FloatArray = field(repr=False)
    u0: FloatArray = field(repr=False)
    k_ic: sp.csr_matrix = field(repr=False)
    k_ci: sp.csr_matrix = field(repr=False)
    solver: _Interior = field(repr=False)
    clamp_interior: FloatArray = field(repr=False)
    active: IntArray | None = field(default=None, repr=False)

    def load(self, p: FloatArray) -> tuple[FloatArray, FloatArray, FloatArray]:
        """For a free-dof load vector p: the reduced load p_c - K_ci K_ii^-1 p_i, and (a, b)
        with p . u = a . u_c + b . f_i."""
        b = self.solver.solve(p[self.interior])
        kb = np.asarray(self.k_ci @ b)
        return p[self.keep] - kb, p[self.keep] - kb, b

    def expand(self, u_c: FloatArray, f_i: FloatArray) -> FloatArray:
        """The free-dof displacements of the reduced ones under the interior forces f_i, mm."""
        u = np.zeros(self.keep.size + self.interior.size)
        u[self.keep] = u_c
        u[self.interior] = self.solver.solve(f_i - np.asarray(self.k_ic @ u_c))
        return u


def condense(stiffness: sp.csr_matrix, contact_dofs: IntArray, normal: PenaltyNormal | None,
             clamp_load: FloatArray, u0: FloatArray, band_limit: int) -> Reduced:
    """Condense a clamped model's free dofs onto its contact dofs."""
    n = stiffness.shape[0]
    parts = [contact_dofs[:, 0], contact_dofs[:, 1]] + ([] if normal is None
                                                          else [normal.dofs])
    keep = np.sort(np.concatenate(parts)).astype(np.int64)
    mask = np.ones(n, dtype=bool)
    mask[keep] = False
    interior = np.flatnonzero(mask).astype(np.int64)
    pos = np.full(n, -1, dtype=np.int64)
    pos[keep] = np.arange(keep.size)
    k = stiffness.tocsr()
    k_ii = k[interior][:, interior].tocsr()
    k_ic = k[interior][:, keep].tocsr()
    k_ci = k[keep][:, interior].tocsr()
    solver = _Interior(k_ii, band_limit)
    s = k[keep][:, keep].toarray() - solver.schur(k_ic)
    s = 0.5 * (s + s.T)
    cdofs = np.stack([pos[contact_dofs[:, 0]], pos[contact_dofs[:, 1]]], axis=1)
    springs = (None if normal is None else
               PenaltyNormal(normal.stiffness, pos[normal.dofs], normal.slope, normal.gap))
    backend = DenseBackend(s, cdofs[:, 0], cdofs[:, 1],
                           None if springs is None else springs.dofs)
    clamp_i = clamp_load[interior]
    clamp_r = clamp_load[keep] - np.asarray(k_ci @ solver.solve(clamp_i))
    return Reduced(keep, interior, s, backend, cdofs, springs, clamp_r, u0[keep].copy(), k_ic,
                   k_ci, solver, clamp_i)
