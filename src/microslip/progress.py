"""Progress display for long runs on standard error: tqdm's bar on a terminal, plain lines
otherwise.

The one place that talks to tqdm: :func:`progress_bar` (a counter advanced by hand, e.g. by
cases as chunks finish) and :func:`progress` (an iterable wrapped in such a counter). When
standard error is not a terminal (a log file, ``2>&1`` into a file) or tqdm is not
installed, the progress is plain lines, one every :data:`LINE_SECONDS` at most (none for a
run shorter than that; the last step's when any was printed), so that a run writing its
output to a file still shows that it moves.
"""

from __future__ import annotations

import contextlib
import sys
import time
from collections.abc import Iterable, Iterator, Sized
from typing import Any, Protocol, TypeVar

T = TypeVar("T")

__all__ = ["LINE_SECONDS", "Counter", "progress", "progress_bar"]


class Counter(Protocol):
    """What a progress bar offers: advance by ``n``."""

    def update(self, n: int = 1) -> Any: ...


class _Silent:
    """A counter that shows nothing (progress off, or tqdm not installed)."""

    def update(self, n: int = 1) -> None:
        return None

    def close(self) -> None:
        return None


#: Seconds between two plain progress lines (the first and the last step always print).
LINE_SECONDS = 10.0


class _Lines:
    """Progress as plain lines on standard error: ``desc: 3/12 runs (25 %), 40 s, about
    120 s left``, one every :data:`LINE_SECONDS` at most, the first once the run has taken
    that long (a short run says nothing), and the last if any was printed."""

    def __init__(self, total: int | None, desc: str, unit: str) -> None:
        self.total, self.desc, self.unit = total, desc, unit
        self.done = 0
        self.start = self.last = time.monotonic()
        self.printed = False

    def update(self, n: int = 1) -> None:
        self.done += n
        now = time.monotonic()
        final = self.total is not None and self.done >= self.total and self.printed
        if not final and now - self.last < LINE_SECONDS:
            return
        self.last, self.printed = now, True
        spent = now - self.start
        units = f"{self.unit}s" if not self.unit.endswith("s") else self.unit
        if self.total:
            left = spent / self.done * (self.total - self.done) if self.done else 0.0
            text = (f"{self.desc}: {self.done}/{self.total} {units} "
                    f"({100 * self.done / self.total:.0f} %), {spent:.0f} s"
                    + (f", about {left:.0f} s left" if not final else ""))
        else:
            text = f"{self.desc}: {self.done} {units}, {spent:.0f} s"
        print(text, file=sys.stderr, flush=True)

    def close(self) -> None:
        return None


def _terminal() -> bool:
    try:
        return bool(sys.stderr.isatty())
    except (AttributeError, ValueError):
        return False


@contextlib.contextmanager
def progress_bar(total: int | None, desc: str, *, enabled: bool = True,
                 unit: str = "step") -> Iterator[Counter]:
    """A progress bar on standard error over ``total`` units, closed on leaving the block
    (plain lines when standard error is not a terminal or tqdm is missing)."""
    bar: Any = _Silent()
    if enabled:
        try:
            from tqdm import tqdm
        except ImportError:
            bar = _Lines(total, desc, unit)
        else:
            bar = (tqdm(total=total, desc=desc, unit=unit, unit_scale=True, leave=False)
                   if _terminal() else _Lines(total, desc, unit))
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
