"""One BLAS/LAPACK thread for the small dense and banded solves of the FE solver and the
harmonic balance (shared by :mod:`microslip.fe.builtin` and :mod:`microslip.dynamics`)."""

from __future__ import annotations

import contextlib
from collections.abc import Iterator

#: Nothing public: :func:`single_threaded_blas` is an internal of the solvers.
__all__: list[str] = []


@contextlib.contextmanager
def single_threaded_blas() -> Iterator[None]:
    """Limit BLAS/LAPACK to one thread inside the block (threadpoolctl).

    The solves are small (the solver's banded factorisations n b^2 ~ 1e6-1e8 flops, the
    harmonic balance's systems of tens of unknowns); threading them costs more in
    synchronisation than it gains (measured 0.96 ms vs 0.14 ms for 625 dofs), and on a
    shared machine it can cost 10-40x.
    """
    from threadpoolctl import threadpool_limits  # here: only the solves pay its import

    with threadpool_limits(limits=1, user_api="blas"):
        yield
