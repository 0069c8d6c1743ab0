"""The mark of a model kernel: plain Python that numba may compile (no numba here).

The models' kernels (:mod:`.tip`, :mod:`.centre`, :mod:`.columns`, :mod:`.masing`,
:mod:`.layer`, :mod:`.layered`) are plain Python functions marked ``@jit(...)`` with the
options numba compiles them with; importing them costs nothing. :mod:`.compiled` compiles
every marked function (``cache=True, fastmath=False`` and the options given) into a copy
whose calls to other kernels are calls to their compiled copies, for the batch engine and
for long single loops; a short single loop (``microslip loop``) runs them as they are
(:func:`microslip.models.dispatch.kernel`).
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any, TypeVar

__all__ = ["JIT_OPTIONS", "jit"]

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
