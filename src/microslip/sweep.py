"""Parameter studies: grids, random samples, chunked local or Dask runs, CSV/NetCDF, plots.

A sweep is a set of cases of one model (tip or centre): the product of its grid axes
(amplitude, friction, normal force, geometry, modulus, ...) and, optionally, of a sample axis
of random draws (uncertain friction and normal force, ...). The cases are numbered in C
order over (grid axes in the order given, then the sample), which is the row order of the
CSV file; a NetCDF file keeps the axes as labelled dimensions. Every case is computed by the
batch engine (:mod:`microslip.batch`) in independent chunks, so a run on a Dask cluster
gives the same numbers as a local one, bit for bit.

Random samples use common random numbers: sample k has the same drawn values at every
grid point, so differences along a grid axis are not blurred by sampling noise. The draws
come from ``numpy.random.default_rng(seed)`` in the order the sampled parameters are given,
so a sweep with the same seed writes the same file, byte for byte.

The R sweep of the planar model (force ratio, paper Fig. 12) is a short loop over
:func:`microslip.planar.planar_damping` (:func:`ratio_sweep`).

Units: N, mm, MPa, N·mm; column names carry them (``amplitude_N``, ``length_mm``, ...).
"""

from __future__ import annotations

import math
import os
import secrets
import time
from collections.abc import Callable, Iterable, Iterator, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from . import __version__
from .batch import PARAM_FIELDS, batch_damping, check_range, default_backend, prepare_batch
from .batch.driver import run_batch
from .cluster import map_on_cluster
from .energy import DEFAULT_STRAIN_ENERGY, STRAIN_ENERGY
from .errors import MicroslipError, ParameterError
from .io import atomic_path, atomic_write
from .models import MODELS, check_increments, get_model
from .options import ModelOptions
from .params import ClampParams

__all__ = [
    "ALIASES",
    "COLUMNS",
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
    "make_sweep",
    "map_on_cluster",
    "parse_grid",
    "parse_parameter",
    "parse_sample",
    "plot_ratio_sweep",
    "plot_sweep",
    "ratio_sweep",
    "run_sweep",
    "write_ratio_sweep",
    "write_sweep",
]

FloatArray = NDArray[np.float64]

#: Parameters a sweep can vary: name -> (column name, unit, axis label).
PARAMETERS: dict[str, tuple[str, str, str]] = {
    "amplitude": ("amplitude_N", "N", "Amplitude $F_0$ (N)"),
    "friction": ("friction", "", "Friction coefficient μ (–)"),
    "normal_force": ("normal_force_N", "N", "Normal force $F_N$ (N)"),
    "length": ("length_mm", "mm", "Length $L$ (mm)"),
    "width": ("width_mm", "mm", "Width $w$ (mm)"),
    "thickness": ("thickness_mm", "mm", "Thickness $t$ (mm)"),
    "modulus": ("modulus_MPa", "MPa", "Young's modulus $E$ (MPa)"),
    "poisson_ratio": ("poisson_ratio", "", "Poisson's ratio ν (–)"),
}

#: Other spellings accepted for the parameters (case-insensitive).
ALIASES: dict[str, str] = {
    "f0": "amplitude", "mu": "friction", "fn": "normal_force", "f_n": "normal_force",
    "normal-force": "normal_force", "l": "length", "w": "width", "t": "thickness",
    "e": "modulus", "nu": "poisson_ratio", "poisson-ratio": "poisson_ratio",
}

#: Result columns: name -> (unit, description).
RESULT_COLUMNS: dict[str, tuple[str, str]] = {
    "peak_displacement_mm": ("mm", "peak displacement d0 of the loaded section"),
    "dissipated_energy_Nmm": ("N·mm", "energy dissipated per cycle W_d (Eq. 21)"),
    "strain_energy_Nmm": ("N·mm", "strain energy U (Eq. 22, definition in the attributes)"),
    "loss_factor": ("", "loss factor eta = W_d / (2 pi U) (Eq. 23)"),
}

#: Every column of a tip/centre sweep, in file order.
COLUMNS: tuple[str, ...] = (*(v[0] for v in PARAMETERS.values()), *RESULT_COLUMNS)

#: Output formats by file extension.
OUTPUT_FORMATS = {".csv": "CSV, one row per case", ".nc": "NetCDF-4 (xarray, h5netcdf)"}

#: Largest number of cases of one sweep (the results are held in memory, 32 bytes a case).
MAX_CASES = 100_000_000

#: Default cases per chunk (one kernel call, one Dask task).
DEFAULT_CHUNK = 65536

_COLUMN_PARAM = {v[0]: k for k, v in PARAMETERS.items()}


def parse_parameter(name: str) -> str:
    """The canonical parameter name of ``name`` (aliases: mu, F_N, L, w, t, E, nu, F0).

    >>> parse_parameter("mu"), parse_parameter("F_N"), parse_parameter("length_mm")
    ('friction', 'normal_force', 'length')
    """
    key = name.strip()
    if key in PARAMETERS:
        return key
    if key in _COLUMN_PARAM:
        return _COLUMN_PARAM[key]
    low = key.lower()
    if low in ALIASES:
        return ALIASES[low]
    if low in PARAMETERS:
        return low
    raise ParameterError(
        f"unknown sweep parameter {name!r}; choose one of {', '.join(PARAMETERS)} "
        f"(or mu, F_N, L, w, t, E, nu)"
    )


def _number(text: str, what: str) -> float:
    try:
        x = float(text)
    except ValueError:
        raise ParameterError(f"{what}: {text!r} is not a number") from None
    if not math.isfinite(x):
        raise ParameterError(f"{what}: {text!r} is not finite")
    return x


def _count(text: str, what: str) -> int:
    try:
        n = int(text)
    except ValueError:
        raise ParameterError(f"{what}: count {text!r} is not a whole number") from None
    if not 1 <= n <= MAX_CASES:
        raise ParameterError(f"{what}: count must be in [1, {MAX_CASES}], got {n}")
    return n


def linear_values(start: float, stop: float, count: int, log: bool = False) -> FloatArray:
    """``count`` values from ``start`` to ``stop``, both included, evenly or geometrically
    spaced; one value is ``start``."""
    if count == 1:
        return np.array([float(start)])
    if log:
        if start <= 0 or stop <= 0:
            raise ParameterError(f"a log-spaced range needs positive ends, got {start}:{stop}")
        return np.geomspace(start, stop, count)
    return np.linspace(start, stop, count)


def parse_grid(text: str) -> tuple[str, FloatArray]:
    """``NAME=START:STOP:COUNT[:log]`` or ``NAME=V1,V2,...`` -> (parameter, values).

    >>> name, v = parse_grid("mu=0.4:0.8:5")
    >>> name, v.tolist()
    ('friction', [0.4, 0.5, 0.6000000000000001, 0.7000000000000001, 0.8])
    >>> parse_grid("E=70000,210000")[1].tolist()
    [70000.0, 210000.0]
    """
    what = f"--grid {text}"
    syntax = "expected NAME=START:STOP:COUNT[:log] or NAME=V1,V2,..."
    if "=" not in text:
        raise ParameterError(f"{what}: {syntax}")
    name_s, spec = text.split("=", 1)
    name = parse_parameter(name_s)
    spec = spec.strip()
    if ":" in spec:
        parts = spec.split(":")
        log = len(parts) == 4 and parts[3].strip().lower() in ("log", "geom")
        if len(parts) not in (3, 4) or (len(parts) == 4 and not log):
            raise ParameterError(f"{what}: {syntax}")
        values = linear_values(_number(parts[0], what), _number(parts[1], what),
                               _count(parts[2], what), log)
    else:
        items = [s for s in spec.split(",") if s.strip()]
        if not items:
            raise ParameterError(f"{what}: {syntax}")
        values = np.array([_number(s, what) for s in items])
    return name, values


@dataclass(frozen=True)
class Distribution:
    """A distribution to draw a parameter from.

    Parameters
    ----------
    kind : {"normal", "lognormal", "uniform"}
    a, b : float
        normal: mean and standard deviation; lognormal: mean and standard deviation of the
        quantity itself (always positive); uniform: lower and upper bound.

    Examples
    --------
    >>> d = Distribution("lognormal", 0.8, 0.05)
    >>> x = d.draw(np.random.default_rng(1), 100000)
    >>> round(float(x.mean()), 2), round(float(x.std()), 2)
    (0.8, 0.05)
    """

    kind: str
    a: float
    b: float

    def __post_init__(self) -> None:
        if self.kind not in DISTRIBUTIONS:
            raise ParameterError(
                f"unknown distribution {self.kind!r}; choose one of {', '.join(DISTRIBUTIONS)}"
            )
        a, b = float(self.a), float(self.b)
        if not (math.isfinite(a) and math.isfinite(b)):
            raise ParameterError(f"{self.kind} distribution needs finite numbers, got {a}, {b}")
        if self.kind == "uniform" and not a < b:
            raise ParameterError(f"uniform distribution needs LOW < HIGH, got {a:g}:{b:g}")
        if self.kind in ("normal", "lognormal") and not b > 0:
            raise ParameterError(f"{self.kind} distribution needs SD > 0, got {b:g}")
        if self.kind == "lognormal" and not a > 0:
            raise ParameterError(f"lognormal distribution needs MEAN > 0, got {a:g}")
        object.__setattr__(self, "a", a)
        object.__setattr__(self, "b", b)

    def draw(self, rng: np.random.Generator, size: int) -> FloatArray:
        """``size`` independent draws."""
        if self.kind == "normal":
            return rng.normal(self.a, self.b, size)
        if self.kind == "uniform":
            return rng.uniform(self.a, self.b, size)
        s2 = math.log1p((self.b / self.a) ** 2)
        return rng.lognormal(math.log(self.a) - 0.5 * s2, math.sqrt(s2), size)

    def __str__(self) -> str:
        names = DISTRIBUTIONS[self.kind][1]
        return f"{self.kind}({names[0]} {self.a:g}, {names[1]} {self.b:g})"


#: Distributions: name -> (syntax, names of the two numbers).
DISTRIBUTIONS: dict[str, tuple[str, tuple[str, str]]] = {
    "normal": ("normal:MEAN:SD", ("mean", "sd")),
    "lognormal": ("lognormal:MEAN:SD (of the quantity, always > 0)", ("mean", "sd")),
    "uniform": ("uniform:LOW:HIGH", ("low", "high")),
}


def parse_sample(text: str) -> tuple[str, Distribution]:
    """``NAME=DIST:A:B`` -> (parameter, distribution).

    >>> parse_sample("friction=normal:0.8:0.05")
    ('friction', Distribution(kind='normal', a=0.8, b=0.05))
    """
    what = f"--sample {text}"
    syntax = "expected NAME=" + " or NAME=".join(v[0].split()[0] for v in DISTRIBUTIONS.values())
    if "=" not in text:
        raise ParameterError(f"{what}: {syntax}")
    name_s, spec = text.split("=", 1)
    name = parse_parameter(name_s)
    parts = spec.strip().split(":")
    if len(parts) != 3:
        raise ParameterError(f"{what}: {syntax}")
    kind = parts[0].strip().lower()
    if kind not in DISTRIBUTIONS:
        raise ParameterError(
            f"{what}: unknown distribution {parts[0]!r}; choose one of {', '.join(DISTRIBUTIONS)}"
        )
    return name, Distribution(kind, _number(parts[1], what), _number(parts[2], what))


@dataclass(frozen=True)
class GridAxis:
    """One labelled dimension of a sweep: a parameter and its values."""

    name: str
    values: FloatArray

    @property
    def column(self) -> str:
        return PARAMETERS[self.name][0]


@dataclass(frozen=True)
class SampledParameter:
    """A parameter drawn at random: its distribution and the draws (one per sample)."""

    name: str
    distribution: Distribution
    values: FloatArray

    @property
    def column(self) -> str:
        return PARAMETERS[self.name][0]


@dataclass(frozen=True)
class SweepSpec:
    """Everything that defines a sweep; build it with :func:`make_sweep`.

    Attributes
    ----------
    model : str
    base : ClampParams
        The values of every parameter that is neither a grid axis nor sampled.
    amplitude : float or None
        F0 in N when it is neither a grid axis nor sampled.
    grid : tuple of GridAxis
    samples : tuple of SampledParameter
    n_samples : int
        Draws per grid point (0 without sampled parameters).
    seed : int or None
        Seed of the draws (None without sampled parameters).
    increments : int
    options : ModelOptions
    strain_energy : str
    """

    model: str
    base: ClampParams
    amplitude: float | None
    grid: tuple[GridAxis, ...]
    samples: tuple[SampledParameter, ...]
    n_samples: int
    seed: int | None
    increments: int
    options: ModelOptions
    strain_energy: str

    @property
    def dims(self) -> tuple[str, ...]:
        """Dimension names (grid columns, then ``sample``)."""
        return tuple(a.column for a in self.grid) + (("sample",) if self.samples else ())

    @property
    def shape(self) -> tuple[int, ...]:
        return tuple(a.values.size for a in self.grid) + (
            (self.n_samples,) if self.samples else ())

    @property
    def size(self) -> int:
        return int(np.prod(self.shape, dtype=np.int64))

    @property
    def varying(self) -> tuple[str, ...]:
        return tuple(a.name for a in self.grid) + tuple(s.name for s in self.samples)

    def constant(self, name: str) -> float:
        """Value of a parameter that does not vary."""
        if name == "amplitude":
            assert self.amplitude is not None
            return self.amplitude
        return float(getattr(self.base, name))

    def values(self, name: str, lo: int, hi: int) -> FloatArray | float:
        """Parameter ``name`` for the cases ``lo:hi`` (a float when it does not vary)."""
        shape = self.shape
        for k, axis in enumerate(self.grid):
            if axis.name == name:
                stride = int(np.prod(shape[k + 1:], dtype=np.int64))
                idx = (np.arange(lo, hi, dtype=np.int64) // stride) % axis.values.size
                return axis.values[idx]
        for s in self.samples:
            if s.name == name:
                return s.values[np.arange(lo, hi, dtype=np.int64) % self.n_samples]
        return self.constant(name)

    def column(self, name: str, lo: int = 0, hi: int | None = None) -> FloatArray:
        """Parameter ``name`` for the cases ``lo:hi`` as an array."""
        hi = self.size if hi is None else hi
        v = self.values(name, lo, hi)
        return v if isinstance(v, np.ndarray) else np.full(hi - lo, v)

    def chunk_inputs(self, lo: int, hi: int) -> tuple[dict[str, FloatArray | float],
                                                     FloatArray | float]:
        """(params mapping, amplitude) of the cases ``lo:hi`` for the batch engine."""
        params = {k: self.values(k, lo, hi) for k in PARAM_FIELDS}
        return params, self.values("amplitude", lo, hi)

    def chunks(self, chunk_size: int = DEFAULT_CHUNK) -> list[tuple[int, int]]:
        """Consecutive case ranges (lo, hi) of at most ``chunk_size`` cases."""
        n = self.size
        return [(lo, min(lo + chunk_size, n)) for lo in range(0, n, chunk_size)]

    def validate(self, chunk_size: int = DEFAULT_CHUNK) -> None:
        """Check every case once (ranges and the macroslip limit), before any computing."""
        for lo, hi in self.chunks(chunk_size):
            params, amp = self.chunk_inputs(lo, hi)
            prepare_batch(self.model, params, amp, self.increments, self.options,
                          self.strain_energy, where=(lo, self.size))

    def describe(self) -> list[str]:
        """One line per swept or sampled parameter."""
        lines = []
        for a in self.grid:
            unit = PARAMETERS[a.name][1]
            u = f" {unit}" if unit else ""
            lines.append(f"{a.column}: {a.values.size} values from {a.values[0]:g} to "
                         f"{a.values[-1]:g}{u}")
        for s in self.samples:
            unit = PARAMETERS[s.name][1]
            u = f" {unit}" if unit else ""
            lines.append(f"{s.column}: {self.n_samples} draws, {s.distribution}{u}, "
                         f"seed {self.seed}")
        return lines


def make_sweep(model: str, base: ClampParams, *, amplitude: float | None = None,
               grid: Sequence[tuple[str, Sequence[float] | FloatArray]] = (),
               samples: Sequence[tuple[str, Distribution]] = (), n_samples: int = 1000,
               seed: int | None = None, increments: int = 1000,
               options: ModelOptions | None = None,
               strain_energy: str = DEFAULT_STRAIN_ENERGY) -> SweepSpec:
    """Build and validate a sweep; random samples are drawn here, from ``seed``.

    Parameters
    ----------
    model : {"tip", "centre"}
    base : ClampParams
        Values of the parameters that do not vary.
    amplitude : float, optional
        F0 in N; needed unless amplitude is a grid axis or sampled.
    grid : sequence of (name, values)
        Grid axes, in order (the first varies slowest in the row order).
    samples : sequence of (name, Distribution)
        Sampled parameters; ``n_samples`` draws each, shared by every grid point.
    seed : int, optional
        Seed of the draws; a fresh one is chosen (and recorded in the spec) when None.
    increments, options, strain_energy
        As for :func:`microslip.damping`.

    Raises
    ------
    ParameterError
        A bad name, value, count or combination (one line naming it).

    Examples
    --------
    >>> from microslip import preset
    >>> s = make_sweep("tip", preset("table2-tip"), grid=[("amplitude", [1000.0, 2000.0]),
    ...                ("mu", [0.6, 0.8])], increments=100)
    >>> s.dims, s.shape, s.column("friction").tolist()
    (('amplitude_N', 'friction'), (2, 2), [0.6, 0.8, 0.6, 0.8])
    """
    spec_model = get_model(model).name
    if spec_model not in MODELS:
        raise ParameterError(f"unknown model {model!r}")
    if not isinstance(base, ClampParams):
        raise ParameterError(f"base must be ClampParams, got {type(base).__name__}")
    opt = options if options is not None else ModelOptions()
    if strain_energy not in STRAIN_ENERGY:
        raise ParameterError(
            f"unknown strain-energy definition {strain_energy!r}; choose one of "
            f"{', '.join(STRAIN_ENERGY)}"
        )
    n = check_increments(increments)
    seen: dict[str, str] = {}
    axes: list[GridAxis] = []
    for name_in, vals in grid:
        name = parse_parameter(name_in)
        if name in seen:
            raise ParameterError(f"{name} is given twice ({seen[name]} and grid)")
        seen[name] = "grid"
        v = np.asarray(vals, dtype=np.float64).ravel()
        if v.size == 0:
            raise ParameterError(f"grid {name} has no values")
        _check_parameter_values(name, v, f" (grid {name} value {{i}})")
        axes.append(GridAxis(name, np.ascontiguousarray(v)))
    sampled: list[SampledParameter] = []
    if samples:
        if isinstance(n_samples, bool) or not isinstance(n_samples, (int, np.integer)) \
                or not 1 <= n_samples <= MAX_CASES:
            raise ParameterError(f"samples must be a whole number in [1, {MAX_CASES}], "
                                 f"got {n_samples!r}")
        if seed is None:
            seed = secrets.randbits(32)
        if isinstance(seed, bool) or not isinstance(seed, (int, np.integer)) \
                or not 0 <= seed < 2**63:
            raise ParameterError(f"seed must be a whole number in [0, 2^63), got {seed!r}")
        rng = np.random.default_rng(int(seed))
        for name_in, dist in samples:
            name = parse_parameter(name_in)
            if name in seen:
                raise ParameterError(f"{name} is given twice ({seen[name]} and sample)")
            seen[name] = "sample"
            if not isinstance(dist, Distribution):
                raise ParameterError(f"sample {name} needs a Distribution, got {dist!r}")
            v = dist.draw(rng, int(n_samples))
            hint = (" (a normal distribution can reach non-physical values; "
                    "use lognormal:MEAN:SD for a positive quantity)"
                    if dist.kind == "normal" else "")
            _check_parameter_values(name, v, f" (sample {{i}} of {name}){hint}")
            sampled.append(SampledParameter(name, dist, v))
    else:
        seed = None
    if "amplitude" in seen:
        if amplitude is not None:
            how = "a grid axis" if seen["amplitude"] == "grid" else "sampled"
            raise ParameterError(f"amplitude {amplitude!r} N is given but the amplitude is "
                                 f"also {how}; give one or the other")
        amp = None
    elif amplitude is None:
        raise ParameterError("give an amplitude (N), or sweep or sample it")
    else:
        amp = float(amplitude)
        check_range("amplitude", np.array([amp]), "N")
    spec = SweepSpec(spec_model, base, amp, tuple(axes), tuple(sampled),
                     int(n_samples) if sampled else 0, None if seed is None else int(seed),
                     n, opt, strain_energy)
    if spec.size > MAX_CASES:
        raise ParameterError(f"the sweep has {spec.size} cases; at most {MAX_CASES} are allowed")
    return spec


def _check_parameter_values(name: str, v: FloatArray, where: str) -> None:
    """Range check of grid values or draws; ``where`` has ``{i}`` for the index."""
    unit = PARAMETERS[name][1]
    if name == "poisson_ratio":
        ok = np.isfinite(v) & (v >= 0.0) & (v < 0.5)
        rng = "[0, 0.5)"
    else:
        ok = np.isfinite(v) & (v > 0.0)
        rng = "(0, inf)"
    if not ok.all():
        i = int(np.argmin(ok))
        u = f" {unit}" if unit else ""
        raise ParameterError(f"{name} must be finite and in {rng}{u}, got {float(v[i])!r}"
                             + where.format(i=i))


# -- running --------------------------------------------------------------------------------
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
        """An ``xarray.Dataset`` with the grid axes (and ``sample``) as labelled dimensions."""
        xr = _import_xarray()
        spec = self.spec
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
            for k, v in self.result_columns().items()
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


def _chunk_task(model: str, params: dict[str, Any], amplitude: Any, increments: int,
                options: ModelOptions, strain_energy: str, backend: str | None,
                threads: int | None) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray]:
    """One independent chunk of a sweep (also the Dask task)."""
    r = batch_damping(model, params, amplitude, increments, options, strain_energy,
                      backend=backend, threads=threads)
    return (r.peak_displacement, r.dissipated_energy, r.strain_energy, r.loss_factor)


def _progress_bar(total: int, enabled: bool, desc: str) -> Any:
    if not enabled:
        return None
    try:
        from tqdm import tqdm
    except ImportError:
        return None
    return tqdm(total=total, desc=desc, unit="case", unit_scale=True, leave=False,
                disable=None)


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
    n = spec.size
    out = [np.empty(n) for _ in range(4)]
    chunks = spec.chunks(int(chunk_size))
    bar = _progress_bar(n, progress, f"{spec.model} sweep")
    t0 = time.perf_counter()
    try:
        if scheduler is None:
            for lo, hi in chunks:
                params, amp = spec.chunk_inputs(lo, hi)
                inp = prepare_batch(spec.model, params, amp, spec.increments, spec.options,
                                    spec.strain_energy, where=(lo, n))
                r = run_batch(inp, backend=be, threads=threads)
                for o, v in zip(out, (r.peak_displacement, r.dissipated_energy,
                                      r.strain_energy, r.loss_factor), strict=True):
                    o[lo:hi] = v
                if bar is not None:
                    bar.update(hi - lo)
        else:
            payloads = []
            for lo, hi in chunks:
                params, amp = spec.chunk_inputs(lo, hi)
                payloads.append((spec.model, params, amp, spec.increments, spec.options,
                                 spec.strain_energy, be, 1))

            def store(i: int, res: tuple[FloatArray, ...]) -> None:
                lo, hi = chunks[i]
                for o, v in zip(out, res, strict=True):
                    o[lo:hi] = v
                if bar is not None:
                    bar.update(hi - lo)

            map_on_cluster(_chunk_task, payloads, scheduler, retries=retries, on_result=store)
    finally:
        if bar is not None:
            bar.close()
    elapsed = time.perf_counter() - t0
    return SweepResult(spec, out[0], out[1], out[2], out[3], backend=be, scheduler=scheduler,
                       elapsed=elapsed, meta={"chunks": len(chunks), "chunk_size": chunk_size})


# -- output ---------------------------------------------------------------------------------
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


def write_sweep(result: SweepResult, path: str | os.PathLike[str],
                chunk_size: int = DEFAULT_CHUNK) -> None:
    """Write a sweep to ``path`` (``.csv`` or ``.nc``), atomically.

    CSV: a header of :data:`COLUMNS`, then one row per case in row order, every number as
    ``%.15g``. NetCDF: :meth:`SweepResult.to_dataset` (labelled dimensions, units and the
    settings in the attributes).
    """
    ext = check_output(path)
    if ext == ".nc":
        ds = result.to_dataset()
        with atomic_path(path) as tmp:
            ds.to_netcdf(tmp, engine="h5netcdf")
        return
    from .batch.textfmt import format_table

    spec = result.spec
    results = list(result.result_columns().values())
    with atomic_write(path, "wb") as fh:
        fh.write((",".join(COLUMNS) + "\n").encode())
        for lo in range(0, result.size, chunk_size):
            hi = min(lo + chunk_size, result.size)
            # parameters that do not vary stay single numbers: formatted once per chunk
            cols: list[Any] = [spec.values(k, lo, hi) for k in PARAMETERS]
            fh.write(format_table(cols + [r[lo:hi] for r in results]))


# -- summary plot ---------------------------------------------------------------------------
_MAX_POINTS = 2000
_MAX_SERIES = 6


def _thin(n: int, m: int = _MAX_POINTS) -> NDArray[np.intp]:
    return np.unique(np.linspace(0, n - 1, min(n, m)).round().astype(np.intp))


def plot_sweep(result: SweepResult, path: str | os.PathLike[str]) -> None:
    """Loss factor against the swept parameter, saved to ``path``.

    The x axis is the first grid axis (or, without a grid, the first sampled parameter,
    case by case as points). A second grid axis gives one curve per value (at most six,
    evenly picked). With random samples each curve is the median over the samples with
    bands from the 25th to the 75th and from the 5th to the 95th percentile.
    """
    from .plot import COLOURS, new_figure, save_figure

    spec = result.spec
    fig, axes = new_figure()
    ax = axes[0, 0]
    eta = result.loss_factor.reshape(spec.shape)
    ax.set_ylabel("Loss factor η (–)")
    if not spec.grid:
        s = spec.samples[0]
        idx = _thin(spec.size, 20000)
        ax.plot(s.values[idx], eta[idx], ".", ms=1.5, color=COLOURS[0], alpha=0.5,
                label=f"{spec.size} draws")
        for q, ls, label in ((50, "-", "median"), (5, ":", "5th and 95th percentiles"),
                             (95, ":", None)):
            ax.axhline(float(np.percentile(eta, q)), color=COLOURS[1], ls=ls, lw=0.8,
                       label=label)
        ax.set_xlabel(PARAMETERS[s.name][2])
    else:
        x_axis = spec.grid[0]
        x = x_axis.values
        ix = _thin(x.size)
        # collapse to (x, series, samples)
        rest = spec.shape[1:len(spec.grid)]
        e = eta.reshape((x.size, int(np.prod(rest, dtype=np.int64)),
                         spec.n_samples if spec.samples else 1))
        series = [0]
        label_of: Callable[[int], str] = lambda j: ""  # noqa: E731
        if len(spec.grid) >= 2:
            second = spec.grid[1]
            inner = int(np.prod(rest[1:], dtype=np.int64))
            picks = _thin(second.values.size, _MAX_SERIES)
            series = [int(p) * inner for p in picks]
            unit = PARAMETERS[second.name][1]

            def label_of(j: int) -> str:
                v = second.values[j // inner]
                return f"{second.column} = {v:g}" + (f" {unit}" if unit else "")
        for c, j in enumerate(series):
            colour = COLOURS[c % len(COLOURS)]
            ej = e[ix, j, :]
            if spec.samples:
                p5, p25, p50, p75, p95 = np.percentile(ej, [5, 25, 50, 75, 95], axis=1)
                ax.fill_between(x[ix], p5, p95, color=colour, alpha=0.15, lw=0)
                ax.fill_between(x[ix], p25, p75, color=colour, alpha=0.3, lw=0)
                ax.plot(x[ix], p50, color=colour, label=(label_of(j) + " median").strip())
            else:
                ax.plot(x[ix], ej[:, 0], color=colour, label=label_of(j) or None)
        if spec.samples:
            ax.fill_between([], [], [], color="0.5", alpha=0.3, label="25–75 %")
            ax.fill_between([], [], [], color="0.5", alpha=0.15, label="5–95 %")
        ax.set_xlabel(PARAMETERS[x_axis.name][2])
    title = f"{spec.model} model, U: {spec.strain_energy}, {spec.increments} increments"
    if spec.samples:
        import textwrap

        draws = "; ".join(f"{s.name} ~ {s.distribution.kind}({s.distribution.a:g}, "
                          f"{s.distribution.b:g})" for s in spec.samples)
        title += "\n" + "\n".join(textwrap.wrap(f"{draws}; {spec.n_samples} draws", 50))
    ax.set_title(title, fontsize=7)
    if ax.get_legend_handles_labels()[0]:
        ax.legend(frameon=False)
    save_figure(fig, path)


# -- planar: loss factor against the force ratio R ------------------------------------------
def ratio_sweep(ratios: Iterable[float], *, tip_params: ClampParams | None = None,
                centre_params: ClampParams | None = None, levels: str = "base",
                increments: int = 1000, options: ModelOptions | None = None,
                strain_energy: str | None = None, phase_deg: float = 0.0,
                progress: bool = True) -> Any:
    """Planar damping against the force ratio R (paper Fig. 12): one
    :func:`microslip.planar.planar_damping` per R, in a plain loop.

    Cases the reading in force cannot compute (e.g. a centre amplitude at the macroslip
    limit) are kept with NaN results and the reason. Returns a
    :class:`microslip.planar.RatioSweep`.
    """
    from .planar import PAPER_STRAIN_ENERGY, loss_factor_vs_ratio

    rs = [float(r) for r in ratios]

    def bar(items: Iterable[float], desc: str, total: int) -> Iterator[float]:
        pb = _progress_bar(total, progress, desc)
        for r in items:
            yield r
            if pb is not None:
                pb.update(1)
        if pb is not None:
            pb.close()

    return loss_factor_vs_ratio(
        rs, tip_params=tip_params, centre_params=centre_params, levels=levels,
        increments=increments, options=options,
        strain_energy=strain_energy or PAPER_STRAIN_ENERGY, phase_deg=phase_deg,
        progress=bar)


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
    from .batch.textfmt import format_table

    with atomic_write(path, "wb") as fh:
        fh.write((",".join(cols) + "\n").encode())
        fh.write(format_table(list(cols.values())))


def _unit_of(column: str) -> str:
    for suffix, unit in (("_Nmm", "N mm"), ("_N_per_mm", "N/mm"), ("_mm", "mm"), ("_N", "N")):
        if column.endswith(suffix):
            return unit
    return "1"


def plot_ratio_sweep(sweep: Any, path: str | os.PathLike[str]) -> None:
    """Loss factor against R (log axis), the paper's coupling and the work of the load."""
    from .plot import COLOURS, new_figure, save_figure

    fig, axes = new_figure()
    ax = axes[0, 0]
    r = sweep.ratios
    ax.plot(r, sweep.loss_factor("paper"), "o-", ms=2.5, color=COLOURS[0],
            label="paper coupling (Eqs 19–23)")
    ax.plot(r, sweep.loss_factor("work"), "s--", ms=2.5, color=COLOURS[1],
            label="work of the load")
    ax.set_xscale("log")
    from matplotlib.ticker import NullFormatter, ScalarFormatter

    nice = [t for t in (0.125, 0.25, 0.5, 1.0, 2.0, 4.0, 8.0) if r.min() <= t <= r.max()]
    if len(nice) >= 2:
        ax.set_xticks(nice)
    ax.xaxis.set_major_formatter(ScalarFormatter())
    ax.xaxis.set_minor_formatter(NullFormatter())
    ax.set_xlabel("Force ratio R = $F_{tip}/F_{centre}$ (–)")
    ax.set_ylabel("Loss factor η (–)")
    ax.set_title(f"planar, U: {sweep.strain_energy_kind}, levels: {sweep.levels}", fontsize=7)
    ax.legend(frameon=False)
    save_figure(fig, path)
