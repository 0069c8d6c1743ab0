"""Factorising the tangent K + C(D): LAPACK banded Cholesky, or a sparse direct solver.

The elastic stiffness K of the free dofs is constant; only the 2 x 2 friction tangents D_i of
the contact nodes change from one Newton iteration to the next, and they sit on the diagonal
and the first off-diagonal (the x and y dofs of a contact node are neighbours in the
numbering). A backend therefore keeps K once and adds D for every factorisation. With
penalty normal contact (:mod:`~microslip.fe.builtin.normal`) the contact tangent has a fourth
column, the normal stiffness of each node on the diagonal of its u_z (the dof after u_y).

Backends (:data:`LINEAR_SOLVERS`):

``banded`` (default)
    K stored in LAPACK's lower band format; ``scipy.linalg.cholesky_banded`` (dpbtrf) and
    ``cho_solve_banded`` (dpbtrs). Cost ~ n b^2 per factorisation with b the half-bandwidth,
    which the slice-by-slice numbering keeps at about 3 (ny + 1)(nz + 1).
``splu``
    ``scipy.sparse.linalg.splu`` (SuperLU, COLAMD ordering), for comparison.
``cholmod``
    ``sksparse.cholmod`` (CHOLMOD supernodal Cholesky) when scikit-sparse is installed; the
    symbolic analysis is done once and reused.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any, Protocol

import numpy as np
import scipy.linalg as sla
import scipy.sparse as sp
import scipy.sparse.linalg as spla
from numpy.typing import NDArray

from ...errors import ParameterError

#: One line for a stiffness matrix that rounding makes indefinite.
NOT_DEFINITE = ("the finite-element stiffness matrix is not positive definite in double "
                "precision: the element aspect ratio or the contact stiffness against the "
                "body's is too extreme for this geometry and mesh; check the lengths (mm) and "
                "the modulus (MPa)")

__all__ = ["LINEAR_SOLVERS", "Factorisation", "available_linear_solvers", "make_backend"]

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.int64]


class Factorisation(Protocol):
    """A factorised tangent: ``solve(rhs) -> x``."""

    def solve(self, rhs: FloatArray) -> FloatArray: ...


class Backend(Protocol):
    """Keeps K; ``factor(d)`` factorises K + C(d) with the contact tangents d (n_c, 3)."""

    name: str

    def factor(self, d: FloatArray) -> Factorisation: ...


class _BandFactor:
    def __init__(self, cb: FloatArray) -> None:
        self.cb = cb

    def solve(self, rhs: FloatArray) -> FloatArray:
        return np.asarray(sla.cho_solve_banded((self.cb, True), rhs, check_finite=False))


_TBTRS = sla.get_lapack_funcs("tbtrs", dtype=np.float64)


class _PartialBandFactor:
    """Cholesky factor whose first m columns are those of a reference factor.

    A = [[A11, A12], [A21, A22]] with A11 = L11 L11^T taken from the reference; the trailing
    factor L22 is that of S = A22 - L21 L21^T, where L21 = B is the only non-zero block of the
    coupling (kd x kd, the band). Solving: L11 y1 = b1, S x2 = b2 - B y1, L11^T x1 = y1 - B^T x2.
    """

    def __init__(self, ref: FloatArray, m: int, b: FloatArray, l22: FloatArray) -> None:
        self.ref, self.m, self.b, self.l22 = ref, m, b, l22
        self.kd = ref.shape[0] - 1

    def solve(self, rhs: FloatArray) -> FloatArray:
        m, kd, b = self.m, self.kd, self.b
        lead = self.ref[:, :m]
        y1, info = _TBTRS(lead, rhs[:m], uplo="L", trans="N")
        r2 = np.array(rhs[m:], dtype=float)
        rk = b.shape[0]
        r2[:rk] -= b @ y1[m - kd:m]
        x2 = sla.cho_solve_banded((self.l22, True), r2, check_finite=False)
        z = np.array(y1, dtype=float)
        z[m - kd:m] -= b.T @ x2[:rk]
        x1, info2 = _TBTRS(lead, z, uplo="L", trans="T")
        if info or info2:
            raise np.linalg.LinAlgError("singular triangular factor")
        return np.concatenate([x1, x2])


class BandedBackend:
    """LAPACK banded Cholesky of K + C(D), refactorising only the trailing part that changed.

    With the stick stiffnesses ``kc`` given, the factor of the all-stick tangent K + C(kc I)
    is kept. A tangent equal to it up to dof m (every contact node before m sticks) keeps
    the first m columns of that factor, and only the trailing band from m on is factorised
    (cost ~ (n - m) b^2 instead of n b^2). The mesh is numbered from x = 0 towards the end
    face x = L carrying the tip load, so under tip loading the stuck part of the interface
    is the reused leading block.
    """

    name = "banded"

    def __init__(self, k: sp.csr_matrix, cx: IntArray, cy: IntArray,
                 kc: FloatArray | None = None, kn: FloatArray | None = None) -> None:
        if np.any(cy != cx + 1) or np.any(np.diff(cx) <= 0):
            raise ValueError("contact x and y dofs must be neighbours, in increasing order")
        coo = sp.tril(k, format="coo")
        kd = int(np.max(coo.row - coo.col)) if coo.nnz else 0
        ab = np.zeros((kd + 1, k.shape[0]), order="F")
        ab[coo.row - coo.col, coo.col] = coo.data  # LAPACK lower band storage
        self.ab, self.kd, self.cx, self.cy = ab, kd, cx, cy
        self.ref_d: FloatArray | None = None
        self.ref: FloatArray | None = None
        self.partial_factorisations = 0
        self.factorised_columns = 0
        if kc is not None and kd > 0:
            ref = [kc, np.zeros_like(kc), kc] + ([] if kn is None else [kn])
            self.ref_d = np.stack(ref, axis=1)
            self.ref = np.asfortranarray(self._full(self.ref_d))
            ii, jj = np.tril_indices(kd)
            self._tril = (ii - jj, jj, ii)

    @property
    def half_bandwidth(self) -> int:
        return self.kd

    def _band_with(self, d: FloatArray, first: int = 0, node0: int = 0) -> FloatArray:
        ab = np.array(self.ab[:, first:], order="F")
        cx = self.cx[node0:] - first
        ab[0, cx] += d[node0:, 0]
        ab[0, cx + 1] += d[node0:, 2]
        if d.shape[1] > 3:
            ab[0, cx + 2] += d[node0:, 3]
        if self.kd > 0:
            ab[1, cx] += d[node0:, 1]
        return ab

    def _full(self, d: FloatArray) -> FloatArray:
        self.factorised_columns += self.ab.shape[1]
        try:
            return np.asarray(sla.cholesky_banded(self._band_with(d), lower=True,
                                                  check_finite=False))
        except np.linalg.LinAlgError:
            raise ParameterError(NOT_DEFINITE) from None

    def factor(self, d: FloatArray) -> _BandFactor | _PartialBandFactor:
        if self.ref is None or self.ref_d is None:
            return _BandFactor(self._full(d))
        changed = np.flatnonzero(np.any(d != self.ref_d, axis=1))
        if changed.size == 0:
            return _BandFactor(self.ref)
        node0 = int(changed[0])
        m = int(self.cx[node0])
        kd, n = self.kd, self.ab.shape[1]
        if m < kd:
            return _BandFactor(self._full(d))
        ab = self._band_with(d, m, node0)
        rk = min(kd, n - m)
        # B = L[m:m+rk, m-kd:m] from the reference band (L[i, j] = ref[i - j, j], i - j <= kd).
        r = np.arange(rk)[:, None]
        c = np.arange(kd)[None, :]
        rows = kd + r - c
        b = np.where(rows <= kd, self.ref[np.minimum(rows, kd), m - kd + c], 0.0)
        bbt = b @ b.T
        di, dj, ii = self._tril
        keep = ii < rk
        ab[di[keep], dj[keep]] -= bbt[ii[keep], dj[keep]]
        self.partial_factorisations += 1
        self.factorised_columns += n - m
        l22 = sla.cholesky_banded(ab, lower=True, check_finite=False)
        return _PartialBandFactor(self.ref, m, b, l22)


#: SuperLU's column ordering for the symmetric stiffness: minimum degree on A^T + A with the
#: diagonal pivots preferred (SymmetricMode). On the 40k-DOF Hertz block it fills half as much
#: as the default COLAMD and factorises twice as fast (18 s against 37 s).
SYMMETRIC_ORDERING = "MMD_AT_PLUS_A"


class _SparseContactSum:
    """K + C(D) as CSC with a fixed sparsity pattern (the contact entries are in K's pattern)."""

    def __init__(self, k: sp.csr_matrix, cx: IntArray, cy: IntArray) -> None:
        # the contact entries as explicit entries of the pattern (zero where K has none: a
        # node's x-y coupling cancels on a symmetric mesh, and sparse sums drop zeros);
        # coo -> csc sums duplicates and keeps explicit zeros
        coo = k.tocoo()
        rows = np.concatenate([cx, cx, cy, cy] + ([cy + 1] if cy[-1] + 1 < k.shape[0] else []))
        cols = np.concatenate([cx, cy, cx, cy] + ([cy + 1] if cy[-1] + 1 < k.shape[0] else []))
        kc = sp.csc_matrix((np.concatenate([coo.data, np.zeros(rows.size)]),
                            (np.concatenate([coo.row, rows]), np.concatenate([coo.col, cols]))),
                           shape=k.shape)
        kc.sort_indices()
        self.k = kc
        self.pos = [self._position(kc, r, c) for r, c in ((cx, cx), (cx, cy), (cy, cx), (cy, cy))]
        self.pos_z = self._position(kc, cy + 1, cy + 1) if cy[-1] + 1 < k.shape[0] else None

    @staticmethod
    def _position(m: sp.csc_matrix, rows: IntArray, cols: IntArray) -> IntArray:
        """Positions in ``m.data`` of the entries (rows, cols), which must be in the pattern."""
        marker = sp.csc_matrix((np.arange(1, m.nnz + 1, dtype=float), m.indices, m.indptr),
                               shape=m.shape)
        pos = np.asarray(marker[rows, cols]).ravel().astype(np.int64) - 1
        if np.any(pos < 0):
            raise ValueError("contact entry outside the sparsity pattern of K")
        return pos

    def matrix(self, d: FloatArray) -> sp.csc_matrix:
        m = self.k.copy()
        m.data[self.pos[0]] += d[:, 0]
        m.data[self.pos[1]] += d[:, 1]
        m.data[self.pos[2]] += d[:, 1]
        m.data[self.pos[3]] += d[:, 2]
        if d.shape[1] > 3:
            if self.pos_z is None:
                raise ValueError("no u_z dofs after the contact y dofs")
            m.data[self.pos_z] += d[:, 3]
        return m


class _LUFactor:
    def __init__(self, lu: Any) -> None:
        self.lu = lu

    def solve(self, rhs: FloatArray) -> FloatArray:
        return np.asarray(self.lu.solve(rhs))


class SpluBackend:
    """SuperLU (scipy.sparse.linalg.splu) of K + C(D)."""

    name = "splu"

    def __init__(self, k: sp.csr_matrix, cx: IntArray, cy: IntArray) -> None:
        self.sum = _SparseContactSum(k, cx, cy)

    def factor(self, d: FloatArray) -> _LUFactor:
        return _LUFactor(spla.splu(self.sum.matrix(d), permc_spec=SYMMETRIC_ORDERING,
                                   options={"SymmetricMode": True}))


class _CholmodFactor:
    def __init__(self, factor: Any) -> None:
        self.factor = factor

    def solve(self, rhs: FloatArray) -> FloatArray:
        return np.asarray(self.factor(rhs))


class CholmodBackend:
    """CHOLMOD (scikit-sparse) of K + C(D); symbolic analysis once."""

    name = "cholmod"

    def __init__(self, k: sp.csr_matrix, cx: IntArray, cy: IntArray) -> None:
        try:
            from sksparse.cholmod import analyze
        except ImportError:
            raise ParameterError(
                "linear solver 'cholmod' needs scikit-sparse (pip install 'scikit-sparse<0.5' "
                "with libsuitesparse-dev installed); use 'banded'") from None
        self.sum = _SparseContactSum(k, cx, cy)
        self.symbolic = analyze(self.sum.k)

    def factor(self, d: FloatArray) -> _CholmodFactor:
        return _CholmodFactor(self.symbolic.cholesky(self.sum.matrix(d)))


#: Linear-solver backends: name -> (class, description).
LINEAR_SOLVERS: dict[str, tuple[Callable[[sp.csr_matrix, IntArray, IntArray], Backend], str]] = {
    "banded": (BandedBackend, "LAPACK banded Cholesky (dpbtrf/dpbtrs via scipy.linalg)"),
    "splu": (SpluBackend, "SuperLU sparse LU (scipy.sparse.linalg.splu)"),
    "cholmod": (CholmodBackend, "CHOLMOD sparse Cholesky (scikit-sparse, optional)"),
}


def available_linear_solvers() -> tuple[str, ...]:
    """Names of the backends usable on this machine."""
    out = ["banded", "splu"]
    try:
        import sksparse.cholmod  # noqa: F401
    except ImportError:
        pass
    else:
        out.append("cholmod")
    return tuple(out)


def make_backend(name: str, k: sp.csr_matrix, cx: IntArray, cy: IntArray,
                 kc: FloatArray | None = None, kn: FloatArray | None = None) -> Backend:
    """Build the named backend for the free-dof stiffness ``k`` and contact dofs ``cx, cy``;
    ``kc`` (the stick stiffnesses) lets the banded backend reuse the all-stick factor, with
    ``kn`` (penalty normal contact) that of the all-closed one."""
    try:
        cls = LINEAR_SOLVERS[name][0]
    except (KeyError, TypeError):
        raise ParameterError(
            f"unknown linear solver {name!r}; choose one of {', '.join(LINEAR_SOLVERS)}"
        ) from None
    if name == "banded":
        return BandedBackend(k, cx, cy, kc, kn)
    return cls(k, cx, cy)
