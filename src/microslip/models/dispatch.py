"""Which copy of a model kernel a call runs: the plain function or its compiled copy.

A plain kernel (``@jit``, :mod:`._jit`) costs nothing to import and about a microsecond a
step; its compiled copy (:mod:`.compiled`) costs 1-1.5 s to load once (numba's import and
registries, the cached machine code) and little per step. :func:`kernel` runs a process's
first, small work plain and everything after compiled; both give the same numbers bit for
bit, so the choice changes the time only. No numba here.
"""

from __future__ import annotations

import sys
from collections.abc import Callable
from typing import Any

__all__ = ["LAYER_STEP", "PLAIN_STEPS", "kernel"]


#: Steps (increments of the rigid-foundation models, about 1 microsecond each in plain
#: Python) a process runs through the plain-Python kernels before it loads their compiled
#: copies (:mod:`.compiled`), which costs 1-1.5 s (numba's import and registries, the cached
#: machine code). ``microslip loop`` (1000 increments) stays plain; a study of many loops,
#: or one long loop, compiles.
PLAIN_STEPS = 200_000

#: What one step of the shear-layer models (a slip-front search: 50-200 microseconds in
#: plain Python, measured) counts in :data:`PLAIN_STEPS`.
LAYER_STEP = 100

_plain_steps = 0


def kernel(func: Callable[..., Any], steps: int) -> Callable[..., Any]:
    """The model kernel ``func`` (a plain function of :mod:`.tip`, :mod:`.centre`,
    :mod:`.layer`, :mod:`.layered`, :mod:`.masing` or :mod:`.columns`) to run for about
    ``steps`` steps: itself while this process has run fewer than :data:`PLAIN_STEPS` plain
    steps and not loaded the compiled kernels, else its compiled copy. Both give the same
    numbers bit for bit; only the time differs."""
    global _plain_steps
    if "microslip.models.compiled" not in sys.modules and _plain_steps + steps <= PLAIN_STEPS:
        _plain_steps += steps
        return func
    from .compiled import compiled
    return compiled(func)
