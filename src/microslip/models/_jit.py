"""The mark of a model kernel: plain Python that numba may compile (no numba here).

The models' kernels (:mod:`.tip`, :mod:`.centre`, :mod:`.columns`, :mod:`.masing`,
:mod:`.layer`, :mod:`.layered`) are plain Python functions marked ``@jit(...)`` with the
options numba compiles them with; importing them costs nothing. :mod:`.compiled` compiles
every marked function (``cache=True, fastmath=False`` and the options given) into a copy
whose calls to other kernels are calls to their compiled copies, for the batch engine and
for long single loops; a short single loop (``microslip loop``) runs them as they are
(:func:`kernel`).
"""

from __future__ import annotations

import sys
from collections.abc import Callable
from typing import Any, TypeVar

__all__ = ["JIT_OPTIONS", "LAYER_STEP", "PLAIN_STEPS", "jit", "kernel"]

F = TypeVar("F", bound=Callable[..., Any])

#: The attribute that carries a kernel's numba options.
JIT_OPTIONS = "__microslip_jit__"


def jit(**options: Any) -> Callable[[F], F]:
    """Mark a function as a kernel that numba compiles with ``options`` (``inline``, ...);
    the function itself is returned unchanged."""
    def mark(func: F) -> F:
        setattr(func, JIT_OPTIONS, dict(options))
        return func
    return mark


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
