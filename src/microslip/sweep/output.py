"""Writing sweeps: CSV (one row per case, in row order, written chunk by chunk by the compiled
formatter :func:`microslip.batch.textfmt.format_table`) or NetCDF (xarray, labelled
dimensions, units and the settings as attributes), always atomically.

Units: N, mm, MPa, N·mm, recorded in the column names and the NetCDF attributes.
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from .. import __version__
from ..batch.textfmt import format_table
from ..energy import STRAIN_ENERGY
from ..errors import MicroslipError, ParameterError
from ..io import atomic_path, atomic_write
from ..models import get_model
from .parameters import COLUMNS, PARAMETERS, RESULT_COLUMNS, FloatArray
from .spec import DEFAULT_CHUNK, SweepSpec

if TYPE_CHECKING:  # run.py imports this module (SweepResult.to_dataset)
    from .run import SweepResult

__all__ = [
    "OUTPUT_FORMATS",
    "check_output",
    "sweep_attributes",
    "sweep_dataset",
    "write_ratio_sweep",
    "write_sweep",
]

#: Output formats by file extension.
OUTPUT_FORMATS = {".csv": "CSV, one row per case", ".nc": "NetCDF-4 (xarray, h5netcdf)"}


def check_output(path: str | os.PathLike[str]) -> str:
    """The output format of ``path`` by its extension; checks the libraries it needs."""
    ext = Path(path).suffix.lower()
    if ext not in OUTPUT_FORMATS:
        raise ParameterError(
            f"output file must end in {' or '.join(OUTPUT_FORMATS)}, got {os.fspath(path)!r}"
        )
    if ext == ".nc":
        _import_xarray()
        try:
            import h5netcdf  # noqa: F401
            import h5py  # noqa: F401  (h5netcdf >= 1.5 leaves it optional)
        except ImportError:
            raise MicroslipError(
                "NetCDF output needs h5netcdf and h5py: pip install 'microslip[sweep]' h5py"
            ) from None
    return ext


def _import_xarray() -> Any:
    try:
        import xarray as xr
    except ImportError:
        raise MicroslipError("NetCDF output needs xarray: pip install 'microslip[sweep]'") from None
    return xr



def sweep_dataset(result: SweepResult) -> Any:
    """An ``xarray.Dataset`` with the grid axes (and ``sample``) as labelled dimensions
    (:meth:`SweepResult.to_dataset`)."""
    xr = _import_xarray()
    spec = result.spec
    dims, shape = spec.dims, spec.shape
    coords: dict[str, Any] = {}
    for a in spec.grid:
        coords[a.column] = ((a.column,), a.values, _attrs(a.name))
    if spec.samples:
        coords["sample"] = ("sample", np.arange(spec.n_samples, dtype=np.int64),
                            {"long_name": "index of the random draw"})
        for s in spec.samples:
            attrs = _attrs(s.name)
            attrs["distribution"] = str(s.distribution)
            coords[s.column] = (("sample",), s.values, attrs)
    for k in PARAMETERS:
        if k not in spec.varying:
            coords[PARAMETERS[k][0]] = ((), spec.constant(k), _attrs(k))
    data = {
        k: (dims, v.reshape(shape), {"units": RESULT_COLUMNS[k][0] or "1",
                                     "long_name": RESULT_COLUMNS[k][1]})
        for k, v in result.result_columns().items()
    }
    return xr.Dataset(data, coords=coords, attrs=sweep_attributes(spec))


def _attrs(name: str) -> dict[str, str]:
    unit = PARAMETERS[name][1]
    return {"units": unit or "1", "long_name": name.replace("_", " ")}


def sweep_attributes(spec: SweepSpec) -> dict[str, Any]:
    """Global attributes recording how a sweep was made (no None or bool: NetCDF types)."""
    attrs: dict[str, Any] = {
        "title": f"microslip {spec.model} model sweep",
        "source": f"microslip {__version__}",
        "references": "Lord & Rongong 2016, Proc IMechE C, doi:10.1177/0954406215608409",
        "model": spec.model,
        "equations": get_model(spec.model).equations,
        "increments": spec.increments,
        "poisson": spec.options.poisson,
        "length_update": int(spec.options.length_update),
        "centre_reading": spec.options.centre,
        "strain_energy_definition": spec.strain_energy,
        "strain_energy_meaning": STRAIN_ENERGY[spec.strain_energy][1],
        "units": "force N, length mm, modulus MPa, energy N mm",
        "row_order": "C order over " + ", ".join(spec.dims),
    }
    if spec.samples:
        attrs["seed"] = int(spec.seed or 0)
        attrs["samples"] = "; ".join(f"{s.name} ~ {s.distribution}" for s in spec.samples)
        attrs["sampling"] = "common random numbers: each sample index has the same draws " \
                            "at every grid point"
    return attrs


def write_sweep(result: SweepResult, path: str | os.PathLike[str],
                chunk_size: int = DEFAULT_CHUNK) -> None:
    """Write a sweep to ``path`` (``.csv`` or ``.nc``), atomically.

    CSV: a header of :data:`COLUMNS`, then one row per case in row order, every number in the
    fewest of 15-17 significant digits that read back exactly (``batch.textfmt``). NetCDF:
    :meth:`SweepResult.to_dataset` (labelled dimensions, units and the settings in the
    attributes).
    """
    ext = check_output(path)
    if ext == ".nc":
        ds = result.to_dataset()
        with atomic_path(path) as tmp:
            ds.to_netcdf(tmp, engine="h5netcdf")
        return
    spec = result.spec
    results = list(result.result_columns().values())
    with atomic_write(path, "wb") as fh:
        fh.write((",".join(COLUMNS) + "\n").encode())
        for lo in range(0, result.size, chunk_size):
            hi = min(lo + chunk_size, result.size)
            # parameters that do not vary stay single numbers: formatted once per chunk
            cols: list[Any] = [spec.values(k, lo, hi) for k in PARAMETERS]
            fh.write(format_table(cols + [r[lo:hi] for r in results]))


def _ratio_columns(sweep: Any) -> dict[str, FloatArray]:
    cols = sweep.columns()
    return {k: np.asarray(v, dtype=np.float64) for k, v in cols.items()}


def write_ratio_sweep(sweep: Any, path: str | os.PathLike[str]) -> None:
    """Write an R sweep (CSV: one row per R; NetCDF: dimension ``R``), atomically."""
    ext = check_output(path)
    cols = _ratio_columns(sweep)
    if ext == ".nc":
        xr = _import_xarray()
        r = cols.pop("R")
        ds = xr.Dataset(
            {k: (("R",), v, {"units": _unit_of(k)}) for k, v in cols.items()},
            coords={"R": ("R", r, {"units": "1", "long_name": "force ratio F_tip / F_centre "
                                   "(Eq. 1, normalised forces)"})},
            attrs={"title": "microslip planar sweep over the force ratio R",
                   "source": f"microslip {__version__}", "levels": sweep.levels,
                   "strain_energy_definition": sweep.strain_energy_kind,
                   "work_energy": sweep.work_energy, "phase_deg": sweep.phase_deg,
                   "increments": sweep.increments, "poisson": sweep.options.poisson,
                   "length_update": int(sweep.options.length_update),
                   "centre_reading": sweep.centre_options.centre})
        with atomic_path(path) as tmp:
            ds.to_netcdf(tmp, engine="h5netcdf")
        return
    with atomic_write(path, "wb") as fh:
        fh.write((",".join(cols) + "\n").encode())
        fh.write(format_table(list(cols.values())))


def _unit_of(column: str) -> str:
    for suffix, unit in (("_Nmm", "N mm"), ("_N_per_mm", "N/mm"), ("_mm", "mm"), ("_N", "N")):
        if column.endswith(suffix):
            return unit
    return "1"

