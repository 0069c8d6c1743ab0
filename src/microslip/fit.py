"""Identify a clamp's friction and contact stiffness from measured hysteresis loops.

A measured loop (force N, displacement mm, in the order they were sampled) is compared with
the Masing loop of the 1-D interface model (:mod:`microslip.models.interface`: the bar on a
shear layer with the body's shear lag) at the loop's own force amplitude. The residual is the
displacement error at every sample; the parameters are found by ``scipy.optimize.least_squares``
(trust-region reflective, bounded), with the positive ones on a log scale. Confidence intervals
come from the Jacobian at the optimum, cov = s^2 (J^T J)^-1 with s^2 = SSR / (m - n), and
Student's t; a parameter whose interval is unbounded, or which the data cannot tell apart
from another (|correlation| > :data:`MAX_CORRELATION`), is reported as not identified.

Each loop is centred first (the mid-points of its force and displacement ranges), because a
rig's zero is arbitrary; its amplitude F0 is half its peak-to-peak force. The samples of a
descending branch (force falling) follow d = d0 - 2 g((F0 - F)/2), of an ascending branch
d = -d0 + 2 g((F0 + F)/2), with g the model's virgin curve (Masing's rule).
"""

from __future__ import annotations

import csv
import dataclasses
import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray
from scipy import optimize, stats

from .conventions import DEFAULT_STICK_SLOPE
from .errors import ParameterError
from .io import LOOP_COLUMNS
from .models.interface import PressureLaw, virgin_curve
from .named import result
from .params import ClampParams

__all__ = [
    "FIT_PARAMETERS",
    "MAX_CORRELATION",
    "FitParameter",
    "FitResult",
    "MeasuredLoop",
    "fit_loops",
    "read_loop_csv",
]

FloatArray = NDArray[np.float64]

#: Correlation above which two fitted parameters count as not separately identified.
MAX_CORRELATION = 0.999
#: Singular values of the Jacobian (log parameters) below this fraction of the largest span
#: its null space (a parameter that moves the loop by a millionth of the others' effect), and
#: a parameter with a component above :data:`NULL_SHARE` in it is not identified: its
#: interval is its whole range, and it is nobody's correlation partner.
NULL_SPACE, NULL_SHARE = 1e-6, 0.1


@dataclass(frozen=True)
class FitSpec:
    """A parameter that can be fitted: unit, bounds, and where it goes in the model."""

    unit: str
    bounds: tuple[float, float]
    #: (known clamp, stick slope, value) -> (clamp, stick slope) with the value put in
    apply: Callable[[ClampParams, float, float], tuple[ClampParams, float]]
    #: (known clamp, stick slope) -> the starting value
    start: Callable[[ClampParams, float], float]
    #: the gross-sliding force mu F_N grows in proportion to this parameter
    sets_limit: bool = False


def _clamp_field(unit: str, bounds: tuple[float, float], name: str,
                 sets_limit: bool = False) -> FitSpec:
    return FitSpec(unit, bounds, lambda p, slope, v: (dataclasses.replace(p, **{name: v}), slope),
                   lambda p, slope: float(getattr(p, name)), sets_limit)


#: What ``fit_loops`` can identify; every one is fitted on a log scale.
FIT_PARAMETERS: dict[str, FitSpec] = {
    "friction": _clamp_field("", (1e-3, 10.0), "friction", sets_limit=True),
    "stick_slope": FitSpec("N/mm^3", (1e1, 1e10), lambda p, slope, v: (p, v),
                           lambda p, slope: slope),
    "normal_force": _clamp_field("N", (1e-3, 1e9), "normal_force", sets_limit=True),
    "modulus": _clamp_field("MPa", (1e1, 1e8), "modulus"),
}


@result
class MeasuredLoop:
    """One measured loop: force (N) and displacement (mm) in sampling order."""

    force: FloatArray
    displacement: FloatArray
    source: str = ""

    @property
    def amplitude(self) -> float:
        """Half the peak-to-peak force, N."""
        return float(0.5 * (self.force.max() - self.force.min()))

    def centred(self) -> tuple[FloatArray, FloatArray]:
        """Force (N) and displacement (mm) about the middle of their ranges: the loop as the
        fit sees it."""
        f = self.force - 0.5 * (self.force.max() + self.force.min())
        d = self.displacement - 0.5 * (self.displacement.max() + self.displacement.min())
        return f, d


def read_loop_csv(path: str) -> MeasuredLoop:
    """A loop from a CSV file with the columns ``force_N,displacement_mm`` (as microslip
    writes loops); other columns are ignored."""
    try:
        with open(path, newline="", encoding="utf-8") as fh:
            rows = list(csv.DictReader(fh))
    except OSError as exc:
        raise ParameterError(f"cannot read loop file {path}: {exc.strerror}") from None
    except UnicodeDecodeError:
        raise ParameterError(f"loop file {path} is not a text CSV file") from None
    fn, dn = LOOP_COLUMNS
    if not rows or not {fn, dn} <= set(rows[0]):
        raise ParameterError(f"loop file {path} needs the columns {fn},{dn}")
    try:
        f = np.array([float(r[fn]) for r in rows])
        d = np.array([float(r[dn]) for r in rows])
    except (TypeError, ValueError):
        raise ParameterError(f"loop file {path} holds a value that is not a number") from None
    if f.size < 8 or not (np.all(np.isfinite(f)) and np.all(np.isfinite(d))):
        raise ParameterError(f"loop file {path} needs >= 8 finite samples, got {f.size}")
    if np.ptp(f) <= 0.0 or np.ptp(d) <= 0.0:
        raise ParameterError(f"loop file {path} has no force or displacement range")
    return MeasuredLoop(f, d, str(path))


@result
class FitParameter:
    """One identified parameter with its confidence interval (same unit)."""

    name: str
    value: float
    low: float
    high: float
    unit: str
    identified: bool
    note: str = ""


@result
class FitResult:
    """The fitted parameters, the fit quality and the model's loops at the optimum."""

    model: str
    parameters: tuple[FitParameter, ...]
    params: ClampParams
    stick_slope: float
    confidence: float
    rms_residual_mm: float
    r_squared: float
    points: int
    loops: tuple[MeasuredLoop, ...]
    predicted: tuple[FloatArray, ...]

    def summary(self) -> dict[str, object]:
        out: dict[str, object] = {"model": self.model, "confidence": self.confidence}
        for p in self.parameters:
            out[p.name] = p.value
            out[f"{p.name}_low"] = p.low
            out[f"{p.name}_high"] = p.high
            out[f"{p.name}_unit"] = p.unit or "-"
            out[f"{p.name}_identified"] = p.identified
            if p.note:
                out[f"{p.name}_note"] = p.note
        out["rms_residual_mm"] = self.rms_residual_mm
        out["r_squared"] = self.r_squared
        out["points"] = self.points
        return out


def _centred(loop: MeasuredLoop) -> tuple[FloatArray, FloatArray, float]:
    return (*loop.centred(), loop.amplitude)


def _predict(loading: str, p: ClampParams, slope: float, law: PressureLaw | None,
             f: FloatArray, f0: float) -> FloatArray:
    """The Masing loop's displacement at the measured forces (branch from the force's trend)."""
    falling = np.gradient(f) < 0.0
    arg = np.where(falling, 0.5 * (f0 - f), 0.5 * (f0 + f))
    arg = np.clip(arg, 0.0, f0)
    g = virgin_curve(loading, p, np.concatenate((arg, [f0])), stick_slope=slope, law=law)[1]
    d0 = g[-1]
    return np.where(falling, d0 - 2.0 * g[:-1], -d0 + 2.0 * g[:-1])


def fit_loops(loops: Sequence[MeasuredLoop], loading: str, params: ClampParams, *,
              fit: Sequence[str] = ("friction", "stick_slope"),
              stick_slope: float = DEFAULT_STICK_SLOPE,
              law: PressureLaw | None = None, confidence: float = 0.95) -> FitResult:
    """Fit the parameters named in ``fit`` to one or more measured loops.

    ``params`` and ``stick_slope`` (N/mm^3) hold the known values and the start of the fitted
    ones. Raises ParameterError for unknown names or loops beyond the model's gross sliding.
    """
    names = list(dict.fromkeys(fit))
    unknown = [n for n in names if n not in FIT_PARAMETERS]
    if unknown or not names:
        raise ParameterError(f"cannot fit {unknown or 'nothing'}; choose from "
                             f"{', '.join(FIT_PARAMETERS)}")
    if not 0.5 <= confidence < 1.0:
        raise ParameterError(f"confidence must lie in [0.5, 1), got {confidence!r}")
    data = [_centred(loop) for loop in loops]
    if not data:
        raise ParameterError("give at least one measured loop")
    f0_max = max(f0 for _, _, f0 in data)

    def model_at(z: FloatArray) -> tuple[ClampParams, float]:
        p, slope = params, stick_slope
        for name, value in zip(names, np.exp(z), strict=True):
            p, slope = FIT_PARAMETERS[name].apply(p, slope, float(value))
        return p, slope

    def residual(z: FloatArray) -> FloatArray:
        p, slope = model_at(z)
        if p.macroslip_force <= f0_max * (1.0 + 1e-9):
            return np.full(sum(f.size for f, _, _ in data), 1e3)  # beyond gross sliding
        return np.concatenate([_predict(loading, p, slope, law, f, f0) - d
                               for f, d, f0 in data])

    start = np.log([FIT_PARAMETERS[n].start(params, stick_slope) for n in names])
    shortfall = 1.5 * f0_max / model_at(start)[0].macroslip_force
    if shortfall > 1.0:  # start below the loops' amplitude: raise mu F_N to 1.5 F0
        movable = [i for i, n in enumerate(names) if FIT_PARAMETERS[n].sets_limit]
        if not movable:
            raise ParameterError(
                f"the loops reach {f0_max:g} N, beyond the clamp's gross-sliding force "
                f"{model_at(start)[0].macroslip_force:g} N = mu F_N; fit friction or give "
                "the right clamp")
        start[movable[0]] += math.log(shortfall)
    lower = np.log([FIT_PARAMETERS[n].bounds[0] for n in names])
    upper = np.log([FIT_PARAMETERS[n].bounds[1] for n in names])
    sol = optimize.least_squares(residual, np.clip(start, lower + 1e-9, upper - 1e-9),
                                 bounds=(lower, upper), x_scale=1.0, xtol=1e-12, ftol=1e-12,
                                 gtol=1e-12)
    return _result(loading, names, sol, model_at, residual, data, loops, confidence, law)


def _result(loading: str, names: list[str], sol: optimize.OptimizeResult,
            model_at: Callable[[FloatArray], tuple[ClampParams, float]],
            residual: Callable[[FloatArray], FloatArray],
            data: list[tuple[FloatArray, FloatArray, float]], loops: Sequence[MeasuredLoop],
            confidence: float, law: PressureLaw | None) -> FitResult:
    m = sol.fun.size
    ssr = float(sol.fun @ sol.fun)
    lower = np.log([FIT_PARAMETERS[n].bounds[0] for n in names])
    upper = np.log([FIT_PARAMETERS[n].bounds[1] for n in names])
    at_bound = (sol.x - lower < 1e-3) | (upper - sol.x < 1e-3)  # within 0.1 % of a bound
    free = np.flatnonzero(~at_bound)
    jac = np.asarray(sol.jac)[:, free]
    dof = max(m - free.size, 1)
    cov = np.linalg.pinv(jac.T @ jac) * ssr / dof if free.size else np.zeros((0, 0))
    sd = np.sqrt(np.clip(np.diag(cov), 0.0, None))
    with np.errstate(invalid="ignore", divide="ignore"):
        corr = cov / np.outer(sd, sd)
    t = float(stats.t.ppf(0.5 + 0.5 * confidence, dof))
    # a parameter the loops do not move at all (a near-zero Jacobian column, or a combination
    # of columns) is in the null space of the Jacobian: only the parameters with a share in
    # that space are not identified, not every one (a stick slope the slender bar's loop does
    # not feel leaves its friction well determined)
    null = np.zeros((0, free.size), dtype=bool)
    if free.size:
        _, singular, vt = np.linalg.svd(jac, full_matrices=False)
        null = np.asarray(np.abs(vt[singular <= NULL_SPACE * singular.max()]) > NULL_SHARE,
                          dtype=bool)
    in_null = np.any(null, axis=0) if null.size else np.zeros(free.size, dtype=bool)
    out = []
    for i, name in enumerate(names):
        z, spec = float(sol.x[i]), FIT_PARAMETERS[name]
        if at_bound[i]:
            out.append(FitParameter(name, math.exp(z), math.exp(z), math.exp(z), spec.unit, False,
                                    f"{name} ran to the end of its range {spec.bounds}: the "
                                    "loops do not determine it (fix it and fit again)"))
            continue
        k = int(np.flatnonzero(free == i)[0])
        half = t * float(sd[k])
        if in_null[k]:  # the loops do not move it (alone or with others): its whole range
            with_ = [names[free[j]] for j in range(free.size)
                     if j != k and np.any(null[:, j] & null[:, k])]
            note = (f"the data cannot separate {name} from {', '.join(with_)}; fix one of them"
                    if with_ else f"the loops do not determine {name} (they hardly change "
                    "with it): fix it and fit again")
            out.append(FitParameter(name, math.exp(z), math.exp(lower[i]), math.exp(upper[i]),
                                    spec.unit, False, note))
            continue
        partners = [names[free[j]] for j in range(free.size)
                    if j != k and not in_null[j] and abs(corr[k, j]) > MAX_CORRELATION]
        identified = bool(np.isfinite(half) and 2.0 * half < math.log(10.0) and not partners
                          and not in_null[k])
        note = ""
        if partners:
            note = (f"the data cannot separate {name} from {', '.join(partners) or 'the others'}"
                    "; fix one of them")
        elif not identified:
            note = f"the loops do not determine {name}: its interval spans more than a decade"
        lo, hi = max(z - half, lower[i]), min(z + half, upper[i])  # within the range
        out.append(FitParameter(name, math.exp(z), math.exp(lo), math.exp(hi), spec.unit,
                                identified, note))
    p, slope = model_at(sol.x)
    d_all = np.concatenate([d for _, d, _ in data])
    predicted = residual(sol.x)
    pieces = np.split(predicted + d_all, np.cumsum([d.size for _, d, _ in data])[:-1])
    sst = float(np.sum((d_all - d_all.mean()) ** 2))
    return FitResult(loading, tuple(out), p, slope, confidence, math.sqrt(ssr / m),
                     1.0 - ssr / sst if sst > 0 else 0.0, m, tuple(loops), tuple(pieces))
