"""Real clamps in 1-D: an elastic shear layer under the bar and a clamping pressure law q(x).

The paper's bar lies on a rigid Coulomb foundation under a uniform pressure. Here the bar
(axial stiffness E A) rests on an elastic-perfectly-plastic shear layer of stiffness ``k`` per
unit length (N/mm per mm) whose traction saturates at the local friction limit q(x) per unit
length. Loaded from the virgin state by a force F at one end (distance s from the loaded
section, 0 <= s <= L), a slip zone 0 <= s <= a forms next to the load and the rest sticks:

- slip zone: N(s) = F - Q(s), with Q(s) = integral_0^s q;
- stuck zone (layer elastic, free far end): u(s) = C cosh(lambda (L - s)), lambda = sqrt(k/EA);
- slip front: k u(a) = q(a), so the stuck zone carries N(a) = (q(a)/lambda) tanh(lambda (L - a)).

Hence, exactly, for a slip front a in [0, L]::

    F(a) = Q(a) + (q(a) / lambda) tanh(lambda (L - a))
    d(a) = q(a) / k + (F a - R(a)) / (E A),        R(s) = integral_0^s Q

Uniform q gives Menq, Bielak & Griffin's microslip bar (shared/REFERENCES.md); k -> infinity
gives the rigid-foundation bar with non-uniform pressure (Q(a) = F, d = integral (F - Q)/EA);
both together give Goodman & Klumpp's d = F^2 / (2 E A q). Before slip (F < F(0)) the bar
sticks with stiffness K0 = E A lambda tanh(lambda L).

The layer stiffness combines the contact's stick slope (N/mm^3, the FE penalty friction law)
over the width with the body's own through-thickness shear compliance (shear lag, as in the
Tsai-Oplinger-Morton correction of bonded laps): with the shear traction falling linearly from
the interface to the free (frictionless) clamped face, the interface moves t / (3 G) per unit
shear stress more than the section's mean, so 1/k = 1/(k_c w) + t/(3 G w), G = E / (2 (1 + nu)).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..errors import ParameterError
from ..params import ClampParams
from . import layer as kernel
from .dispatch import LAYER_STEP
from .dispatch import kernel as _run

__all__ = [
    "PRESSURE_LAWS",
    "PressureLaw",
    "backbone_force",
    "layer_stiffness",
    "pressure_law",
    "read_pressure_table",
    "slip_front",
    "table_law",
    "tip_backbone",
]

FloatArray = NDArray[np.float64]


@dataclass(frozen=True)
class PressureLaw:
    """A clamping-pressure shape along the clamped length, normalised to a mean of 1.

    ``shape(xi)`` is p(xi) for xi = x / L in [0, 1] (x from one end of the clamped zone),
    ``cumulative(xi)`` its integral from 0 and ``second(xi)`` the integral of that; the line
    friction limit is q(x) = (mu F_N / L) p(x / L), so the total is always mu F_N. All three
    evaluate the compiled law ``(code, data)`` of :mod:`microslip.models.layer`, the one the
    models run (build a law with :func:`power_law`, :func:`table_law` or
    :func:`pressure_law`).
    """

    name: str
    shape: Callable[[FloatArray], FloatArray]
    cumulative: Callable[[FloatArray], FloatArray]
    second: Callable[[FloatArray], FloatArray]
    description: str
    #: p(xi) = p(1 - xi): the two halves of a centre-loaded bar are mirror images.
    symmetric: bool = True
    #: The compiled form: law code (:data:`microslip.models.layer.LAW_UNIFORM`, ...) and data.
    code: int = kernel.LAW_UNIFORM
    data: FloatArray = field(default_factory=lambda: np.zeros((1, 1)), compare=False)


def _compiled_law(name: str, code: int, data: FloatArray, description: str,
                  symmetric: bool = True) -> PressureLaw:
    """A :class:`PressureLaw` whose NumPy functions evaluate the compiled ``(code, data)``."""
    data = np.ascontiguousarray(data, dtype=np.float64)
    data.setflags(write=False)

    def values(which: int) -> Callable[[FloatArray], FloatArray]:
        def evaluate(xi: FloatArray) -> FloatArray:
            x = np.asarray(xi, dtype=np.float64)
            flat = np.ascontiguousarray(x.reshape(-1))
            return _run(kernel.law_values, flat.size)(which, code, data, flat).reshape(x.shape)
        return evaluate

    return PressureLaw(name, values(0), values(2), values(3), description, symmetric, code,
                       data)


def _uniform() -> PressureLaw:
    return _compiled_law("uniform", kernel.LAW_UNIFORM, np.zeros((1, 1)),
                         "uniform pressure F_N / (L w) (the paper's)")


def power_law(exponent: float = 2.0, edge_ratio: float = 2.0) -> PressureLaw:
    """Pressure rising from the middle to both edges: p = c (1 + b |2 xi - 1|^n).

    ``edge_ratio`` = p(edge) / p(middle) = 1 + b >= 1, ``exponent`` n > 0 (2: parabolic); c
    makes the mean 1. With z = 2 xi - 1, the integrals are exact polynomials in |z|.
    """
    n = float(exponent)
    if not (math.isfinite(n) and n > 0.0):
        raise ParameterError(f"pressure-law exponent must be > 0, got {exponent!r}")
    r = float(edge_ratio)
    if not (math.isfinite(r) and r >= 1.0):
        raise ParameterError(f"pressure-law edge ratio must be >= 1, got {edge_ratio!r}")
    b = r - 1.0
    c = 1.0 / (1.0 + b / (n + 1.0))
    # P, PP: with z = 2 xi - 1, exact polynomials in |z| (models/layer.py)
    return _compiled_law(f"power(n={n:g}, edge_ratio={r:g})", kernel.LAW_POWER,
                         np.array([[c, b, n, n if n.is_integer() and n <= kernel.WHOLE_EXPONENTS
                                    else 0.0]]),
                         f"p = c (1 + {b:g} |2x/L - 1|^{n:g}), edges {r:g} x the middle")


def table_law(position: ArrayLike, pressure: ArrayLike, length: float) -> PressureLaw:
    """A measured or computed pressure, linear between the points given (x in mm from the end
    x = 0 of the clamped zone, any pressure unit: the shape is normalised to a mean of 1).

    The points must start at x = 0, end at x = ``length`` and increase; pressures >= 0 with a
    positive mean. Integrals are exact for the piecewise-linear shape.
    """
    x = np.asarray(position, dtype=float) / float(length)
    p = np.asarray(pressure, dtype=float)
    if x.ndim != 1 or x.shape != p.shape or x.size < 2:
        raise ParameterError("a pressure table needs two columns of equal length, >= 2 rows")
    if not (np.all(np.isfinite(x)) and np.all(np.isfinite(p))):
        raise ParameterError("a pressure table must hold finite numbers only")
    if abs(x[0]) > 1e-9 or abs(x[-1] - 1.0) > 1e-9 or np.any(np.diff(x) <= 0.0):
        raise ParameterError(
            f"pressure-table positions must increase from 0 to the clamped length {length:g} mm,"
            f" got {x[0] * length:g} ... {x[-1] * length:g} mm")
    if np.any(p < 0.0):
        raise ParameterError(f"pressure-table values must be >= 0, got {float(p.min()):g}")
    x[0], x[-1] = 0.0, 1.0
    h = np.diff(x)
    mean = float(np.sum(0.5 * (p[:-1] + p[1:]) * h))
    if mean <= 0.0:
        raise ParameterError("a pressure table must have a positive mean")
    p = p / mean
    slope = np.diff(p) / h
    # at the nodes: P (exact trapezoid sums) and PP (exact integral of the quadratic P)
    big_p = np.concatenate(([0.0], np.cumsum(0.5 * (p[:-1] + p[1:]) * h)))
    big_pp = np.concatenate(([0.0], np.cumsum(big_p[:-1] * h + p[:-1] * h**2 / 2
                                              + slope * h**3 / 6)))

    mirrored = np.interp(1.0 - x, x, p)
    data = np.zeros((5, x.size))
    data[0], data[1], data[2, :-1], data[3], data[4] = x, p, slope, big_p, big_pp
    return _compiled_law(f"table({x.size} points)", kernel.LAW_TABLE, data,
                         "piecewise-linear pressure from a table", symmetric=bool(
                             np.allclose(mirrored, p, rtol=1e-12, atol=1e-12)))


def read_pressure_table(path: str, length: float) -> PressureLaw:
    """A :func:`table_law` from a CSV file with the header ``x_mm,pressure``."""
    import csv

    try:
        with open(path, newline="", encoding="utf-8") as fh:
            rows = list(csv.DictReader(fh))
    except OSError as exc:
        raise ParameterError(f"cannot read pressure table {path}: {exc.strerror}") from None
    if not rows or set(rows[0]) != {"x_mm", "pressure"}:
        raise ParameterError(f"pressure table {path} needs exactly the columns x_mm,pressure")
    try:
        x = [float(r["x_mm"]) for r in rows]
        p = [float(r["pressure"]) for r in rows]
    except (TypeError, ValueError):
        raise ParameterError(f"pressure table {path} holds a value that is not a number") from None
    return table_law(x, p, length)


#: Named pressure laws (``table`` and ``fe`` laws are built from data).
PRESSURE_LAWS: dict[str, Callable[[], PressureLaw]] = {
    "uniform": _uniform,
    "parabolic": lambda: power_law(2.0, 2.0),
}


def pressure_law(name: str) -> PressureLaw:
    """The registered law called ``name``."""
    try:
        return PRESSURE_LAWS[name]()
    except KeyError:
        raise ParameterError(
            f"unknown pressure law {name!r}; choose one of {', '.join(PRESSURE_LAWS)}"
        ) from None


def layer_stiffness(params: ClampParams, stick_slope: float, *, shear_lag: bool = True) -> float:
    """Shear-layer stiffness per unit length k, N/mm^2 (contact in series with shear lag).

    ``stick_slope`` is the contact's tangential stiffness per unit area, N/mm^3 (math.inf: a
    rigid contact). ``shear_lag`` adds the body's through-thickness shear compliance
    t / (3 G w); without it and with a rigid contact, k is infinite (the paper's foundation).
    """
    if not stick_slope > 0.0:
        raise ParameterError(f"stick slope must be > 0 N/mm^3, got {stick_slope!r}")
    return float(kernel.layer_k(params.width, params.thickness, params.modulus,
                                params.poisson_ratio, float(stick_slope), int(shear_lag)))


@dataclass(frozen=True)
class Domain:
    """One loaded domain of the clamped zone: from the loaded section at xi0 = x0 / L it runs a
    length ``length`` (mm) in the direction ``direction`` (+1 towards x = L, -1 towards x = 0).

    ``axial`` E A (N), ``k`` the layer stiffness per unit length (N/mm^2, inf: rigid),
    ``limit`` mu F_N of the whole clamped zone (N), ``span`` its length L (mm); the line
    friction limit is q = (limit / span) p(xi) with s the distance from the loaded section.
    The arithmetic is :mod:`microslip.models.layer`'s, on :attr:`constants`.
    """

    length: float
    axial: float
    k: float
    limit: float
    span: float
    law: PressureLaw
    xi0: float
    direction: float

    @property
    def constants(self) -> tuple[float, ...]:
        """The compiled domain (:func:`microslip.models.layer.domain_constants`)."""
        return tuple(kernel.domain_constants(self.length, self.axial, self.k, self.limit,
                                             self.span, self.xi0, self.direction,
                                             self.law.code, self.law.data))

    @property
    def total(self) -> float:
        """The domain's macroslip force, N."""
        return float(self.constants[11])

    @property
    def onset(self) -> float:
        """F(0), the load at which the domain starts to slip, N."""
        return float(self.constants[12])

    def force(self, a: ArrayLike) -> FloatArray:
        """F(a): the load that puts the slip front at a."""
        dom, law = self.constants, self.law
        return np.array([kernel.domain_force(dom, law.code, law.data, float(x))[0]
                         for x in np.atleast_1d(np.asarray(a, dtype=float))])

    def stuck_stiffness(self) -> float:
        return float(self.constants[13])


def tip_domain(params: ClampParams, k: float, law: PressureLaw) -> Domain:
    """The tip-loaded bar: loaded at x = L, one domain of length L."""
    return Domain(params.length, params.axial_stiffness, k, params.macroslip_force,
                  params.length, law, 1.0, -1.0)


def centre_domains(params: ClampParams, k: float, law: PressureLaw) -> tuple[Domain, Domain]:
    """The centre-loaded bar: tension (towards x = L) and compression (towards 0) halves."""
    half = 0.5 * params.length

    def domain(sign: float) -> Domain:
        return Domain(half, params.axial_stiffness, k, params.macroslip_force, params.length,
                      law, 0.5, sign)

    return domain(1.0), domain(-1.0)


def slip_front(bar: Domain, force: ArrayLike) -> FloatArray:
    """The slip front a(F) in [0, L] (a = 0 before slip), :func:`~microslip.models.layer.front`."""
    return backbone_force(bar, force, check=False)[0]


def backbone_force(bar: Domain, force: ArrayLike, *,
                   check: bool = True) -> tuple[FloatArray, FloatArray]:
    """(slip front a, displacement d) of the virgin curve at the forces given, mm."""
    f = np.asarray(force, dtype=float)
    if check and np.any(f >= bar.total):
        raise ParameterError(f"force must stay below the macroslip force {bar.total:g} N")
    flat = np.ascontiguousarray(f.reshape(-1))
    curve = _run(kernel.domain_curve, flat.size * LAYER_STEP)
    a, d = curve(bar.constants, bar.law.code, bar.law.data, flat)
    return a.reshape(f.shape), d.reshape(f.shape)


def tip_backbone(params: ClampParams, force: ArrayLike, *, stick_slope: float = math.inf,
                 shear_lag: bool = True,
                 law: PressureLaw | None = None) -> tuple[FloatArray, FloatArray]:
    """Exact virgin curve of the tip-loaded bar on a shear layer: (a, d) at ``force``, mm."""
    k = layer_stiffness(params, stick_slope, shear_lag=shear_lag)
    return backbone_force(tip_domain(params, k, law or _uniform()), force)


#: Load cases of the 1-D interface model: the domains that the load acts on in parallel.
LOADINGS: dict[str, Callable[[ClampParams, float, PressureLaw], tuple[Domain, ...]]] = {
    "tip": lambda p, k, law: (tip_domain(p, k, law),),
    "centre": centre_domains,
}


def _curve(domains: tuple[Domain, ...], f: FloatArray,
           law: PressureLaw) -> tuple[FloatArray, FloatArray]:
    """(slip of each domain, d) with the load shared by equal displacement of all domains."""
    if len(domains) == 1:
        a, d = backbone_force(domains[0], f, check=False)
        return a[None, :], d
    first, second = domains
    if law.symmetric:
        share = f / len(domains)
        (a1, d), (a2, _) = (backbone_force(first, share, check=False),
                            backbone_force(second, share, check=False))
        return np.array([a1, a2]), d
    curve = _run(kernel.split_curve, f.size * LAYER_STEP)
    a1, a2, d = curve(first.constants, second.constants, law.code, law.data, f)
    return np.array([a1, a2]), d


def virgin_curve(loading: str, params: ClampParams, force: ArrayLike, *,
                 stick_slope: float = math.inf, shear_lag: bool = True,
                 law: PressureLaw | None = None) -> tuple[FloatArray, FloatArray]:
    """Exact virgin curve of a tip- or centre-loaded bar on a shear layer with pressure law.

    Returns ``(slip, d)``: the slip length of each domain, shape (domains, len(force)), mm, and
    the displacement of the loaded section, mm.
    """
    try:
        build = LOADINGS[loading]
    except KeyError:
        raise ParameterError(
            f"unknown loading {loading!r}; choose one of {', '.join(LOADINGS)}") from None
    law = law or _uniform()
    f = np.ascontiguousarray(np.asarray(force, dtype=float).reshape(-1))
    domains = build(params, layer_stiffness(params, stick_slope, shear_lag=shear_lag), law)
    limit = sum(d.total for d in domains)
    if np.any(f >= limit) or np.any(f < 0.0):
        raise ParameterError(
            f"force must lie in [0, {limit:g}) N (below the macroslip force), got "
            f"{float(np.max(f)):g} N")
    return _curve(domains, f, law)


def masing_dissipation(loading: str, params: ClampParams, amplitude: float, *,
                       stick_slope: float = math.inf, shear_lag: bool = True,
                       law: PressureLaw | None = None, nodes: int = 64) -> tuple[float, float]:
    """(W_d, d0): energy dissipated per Masing cycle of amplitude F0 (N mm) and peak d (mm).

    W_d = 4 F0 d0 - 8 integral_0^F0 g(F) dF. The virgin curve g is linear up to the slip
    onset F1 and smooth after it, so the integral is exact on [0, F1] and Gauss-Legendre with
    ``nodes`` points on [F1, F0] (converged to rounding at the default).
    """
    def curve(force: ArrayLike) -> FloatArray:
        return virgin_curve(loading, params, force, stick_slope=stick_slope,
                            shear_lag=shear_lag, law=law)[1]

    f0 = float(amplitude)
    d0 = float(curve(np.array([f0]))[0])
    f1 = _slip_onset(loading, params, stick_slope=stick_slope, shear_lag=shear_lag, law=law)
    if f0 <= f1:
        return 0.0, d0
    x, wts = np.polynomial.legendre.leggauss(nodes)
    f = 0.5 * (f0 - f1) * x + 0.5 * (f0 + f1)
    d = curve(f)
    d1 = float(curve(np.array([f1]))[0])
    area = 0.5 * f1 * d1 + 0.5 * (f0 - f1) * float(wts @ d)
    return max(4.0 * f0 * d0 - 8.0 * area, 0.0), d0


def _slip_onset(loading: str, params: ClampParams, *, stick_slope: float, shear_lag: bool,
                law: PressureLaw | None) -> float:
    """The load at which the first domain starts to slip, N (0 on a rigid foundation)."""
    law = law or _uniform()
    domains = LOADINGS[loading](params, layer_stiffness(params, stick_slope, shear_lag=shear_lag),
                                law)
    if math.isinf(domains[0].k):
        return 0.0
    onsets = [d.onset for d in domains]
    # Before slip the domains share the load in proportion to their stuck stiffnesses.
    stiff = np.array([d.stuck_stiffness() for d in domains])
    return float(min(o * stiff.sum() / k for o, k in zip(onsets, stiff, strict=True)))
