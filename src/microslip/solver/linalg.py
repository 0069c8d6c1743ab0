"""Factorising the tangent K + C(D): LAPACK banded Cholesky, or a sparse direct solver.

The elastic stiffness K of the free dofs is constant; only the 2 x 2 friction tangents D_i of
the contact nodes change from one Newton iteration to the next, and they sit on the diagonal
and the first off-diagonal (the x and y dofs of a contact node are neighbours in the
numbering). A backend therefore keeps K once and adds D for every factorisation.

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

from ..errors import ParameterError

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


class BandedBackend:
    """LAPACK banded Cholesky of K + C(D)."""

    name = "banded"

    def __init__(self, k: sp.csr_matrix, cx: IntArray, cy: IntArray) -> None:
        if np.any(cy != cx + 1):
            raise ValueError("contact x and y dofs must be neighbours in the numbering")
        coo = sp.tril(k, format="coo")
        kd = int(np.max(coo.row - coo.col)) if coo.nnz else 0
        ab = np.zeros((kd + 1, k.shape[0]))
        ab[coo.row - coo.col, coo.col] = coo.data  # LAPACK lower band storage
        self.ab, self.kd, self.cx, self.cy = ab, kd, cx, cy

    @property
    def half_bandwidth(self) -> int:
        return self.kd

    def factor(self, d: FloatArray) -> _BandFactor:
        ab = self.ab.copy()
        ab[0, self.cx] += d[:, 0]
        ab[0, self.cy] += d[:, 2]
        if self.kd > 0:
            ab[1, self.cx] += d[:, 1]
        return _BandFactor(sla.cholesky_banded(ab, lower=True, check_finite=False))


class _SparseContactSum:
    """K + C(D) as CSC with a fixed sparsity pattern (the contact entries are in K's pattern)."""

    def __init__(self, k: sp.csr_matrix, cx: IntArray, cy: IntArray) -> None:
        kc = k.tocsc()
        kc.sort_indices()
        self.k = kc
        self.pos = [self._position(kc, r, c) for r, c in ((cx, cx), (cx, cy), (cy, cx), (cy, cy))]

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
        return _LUFactor(spla.splu(self.sum.matrix(d)))


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

    def factor(self, d: FloatArray) -> _LUFactor:
        return _LUFactor(self.symbolic.cholesky(self.sum.matrix(d)))


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


def make_backend(name: str, k: sp.csr_matrix, cx: IntArray, cy: IntArray) -> Backend:
    """Build the named backend for the free-dof stiffness ``k`` and contact dofs ``cx, cy``."""
    try:
        cls = LINEAR_SOLVERS[name][0]
    except (KeyError, TypeError):
        raise ParameterError(
            f"unknown linear solver {name!r}; choose one of {', '.join(LINEAR_SOLVERS)}"
        ) from None
    return cls(k, cx, cy)
