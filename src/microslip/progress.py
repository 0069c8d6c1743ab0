"""Progress display for long runs: tqdm when installed, silent otherwise."""

from __future__ import annotations

from collections.abc import Iterable, Iterator
from typing import TypeVar

T = TypeVar("T")

__all__ = ["progress"]


def progress(items: Iterable[T], desc: str, total: int | None = None,
             enabled: bool = True) -> Iterator[T]:
    """Iterate over ``items`` with a progress bar on standard error (if tqdm is available)."""
    if enabled:
        try:
            from tqdm import tqdm
        except ImportError:
            pass
        else:
            yield from tqdm(items, desc=desc, total=total, unit="step", leave=False,
                            disable=None)
            return
    yield from items
