"""Running a sweep: every case computed by the batch engine (:mod:`microslip.batch`) in
independent chunks, in this process or on a Dask cluster (:func:`microslip.cluster.map_on_cluster`),
which gives the same numbers bit for bit. Units: N, mm, N·mm.
"""

from __future__ import annotations

import time
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from types import MappingProxyType
from typing import Any

import numpy as np
from numpy.typing import NDArray

from ..batch import batch_damping, default_backend, prepare_batch
from ..batch.driver import run_batch
from ..cluster import map_on_cluster
from ..errors import ParameterError
from ..models.contact import Contact
from ..options import ModelOptions
from ..progress import progress_bar
from .failures import case_failures
from .parameters import PARAMETERS, FloatArray
from .spec import DEFAULT_CHUNK, SweepSpec

BoolArray = NDArray[np.bool_]

__all__ = ["SweepResult", "run_sweep"]


@dataclass(frozen=True)
class SweepResult:
    """Results of a sweep, one value per case in row order (flat arrays of ``spec.size``).

    Attributes
    ----------
    spec : SweepSpec
    peak_displacement : ndarray
        d0, mm.
    dissipated_energy : ndarray
        W_d, N·mm.
    strain_energy : ndarray
        U, N·mm (``spec.strain_energy``).
    loss_factor : ndarray
        eta, dimensionless.
    backend : str
        Batch backend used.
    scheduler : str or None
        Address of the Dask scheduler, None for a local run.
    elapsed : float
        Wall time of the computation, s.
    failures : mapping
        Case index -> why it was not computed (its results are NaN); empty unless
        :func:`run_sweep` was asked to record failures.
    """

    spec: SweepSpec
    peak_displacement: FloatArray
    dissipated_energy: FloatArray
    strain_energy: FloatArray
    loss_factor: FloatArray
    backend: str
    scheduler: str | None = None
    elapsed: float = 0.0
    meta: dict[str, Any] = field(default_factory=dict)
    failures: Mapping[int, str] = field(default_factory=dict)

    @property
    def size(self) -> int:
        return self.spec.size

    def result_columns(self) -> dict[str, FloatArray]:
        return {
            "peak_displacement_mm": self.peak_displacement,
            "dissipated_energy_Nmm": self.dissipated_energy,
            "strain_energy_Nmm": self.strain_energy,
            "loss_factor": self.loss_factor,
        }

    def table(self, lo: int = 0, hi: int | None = None) -> dict[str, FloatArray]:
        """Every column (:data:`COLUMNS`) for the rows ``lo:hi``."""
        hi = self.size if hi is None else hi
        out = {PARAMETERS[k][0]: self.spec.column(k, lo, hi) for k in PARAMETERS}
        out.update({k: v[lo:hi] for k, v in self.result_columns().items()})
        return out

    def to_dataset(self) -> Any:
        """An ``xarray.Dataset`` with the grid axes (and ``sample``) as labelled dimensions
        (:func:`microslip.sweep.output.sweep_dataset`)."""
        from .output import sweep_dataset

        return sweep_dataset(self)


def run_sweep(spec: SweepSpec, *, chunk_size: int = DEFAULT_CHUNK,
              scheduler: str | None = None, backend: str | None = None,
              threads: int | None = None, retries: int = 3,
              progress: bool = True, failures: str = "raise") -> SweepResult:
    """Compute every case of a sweep, locally or on a Dask cluster.

    Parameters
    ----------
    spec : SweepSpec
    chunk_size : int
        Cases per chunk (one kernel call; one task on a cluster).
    scheduler : str, optional
        Address of a running ``dask.distributed`` scheduler (e.g. ``tcp://host:8786``);
        None runs in this process.
    backend : str, optional
        Batch backend (:data:`microslip.batch.BACKENDS`); default numba when installed.
    threads : int, optional
        numba threads of a local run (default: all cores); each Dask task uses one.
    retries : int
        Times a failed Dask task is retried (a lost worker's tasks are recomputed by the
        scheduler in any case; results already gathered are never lost).
    progress : bool
        Show a progress bar on standard error (tqdm; only on a terminal).
    failures : str
        ``"raise"``: the first case that cannot be computed (a value out of range, an
        amplitude at the macroslip limit) raises before any computing. ``"record"``: such
        cases get NaN results and their reason in :attr:`SweepResult.failures`; the others
        are computed (:func:`microslip.sweep.failures.case_failures`).

    Returns
    -------
    SweepResult

    Examples
    --------
    >>> from microslip import preset
    >>> from microslip.sweep import make_sweep
    >>> s = make_sweep("tip", preset("table2-tip"), grid=[("amplitude", [4000.0, 8000.0])],
    ...                increments=200)
    >>> r = run_sweep(s, progress=False)
    >>> r.loss_factor.shape, bool(r.loss_factor[1] > r.loss_factor[0])
    ((2,), True)
    """
    if isinstance(chunk_size, bool) or not isinstance(chunk_size, (int, np.integer)) \
            or chunk_size < 1:
        raise ParameterError(f"chunk size must be a whole number >= 1, got {chunk_size!r}")
    if isinstance(retries, bool) or not isinstance(retries, int) or retries < 0:
        raise ParameterError(f"retries must be a whole number >= 0, got {retries!r}")
    if failures not in ("raise", "record"):
        raise ParameterError(f"failures must be 'raise' or 'record', got {failures!r}")
    chunks = spec.chunks(int(chunk_size))
    masks: list[BoolArray | None] = [None] * len(chunks)
    why: dict[int, str] = {}
    if failures == "raise":
        spec.validate(int(chunk_size))
    else:
        for i, (lo, hi) in enumerate(chunks):
            ok, reasons = case_failures(spec, lo, hi)
            if reasons:
                masks[i] = ok
                why.update(reasons)
    be = default_backend() if backend is None else backend
    out = [np.empty(spec.size) for _ in range(4)]
    t0 = time.perf_counter()
    with progress_bar(spec.size, f"{spec.model} sweep", enabled=progress, unit="case") as bar:
        def store(i: int, res: tuple[FloatArray, ...]) -> None:
            lo, hi = chunks[i]
            for o, v in zip(out, res, strict=True):
                if masks[i] is None:
                    o[lo:hi] = v
                else:
                    o[lo:hi] = np.nan
                    o[lo:hi][masks[i]] = v
            bar.update(hi - lo)

        todo = [i for i, ok in enumerate(masks) if ok is None or ok.any()]
        for i in sorted(set(range(len(chunks))) - set(todo)):  # every case failed
            store(i, tuple(np.empty(0) for _ in range(4)))
        inputs = [_chunk_inputs(spec, *chunks[i], masks[i]) for i in todo]
        if scheduler is None:
            _run_local(spec, [chunks[i][0] for i in todo], inputs, be, threads,
                       lambda j, res: store(todo[j], res))
        else:
            payloads = [(spec.model, *inp, spec.increments, spec.options,
                         spec.strain_energy, be, 1, spec.contact) for inp in inputs]
            map_on_cluster(_chunk_task, payloads, scheduler, retries=retries,
                           on_result=lambda j, res: store(todo[j], res))
    elapsed = time.perf_counter() - t0
    return SweepResult(spec, out[0], out[1], out[2], out[3], backend=be, scheduler=scheduler,
                       elapsed=elapsed, meta={"chunks": len(chunks), "chunk_size": chunk_size},
                       failures=MappingProxyType(why))


def _chunk_inputs(spec: SweepSpec, lo: int, hi: int, ok: BoolArray | None
                  ) -> tuple[dict[str, FloatArray | float], FloatArray | float]:
    """(params, amplitude) of the cases ``lo:hi``, only those of ``ok`` if given."""
    params, amp = spec.chunk_inputs(lo, hi)
    if ok is None:
        return params, amp

    def pick(v: FloatArray | float) -> FloatArray | float:
        return v[ok] if isinstance(v, np.ndarray) else v

    return {k: pick(v) for k, v in params.items()}, pick(amp)


def _run_local(spec: SweepSpec, starts: Sequence[int],
               inputs: Sequence[tuple[dict[str, FloatArray | float], FloatArray | float]],
               backend: str, threads: int | None,
               store: Callable[[int, tuple[FloatArray, ...]], None]) -> None:
    """Every chunk in this process, in order; each result handed to ``store(index, arrays)``
    (``starts``: the index of each chunk's first case, for error messages)."""
    for i, (lo, (params, amp)) in enumerate(zip(starts, inputs, strict=True)):
        inp = prepare_batch(spec.model, params, amp, spec.increments, spec.options,
                            spec.strain_energy, where=(lo, spec.size), contact=spec.contact)
        r = run_batch(inp, backend=backend, threads=threads)
        store(i, (r.peak_displacement, r.dissipated_energy, r.strain_energy, r.loss_factor))


def _chunk_task(model: str, params: dict[str, Any], amplitude: Any, increments: int,
                options: ModelOptions, strain_energy: str, backend: str | None,
                threads: int | None, contact: Contact | None = None
                ) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray]:
    """One independent chunk of a sweep (also the Dask task)."""
    r = batch_damping(model, params, amplitude, increments, options, strain_energy,
                      backend=backend, threads=threads, contact=contact)
    return (r.peak_displacement, r.dissipated_energy, r.strain_energy, r.loss_factor)
