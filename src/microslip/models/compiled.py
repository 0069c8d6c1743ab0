"""The models' kernels compiled by numba: the batch engine's and the long single loops'.

Every function marked ``@jit`` in :mod:`.columns`, :mod:`.masing`, :mod:`.tip`,
:mod:`.centre`, :mod:`.layer` and :mod:`.layered` is compiled here (``cache=True,
fastmath=False`` and its own options), as a copy of the function whose module namespace
holds the compiled copies of the other kernels: numba inlines and calls compiled code only,
and the plain functions stay plain. The machine code comes from numba's on-disk cache,
stamped with the whole folder (:mod:`microslip._kernelcache`). ``KERNELS[module]`` holds a
module's compiled kernels under their own names (also importable from here by name:
``from .compiled import tip_step``); :func:`compiled` gives the copy of a plain kernel
(:func:`microslip.models.kernel` chooses between the two).

The compiled code and plain Python give the same numbers bit for bit (IEEE double, no
fused multiply-add, the same libm; checked by ``tests/test_models_compiled.py``).
"""

from __future__ import annotations

import types
from typing import Any

from numba import njit

from .. import _kernelcache  # noqa: F401  (before any kernel: the folder-stamped cache)
from . import centre, columns, layer, layered, masing, tip
from ._jit import JIT_OPTIONS

__all__ = ["KERNELS", "compiled"]

_MODULES = (columns, masing, tip, centre, layer, layered)


def _compile(modules: tuple[types.ModuleType, ...]) -> dict[str, types.SimpleNamespace]:
    """Compiled copies of the marked functions of ``modules``, by module name."""
    by_id: dict[int, Any] = {}
    spaces: list[dict[str, Any]] = []
    out: dict[str, types.SimpleNamespace] = {}
    for module in modules:
        space = dict(vars(module))
        spaces.append(space)
        own = types.SimpleNamespace()
        for name, func in vars(module).items():
            options = getattr(func, JIT_OPTIONS, None)
            if options is None or func.__module__ != module.__name__:
                continue
            copy = types.FunctionType(func.__code__, space, func.__name__, func.__defaults__,
                                      func.__closure__)
            copy.__qualname__, copy.__module__ = func.__qualname__, func.__module__
            copy.__doc__ = func.__doc__
            by_id[id(func)] = njit(cache=True, fastmath=False, **options)(copy)
            setattr(own, name, by_id[id(func)])
        out[module.__name__.rsplit(".", 1)[-1]] = own
    for space in spaces:  # the compiled copies call each other (resolved at compile time)
        for name, value in space.items():
            if callable(value) and id(value) in by_id:
                space[name] = by_id[id(value)]
    return out


#: Module name (``tip``, ``layer``, ...) -> its compiled kernels under their own names.
KERNELS = _compile(_MODULES)


def compiled(func: Any) -> Any:
    """The compiled copy of the kernel ``func`` (a function of one of the six modules)."""
    return getattr(KERNELS[func.__module__.rsplit(".", 1)[-1]], func.__name__)


def __getattr__(name: str) -> Any:
    """A compiled kernel by its name (``from .compiled import tip_step``)."""
    for space in KERNELS.values():
        if hasattr(space, name):
            return getattr(space, name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
