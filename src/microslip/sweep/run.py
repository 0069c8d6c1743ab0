"""Running a sweep: every case computed by the batch engine (:mod:`microslip.batch`) in
independent chunks, in this process or on a Dask cluster (:func:`microslip.cluster.map_on_cluster`),
which gives the same numbers bit for bit. Units: N, mm, N·mm.
"""

from __future__ import annotations

import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..batch import PARAM_FIELDS, batch_damping, default_backend, prepare_batch
from ..batch.driver import run_batch
from ..cluster import map_on_cluster
from ..energy import damping_from_backbone
from ..errors import ParameterError
from ..models import first_loading
from ..options import ModelOptions
from ..params import ClampParams
from ..progress import progress_bar
from .parameters import PARAMETERS, FloatArray
from .spec import DEFAULT_CHUNK, SweepSpec

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
              progress: bool = True) -> SweepResult:
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
    spec.validate(int(chunk_size))
    be = default_backend() if backend is None else backend
    if spec.contact is not None:
        if scheduler is not None:
            raise ParameterError("a sweep on a contact with a stick slope or pressure law runs "
                                 "case by case in this process; leave out --scheduler")
        be = "per case (shear-layer model)"
    out = [np.empty(spec.size) for _ in range(4)]
    chunks = spec.chunks(int(chunk_size))
    t0 = time.perf_counter()
    with progress_bar(spec.size, f"{spec.model} sweep", enabled=progress, unit="case") as bar:
        def store(i: int, res: tuple[FloatArray, ...]) -> None:
            lo, hi = chunks[i]
            for o, v in zip(out, res, strict=True):
                o[lo:hi] = v
            bar.update(hi - lo)

        if spec.contact is not None:
            _run_on_contact(spec, chunks, store)
        elif scheduler is None:
            _run_local(spec, chunks, be, threads, store)
        else:
            payloads = [(spec.model, *spec.chunk_inputs(lo, hi), spec.increments, spec.options,
                         spec.strain_energy, be, 1) for lo, hi in chunks]
            map_on_cluster(_chunk_task, payloads, scheduler, retries=retries, on_result=store)
    elapsed = time.perf_counter() - t0
    return SweepResult(spec, out[0], out[1], out[2], out[3], backend=be, scheduler=scheduler,
                       elapsed=elapsed, meta={"chunks": len(chunks), "chunk_size": chunk_size})


def _run_local(spec: SweepSpec, chunks: Sequence[tuple[int, int]], backend: str,
               threads: int | None, store: Callable[[int, tuple[FloatArray, ...]], None]
               ) -> None:
    """Every chunk in this process, in order; each result handed to ``store(index, arrays)``."""
    for i, (lo, hi) in enumerate(chunks):
        params, amp = spec.chunk_inputs(lo, hi)
        inp = prepare_batch(spec.model, params, amp, spec.increments, spec.options,
                            spec.strain_energy, where=(lo, spec.size))
        r = run_batch(inp, backend=backend, threads=threads)
        store(i, (r.peak_displacement, r.dissipated_energy, r.strain_energy, r.loss_factor))


def _run_on_contact(spec: SweepSpec, chunks: Sequence[tuple[int, int]],
                    store: Callable[[int, tuple[FloatArray, ...]], None]) -> None:
    """Every case through :func:`microslip.models.first_loading` on the spec's contact (the
    batch engine has the rigid foundation only); same columns as the batch engine."""
    for i, (lo, hi) in enumerate(chunks):
        params, amp = spec.chunk_inputs(lo, hi)
        m = hi - lo
        cols = {k: np.broadcast_to(np.asarray(v, dtype=float), (m,)) for k, v in params.items()}
        amps = np.broadcast_to(np.asarray(amp, dtype=float), (m,))
        res = [np.empty(m) for _ in range(4)]
        for j in range(m):
            p = ClampParams(**{k: float(cols[k][j]) for k in PARAM_FIELDS})
            bb = first_loading(spec.model, p, float(amps[j]), spec.increments, spec.options,
                               spec.contact)
            r = damping_from_backbone(bb, spec.strain_energy)
            for o, v in zip(res, (r.peak_displacement, r.dissipated_energy, r.strain_energy,
                                  r.loss_factor), strict=True):
                o[j] = v
        store(i, tuple(res))


def _chunk_task(model: str, params: dict[str, Any], amplitude: Any, increments: int,
                options: ModelOptions, strain_energy: str, backend: str | None,
                threads: int | None) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray]:
    """One independent chunk of a sweep (also the Dask task)."""
    r = batch_damping(model, params, amplitude, increments, options, strain_energy,
                      backend=backend, threads=threads)
    return (r.peak_displacement, r.dissipated_energy, r.strain_energy, r.loss_factor)
