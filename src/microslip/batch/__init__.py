"""Batch engine: damping of many parameter sets at once (tip and centre models).

:func:`batch_damping` evaluates the models' first loading, Masing's rule and the energies
of Eqs 21-23 for a whole batch of cases, with memory O(batch): the loop of each case is
never stored, its energies are accumulated increment by increment. The compiled kernels
(:mod:`.kernels`, numba, parallel over chunks of cases) need the ``sweep`` extra; without
numba a vectorised numpy fallback (:mod:`.fallback`) gives the same numbers, slower.

>>> import numpy as np
>>> from microslip import preset, damping
>>> from microslip.batch import batch_damping
>>> r = batch_damping("tip", preset("table2-tip"), np.linspace(1000.0, 8000.0, 8))
>>> one = damping("tip", preset("table2-tip"), 8000.0)
>>> bool(abs(r.loss_factor[-1] / one.loss_factor - 1) < 1e-12)
True
"""

from __future__ import annotations

from .driver import (
    BACKENDS,
    PARAM_FIELDS,
    BatchInput,
    BatchResult,
    batch_damping,
    check_range,
    default_backend,
    prepare_batch,
    run_batch,
)

__all__ = [
    "BACKENDS",
    "PARAM_FIELDS",
    "BatchInput",
    "BatchResult",
    "batch_damping",
    "check_range",
    "default_backend",
    "prepare_batch",
    "run_batch",
]
