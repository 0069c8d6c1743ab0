"""The specification of a sweep: its grid axes, its randomly drawn parameters and the values
of every case, in row order (C order over the grid axes, then the sample).

Random samples use common random numbers: sample k has the same drawn values at every grid
point. The draws come from ``numpy.random.default_rng(seed)`` in the order the sampled
parameters are given, so the same seed gives the same cases. Units: N, mm, MPa.
"""

from __future__ import annotations

import secrets
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from ..batch import PARAM_FIELDS, check_range, prepare_batch
from ..conventions import check_choice
from ..energy import DEFAULT_STRAIN_ENERGY, STRAIN_ENERGY
from ..errors import ParameterError
from ..models import MODELS, Contact, check_increments, get_model
from ..models.contact import check_strain_energy
from ..options import ModelOptions
from ..params import ClampParams
from .parameters import MAX_CASES, PARAMETERS, Distribution, FloatArray, parse_parameter

__all__ = ["DEFAULT_CHUNK", "GridAxis", "SampledParameter", "SweepSpec", "make_sweep"]

#: Default cases per chunk (one kernel call, one Dask task).
DEFAULT_CHUNK = 65536


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
    contact : Contact or None
        The interface under the bar (stick slope, shear lag, pressure law); None: the
        paper's rigid foundation. Either way the batch engine computes every case, on a
        contact with the model's compiled layer step (:mod:`microslip.models.layered`).
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
    contact: Contact | None = None

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
        if self.contact is not None:
            c = self.contact
            slope = (f"stick slope {c.stick_slope:g} N/mm^3" if np.isfinite(c.stick_slope)
                     else "rigid contact")
            lines.append(f"contact: {slope}{' + shear lag' if c.shear_lag else ''}, "
                         f"{c.law_name} pressure")
        return lines


def make_sweep(model: str, base: ClampParams, *, amplitude: float | None = None,
               grid: Sequence[tuple[str, Sequence[float] | FloatArray]] = (),
               samples: Sequence[tuple[str, Distribution]] = (), n_samples: int = 1000,
               seed: int | None = None, increments: int = 1000,
               options: ModelOptions | None = None,
               strain_energy: str = DEFAULT_STRAIN_ENERGY,
               contact: Contact | None = None, check_draws: bool = True) -> SweepSpec:
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
    check_draws : bool
        A random draw out of its parameter's range raises (default); False leaves such
        cases to ``run_sweep(..., failures="record")``, which records them as failed rows.

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
    check_choice("strain-energy definition", strain_energy, STRAIN_ENERGY)
    n = check_increments(increments)
    seen: dict[str, str] = {}
    axes = _grid_axes(grid, seen)
    sampled: tuple[SampledParameter, ...] = ()
    if samples:
        seed = _check_draws(n_samples, seed)
        sampled = _draw_samples(samples, int(n_samples), seed, seen, check_draws)
    else:
        seed = None
    amp = _fixed_amplitude(amplitude, seen)
    spec = SweepSpec(spec_model, base, amp, axes, sampled,
                     int(n_samples) if sampled else 0, None if seed is None else int(seed),
                     n, opt, strain_energy,
                     None if contact is None or contact.is_rigid else contact)
    check_strain_energy(spec.contact, strain_energy)
    if spec.size > MAX_CASES:
        raise ParameterError(f"the sweep has {spec.size} cases; at most {MAX_CASES} are allowed")
    return spec


def _grid_axes(grid: Sequence[tuple[str, Sequence[float] | FloatArray]],
               seen: dict[str, str]) -> tuple[GridAxis, ...]:
    """The checked grid axes; records each parameter in ``seen``."""
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
    return tuple(axes)


def _check_draws(n_samples: int, seed: int | None) -> int:
    """The checked seed (a fresh one when None) after checking the number of draws."""
    if isinstance(n_samples, bool) or not isinstance(n_samples, (int, np.integer)) \
            or not 1 <= n_samples <= MAX_CASES:
        raise ParameterError(f"samples must be a whole number in [1, {MAX_CASES}], "
                             f"got {n_samples!r}")
    if seed is None:
        seed = secrets.randbits(32)
    if isinstance(seed, bool) or not isinstance(seed, (int, np.integer)) \
            or not 0 <= seed < 2**63:
        raise ParameterError(f"seed must be a whole number in [0, 2^63), got {seed!r}")
    return int(seed)


def _draw_samples(samples: Sequence[tuple[str, Distribution]], n_samples: int, seed: int,
                  seen: dict[str, str], check: bool = True) -> tuple[SampledParameter, ...]:
    """Draw every sampled parameter from one generator, in the order given; ``check``: a
    draw out of the parameter's range raises (else it is left to ``run_sweep``)."""
    rng = np.random.default_rng(seed)
    sampled: list[SampledParameter] = []
    for name_in, dist in samples:
        name = parse_parameter(name_in)
        if name in seen:
            raise ParameterError(f"{name} is given twice ({seen[name]} and sample)")
        seen[name] = "sample"
        if not isinstance(dist, Distribution):
            raise ParameterError(f"sample {name} needs a Distribution, got {dist!r}")
        v = dist.draw(rng, n_samples)
        hint = (" (a normal distribution can reach non-physical values; "
                "use lognormal:MEAN:SD for a positive quantity)"
                if dist.kind == "normal" else "")
        if check:
            _check_parameter_values(name, v, f" (sample {{i}} of {name}){hint}")
        sampled.append(SampledParameter(name, dist, v))
    return tuple(sampled)


def _fixed_amplitude(amplitude: float | None, seen: dict[str, str]) -> float | None:
    """F0 in N when the amplitude neither varies nor is sampled, else None."""
    if "amplitude" in seen:
        if amplitude is not None:
            how = "a grid axis" if seen["amplitude"] == "grid" else "sampled"
            raise ParameterError(f"amplitude {amplitude!r} N is given but the amplitude is "
                                 f"also {how}; give one or the other")
        return None
    if amplitude is None:
        raise ParameterError("give an amplitude (N), or sweep or sample it")
    amp = float(amplitude)
    check_range("amplitude", np.array([amp]), "N")
    return amp


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

