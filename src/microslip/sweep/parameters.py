"""What a sweep can vary and how it is written on the command line: parameter names and
aliases, the columns of the output, grid values (``NAME=START:STOP:COUNT``) and distributions
of randomly drawn parameters (``NAME=DIST:A:B``).

Units: N, mm, MPa; column names carry them (``amplitude_N``, ``length_mm``, ...).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from ..errors import ParameterError

__all__ = [
    "ALIASES",
    "COLUMNS",
    "DISTRIBUTIONS",
    "MAX_CASES",
    "PARAMETERS",
    "RESULT_COLUMNS",
    "Distribution",
    "linear_values",
    "parse_grid",
    "parse_parameter",
    "parse_sample",
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


#: Largest number of cases of one sweep (the results are held in memory, 32 bytes a case).
MAX_CASES = 100_000_000


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

