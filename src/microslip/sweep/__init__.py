"""Parameter studies: grids, random samples, chunked local or Dask runs, CSV/NetCDF output.

A sweep is a set of cases of one model (tip or centre): the product of its grid axes
(amplitude, friction, normal force, geometry, modulus, ...) and, optionally, of a sample axis
of random draws with common random numbers. :mod:`~microslip.sweep.parameters` holds what
can vary and its command-line syntax, :mod:`~microslip.sweep.spec` the specification and the
values of every case (row order), :mod:`~microslip.sweep.run` the computation (batch engine,
in chunks, locally or on a Dask cluster, bit-identical either way),
:mod:`~microslip.sweep.output` the CSV and NetCDF files, :mod:`~microslip.sweep.ratio` the R
sweep of the planar model; the summary plots live in :mod:`microslip.plot.sweep` (a floor
above: they read the specification's parameter names). This package may import the computing
packages (batch, models, planar, fe, energy), :mod:`microslip.io`, :mod:`microslip.cluster`
and :mod:`microslip.progress`; never plot, the CLI, case, reproduce or validate (the
import-linter contracts in pyproject.toml). Units: N, mm, MPa, N·mm; column names carry them.
"""

from __future__ import annotations

from .output import (
    OUTPUT_FORMATS,
    check_output,
    sweep_attributes,
    sweep_dataset,
    write_ratio_sweep,
    write_sweep,
)
from .parameters import (
    ALIASES,
    COLUMNS,
    DISTRIBUTIONS,
    MAX_CASES,
    PARAMETERS,
    RESULT_COLUMNS,
    Distribution,
    linear_values,
    parse_grid,
    parse_parameter,
    parse_sample,
)
from .ratio import ratio_sweep
from .run import SweepResult, run_sweep
from .spec import DEFAULT_CHUNK, GridAxis, SampledParameter, SweepSpec, make_sweep

__all__ = [
    "ALIASES",
    "COLUMNS",
    "DEFAULT_CHUNK",
    "DISTRIBUTIONS",
    "MAX_CASES",
    "OUTPUT_FORMATS",
    "PARAMETERS",
    "RESULT_COLUMNS",
    "Distribution",
    "GridAxis",
    "SampledParameter",
    "SweepResult",
    "SweepSpec",
    "check_output",
    "linear_values",
    "make_sweep",
    "parse_grid",
    "parse_parameter",
    "parse_sample",
    "ratio_sweep",
    "run_sweep",
    "sweep_attributes",
    "sweep_dataset",
    "write_ratio_sweep",
    "write_sweep",
]
