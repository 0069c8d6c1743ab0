"""Batch engine: damping of many parameter sets at once (tip and centre models).

:func:`batch_damping` evaluates the models' first loading, Masing's rule and the energies
of Eqs 21-23 for a whole batch of cases, with memory O(batch): the loop of each case is
never stored, its energies are accumulated increment by increment. This package validates
and dispatches; the compiled kernels (numba, parallel over chunks of cases) are each
model's own (:attr:`microslip.models.ModelSpec.batch_kernel`), built on the same step
function as :func:`microslip.first_loading`, and the energies are
:func:`microslip.models.masing.masing_energies`, as for :func:`microslip.damping`. It may
import ``models``, ``energy``, ``options``, ``params``, ``named``, ``errors`` and
``_kernelcache``.

>>> import numpy as np
>>> from microslip import preset, damping
>>> from microslip.batch import batch_damping
>>> r = batch_damping("tip", preset("table2-tip"), np.linspace(1000.0, 8000.0, 8))
>>> one = damping("tip", preset("table2-tip"), 8000.0)
>>> bool(r.loss_factor[-1] == one.loss_factor)
True
"""

from __future__ import annotations

from .. import _kernelcache  # noqa: F401  (before any kernel: the folder-stamped cache)
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
