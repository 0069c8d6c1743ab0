"""Running independent tasks on an existing ``dask.distributed`` cluster (optional extra).

Shared by the sweeps (one chunk of cases per task) and the finite-element validation (one
CalculiX job per task).
"""

from __future__ import annotations

import uuid
from collections.abc import Callable, Sequence
from typing import Any

from .errors import MicroslipError
from .progress import progress as progress_bar

__all__ = ["map_on_cluster"]


def map_on_cluster(func: Callable[..., Any], payloads: Sequence[tuple[Any, ...]],
                   scheduler: str, *, retries: int = 3,
                   on_result: Callable[[int, Any], None] | None = None,
                   key_prefix: str = "microslip", progress: str | None = None) -> list[Any]:
    """Run ``func(*payload)`` for every payload on a ``dask.distributed`` cluster.

    One task per payload, each independent. Results are fetched as they complete (and
    handed to ``on_result(index, result)``), so a worker lost later cannot take them with it;
    the tasks of a lost worker are rescheduled by the Dask scheduler, and a task that raises
    is retried ``retries`` times. Returns the results in payload order. Usable for any
    embarrassingly parallel job list, e.g. one finite-element run per task. ``progress``:
    a label for a progress bar over the completed tasks.

    Raises
    ------
    MicroslipError
        dask.distributed is not installed, or the scheduler cannot be reached.
    """
    try:
        from dask.distributed import Client, as_completed
    except ImportError:
        raise MicroslipError(
            "--scheduler needs dask.distributed: pip install 'microslip[dask]'"
        ) from None
    try:
        # connection timeout: dask's distributed.comm.timeouts.connect (30 s by default)
        client = Client(scheduler, set_as_default=False)
    except (OSError, TimeoutError, ValueError) as exc:
        raise MicroslipError(
            f"cannot connect to the Dask scheduler at {scheduler!r}: {exc}"
        ) from None
    results: list[Any] = [None] * len(payloads)
    token = uuid.uuid4().hex[:12]
    with client:
        futures = [
            client.submit(func, *p, key=f"{key_prefix}-{token}-{i:06d}", retries=retries,
                          pure=False)
            for i, p in enumerate(payloads)
        ]
        index = {f.key: i for i, f in enumerate(futures)}
        done = as_completed(futures, loop=client.loop)
        for fut in progress_bar(done, progress or "", total=len(futures),
                                enabled=progress is not None):
            i = index[fut.key]
            res = fut.result()
            results[i] = res
            if on_result is not None:
                on_result(i, res)
            fut.release()
    return results
