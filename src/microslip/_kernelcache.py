"""numba's on-disk cache of microslip's kernels, kept fresh when an inlined function changes.

numba stamps a cached function with the contents of its own source file only. The kernels
inline functions from the other files of their folder (the batch kernels inline the models'
steps and the Masing sums, the layer backbones the layer kernel, every backbone the column
set-up), so an edit there would leave a stale compiled kernel that numba still loads. The
locators below stamp each of microslip's compiled functions with the contents of every
``.py`` file in its folder instead: any edit in the folder rebuilds the folder's kernels, and
an unchanged folder loads them from the cache, compiled once per machine (``cache=True``).

:func:`install` puts such locators (numba's user-provided ``NUMBA_CACHE_DIR``, in-tree
``__pycache__`` and user-wide ones, in numba's order) in front of numba's own. It runs when
this module is imported, which the packages with kernels (``models``, ``batch``,
``dynamics``) do first of all. It uses numba's cache-locator interface
(``numba.core.caching``), which is not a documented API: on a numba without it, numba's own
per-file stamp applies.
"""

from __future__ import annotations

import hashlib
import os
from typing import Any

__all__ = ["install"]

_ROOT = os.path.dirname(os.path.abspath(__file__))


def _folder_stamp(folder: str) -> str:
    """SHA-256 over the names and contents of the ``.py`` files of ``folder``."""
    h = hashlib.sha256()
    for name in sorted(os.listdir(folder)):
        if name.endswith(".py"):
            h.update(name.encode())
            with open(os.path.join(folder, name), "rb") as f:
                h.update(hashlib.sha256(f.read()).digest())
    return h.hexdigest()


def install() -> None:
    """Register the folder-stamped locators with numba (idempotent)."""
    from numba.core import caching

    impl: Any = getattr(caching, "CacheImpl", None) or getattr(caching, "_CacheImpl", None)
    mixin = getattr(caching, "_SourceFileBackedLocatorMixin", None)
    classes = getattr(impl, "_locator_classes", None)
    if mixin is None or classes is None or any(getattr(c, "_microslip", False)
                                               for c in classes):
        return
    stamped = [_stamped(c) for c in classes if issubclass(c, mixin)]
    impl._locator_classes = [*stamped, *classes]


_STAMPS: dict[str, str] = {}


def _stamped(base: Any) -> Any:
    """``base`` (one of numba's source-file locators: user-provided directory, in-tree
    ``__pycache__``, user-wide) for microslip's files, stamped with their whole folder."""

    class FolderStamped(base):
        _microslip = True

        def get_source_stamp(self) -> str:
            folder = os.path.dirname(os.path.abspath(self._py_file))
            if folder not in _STAMPS:
                _STAMPS[folder] = _folder_stamp(folder)
            return _STAMPS[folder]

        @classmethod
        def from_function(cls, py_func: Any, py_file: str) -> Any:
            if not os.path.abspath(py_file).startswith(_ROOT + os.sep):
                return None
            return super().from_function(py_func, py_file)

    FolderStamped.__name__ = FolderStamped.__qualname__ = f"FolderStamped{base.__name__}"
    return FolderStamped


install()
