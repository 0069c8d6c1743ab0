"""Progress display for long runs: tqdm when installed and on a terminal, silent otherwise.

The one place that talks to tqdm: :func:`progress_bar` (a counter advanced by hand, e.g. by
cases as chunks finish) and :func:`progress` (an iterable wrapped in such a counter).
"""

from __future__ import annotations

import contextlib
from collections.abc import Iterable, Iterator, Sized
from typing import Any, Protocol, TypeVar

T = TypeVar("T")

__all__ = ["Counter", "progress", "progress_bar"]


class Counter(Protocol):
    """What a progress bar offers: advance by ``n``."""

    def update(self, n: int = 1) -> Any: ...


class _Silent:
    """A counter that shows nothing (progress off, or tqdm not installed)."""

    def update(self, n: int = 1) -> None:
        return None

    def close(self) -> None:
        return None


@contextlib.contextmanager
def progress_bar(total: int | None, desc: str, *, enabled: bool = True,
                 unit: str = "step") -> Iterator[Counter]:
    """A progress bar on standard error over ``total`` units, closed on leaving the block."""
    bar: Any = _Silent()
    if enabled:
        try:
            from tqdm import tqdm
        except ImportError:
            pass
        else:
            bar = tqdm(total=total, desc=desc, unit=unit, unit_scale=True, leave=False,
                       disable=None)
    try:
        yield bar
    finally:
        bar.close()


def progress(items: Iterable[T], desc: str, total: int | None = None,
             enabled: bool = True, unit: str = "step") -> Iterator[T]:
    """Iterate over ``items`` with a progress bar (``total`` defaults to ``len(items)``)."""
    if total is None and isinstance(items, Sized):
        total = len(items)
    with progress_bar(total, desc, enabled=enabled, unit=unit) as bar:
        for item in items:
            yield item
            bar.update(1)
