"""Damping of one case from the sums the batch kernels accumulate along the first loading.

Plain arithmetic that works on scalars (inside the compiled kernels, which wrap it with
numba's ``njit``) and on numpy arrays (the pure-numpy fallback): one definition for both.
See ``docs/sweeps.md`` for the algebra of the sums.
"""

from __future__ import annotations

import math
from typing import Any

__all__ = ["finish"]


def finish(f0: Any, d0: Any, q: Any, q_k0: Any, d_km1: Any, d_k0: Any, fr_km1: float,
           fr_k0: float, stored: Any, kind: int) -> tuple[Any, Any, Any]:
    """W_d, U and eta of one case (or a block of cases) from the accumulated sums."""
    w = 4.0 * (q - f0 * d0)
    if kind == 0:
        u = 0.5 * f0 * d0
    elif kind == 1:
        u = 0.5 * q
    elif kind == 2:
        fa1 = -f0 + 2.0 * (f0 * fr_k0)
        fa0 = -f0 + 2.0 * (f0 * fr_km1)
        da1 = -d0 + 2.0 * d_k0
        da0 = -d0 + 2.0 * d_km1
        s = -fa0 / (fa1 - fa0)
        d_zero = da0 + s * (da1 - da0)
        u = 0.5 * fa1 * (da1 - d_zero) + 2.0 * (q - q_k0) - 2.0 * f0 * (d0 - d_k0)
    else:
        u = stored
    return w, u, w / (2.0 * math.pi * u)
