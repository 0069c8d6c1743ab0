"""Planar load paths: a start-up from rest, then one closed cycle of named force components.

A :class:`LoadPath` is a sampled in-plane load history on the clamp: the force along the bar
(component ``tip``, on the end face) and at mid-length (component ``centre``, across the bar
for the planar cases) at load parameters theta, ending with one closed cycle. The analytical
planar model (:mod:`microslip.planar.loadpath`) and the built-in FE solver
(:func:`microslip.fe.builtin.solve_load_path`) take the same object; it is validated once, here.

One harmonic convention: F_tip = A_t sin(theta), F_centre = A_c sin(theta + phi), the centre
force ahead by phi; samples one period apart are equal bit for bit. Two start-ups:
:meth:`LoadPath.harmonic` runs the sine from theta = 0 for at least half a cycle (each force
passes its peak once, so a Masing model is on its loop); :meth:`LoadPath.ramped` reaches the
cycle's first sample theta = pi/2 along a straight ramp from zero load (for phi = 0 the
paper's first quarter period). Units: N, radians.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..conventions import CLAMP_MODELS, check_whole
from ..errors import ParameterError

__all__ = ["CLOSE_TOL", "COMPONENTS", "LoadPath"]

FloatArray = NDArray[np.float64]

#: Relative tolerance on the closure of a cycle's forces (the last sample is snapped).
CLOSE_TOL = 1e-9
#: Force components of a planar load path: the clamp's two models.
COMPONENTS = CLAMP_MODELS


def _count(name: str, value: Any, lower: int, upper: int = 10_000_000) -> int:
    return check_whole(name, value, lower, upper)


def _non_negative(x: Any, name: str) -> float:
    try:
        v = float(x)
    except (TypeError, ValueError):
        raise ParameterError(f"{name} must be a number >= 0 N, got {x!r}") from None
    if not (math.isfinite(v) and v >= 0.0):
        raise ParameterError(f"{name} must be finite and >= 0 N, got {x!r}")
    return v


def _harmonic_args(tip_amplitude: Any, centre_amplitude: Any, phase_deg: Any, n: Any,
                   n_name: str) -> tuple[float, float, float, int]:
    at = _non_negative(tip_amplitude, "tip amplitude")
    ac = _non_negative(centre_amplitude, "centre amplitude")
    if at == 0.0 and ac == 0.0:
        raise ParameterError("at least one of the tip and centre amplitudes must be > 0 N")
    try:
        phi = float(phase_deg)
    except (TypeError, ValueError):
        raise ParameterError(f"phase must be an angle in degrees, got {phase_deg!r}") from None
    if not math.isfinite(phi):
        raise ParameterError(f"phase must be a finite angle in degrees, got {phase_deg!r}")
    if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 8:
        raise ParameterError(f"{n_name} must be a whole number >= 8, got {n!r}")
    return at, ac, phi, int(n)


def _ramp_to(theta: FloatArray, ft: FloatArray, fc: FloatArray, k0: int, m: int
             ) -> tuple[FloatArray, FloatArray, FloatArray, int]:
    """Prepend a straight ramp of ``m`` increments from zero load to the first sample."""
    if m <= 1:
        return theta, ft, fc, k0
    s = np.arange(1, m) / m
    step = float(theta[1] - theta[0]) if theta.size > 1 and theta[1] > theta[0] else 1.0
    th = np.r_[theta[0] - step * np.arange(m - 1, 0, -1), theta]
    return th, np.r_[ft[0] * s, ft], np.r_[fc[0] * s, fc], k0 + m - 1


def _as_vectors(theta: ArrayLike, ft: ArrayLike, fc: ArrayLike
                ) -> tuple[FloatArray, FloatArray, FloatArray]:
    th, a, b = (np.array(x, dtype=float) for x in (theta, ft, fc))
    if th.ndim != 1 or th.shape != a.shape or th.shape != b.shape:
        raise ParameterError(
            "a load path needs 1-D theta, tip_force and centre_force of equal length, got "
            f"shapes {th.shape}, {a.shape}, {b.shape}")
    if not (np.all(np.isfinite(th)) and np.all(np.isfinite(a)) and np.all(np.isfinite(b))):
        raise ParameterError("a load path's theta and forces must be finite numbers")
    return th, a, b


@dataclass(frozen=True, eq=False)
class LoadPath:
    """A sampled planar load history on the whole clamp, ending with one closed cycle.

    Attributes
    ----------
    theta : ndarray, shape (K,)
        Load parameter (angle of the cycle, radians, or time), non-decreasing.
    tip_force : ndarray, shape (K,)
        Total force along the bar on the clamp, N (the paper's tip loading; for the paper's
        half model it is :data:`~microslip.planar.trajectories.TIP_SYMMETRY` times the model
        force).
    centre_force : ndarray, shape (K,)
        Force at mid-length, N (the paper's centre loading).
    cycle_start : int
        Samples ``cycle_start`` to ``K - 1`` (at least 3) form the closed cycle: the forces
        at both ends are equal (to 1e-9 of the largest force; the last sample is snapped).
        The samples before it are the start-up from the unloaded state.
    meta : dict
        What the producer wants recorded (amplitudes, phase, ...).

    Examples
    --------
    >>> p = LoadPath.harmonic(1000.0, 500.0, phase_deg=90.0, samples_per_cycle=8)
    >>> p.cycle_start, p.theta.size, p.tip_force[p.cycle_start:].round(3).tolist()[:3]
    (4, 13, [0.0, -707.107, -1000.0])
    """

    theta: FloatArray
    tip_force: FloatArray
    centre_force: FloatArray
    cycle_start: int = 0
    meta: dict[str, Any] = field(default_factory=dict)

    def __post_init__(self) -> None:
        th, ft, fc = _as_vectors(self.theta, self.tip_force, self.centre_force)
        if th.size < 3:
            raise ParameterError(f"a load path needs at least 3 samples, got {th.size}")
        if np.any(np.diff(th) < 0.0):
            raise ParameterError("a load path's theta must be non-decreasing")
        k0 = _count("cycle_start", self.cycle_start, 0, th.size - 3)
        scale = max(float(np.max(np.abs(ft))), float(np.max(np.abs(fc))))
        for name, f in (("tip", ft), ("centre", fc)):
            if abs(f[-1] - f[k0]) > CLOSE_TOL * scale:
                raise ParameterError(
                    f"the {name} force of the cycle does not close: {f[k0]:g} N at its start, "
                    f"{f[-1]:g} N at its end")
            f[-1] = f[k0]
        for a in (th, ft, fc):
            a.setflags(write=False)
        object.__setattr__(self, "theta", th)
        object.__setattr__(self, "tip_force", ft)
        object.__setattr__(self, "centre_force", fc)
        object.__setattr__(self, "cycle_start", k0)

    @classmethod
    def harmonic(cls, tip_amplitude: float, centre_amplitude: float, phase_deg: float = 0.0,
                 samples_per_cycle: int = 2048, startup: float = 0.5) -> LoadPath:
        """The harmonic path from theta = 0, the closed cycle after ``startup`` cycles.

        Parameters
        ----------
        tip_amplitude, centre_amplitude : float
            A_t and A_c, N (>= 0, not both 0; total forces on the clamp).
        phase_deg : float
            phi, degrees. 0 is the paper's zero-phase loading (a straight line in the force
            plane); 90 traces the ellipse of Fig. 1.
        samples_per_cycle : int
            Samples of one cycle (>= 8).
        startup : float
            Cycles before the closed one (>= 0.5, so that each force has passed its peak
            once and a Masing model is on its steady loop).
        """
        at, ac, phi, n = _harmonic_args(tip_amplitude, centre_amplitude, phase_deg,
                                        samples_per_cycle, "samples_per_cycle")
        if not (math.isfinite(startup) and startup >= 0.5):
            raise ParameterError(f"startup must be >= 0.5 cycles, got {startup!r}")
        k0 = round(startup * n)
        j = np.arange(k0 + n + 1)
        theta = 2.0 * np.pi * j / n
        wrapped = np.where(j == k0 + n, theta[k0], theta)  # the cycle's ends: one sample
        return cls(theta, at * np.sin(wrapped), ac * np.sin(wrapped + math.radians(phi)), k0,
                   meta={"tip_amplitude_N": at, "centre_amplitude_N": ac, "phase_deg": phi,
                         "samples_per_cycle": n})

    @classmethod
    def ramped(cls, tip_amplitude: float, centre_amplitude: float, phase_deg: float = 0.0,
               increments_per_cycle: int = 64, startup: float = 0.25) -> LoadPath:
        """The harmonic path with its cycles from theta = pi/2 (the tip force's peak, like the
        paper's t = 0.25 s), reached from rest along a straight ramp of ``startup`` cycles'
        worth of increments (0 < startup <= 10). For phi = 0 the ramp is the paper's first
        quarter period; for other phases it avoids a jump to a finite force.

        >>> p = LoadPath.ramped(2.0, 1.0, 90.0, 8)
        >>> p.cycle_start, p.tip_force[:4].round(3).tolist(), p.centre_force[:4].round(3).tolist()
        (1, [1.0, 2.0, 1.414, 0.0], [0.0, 0.0, -0.707, -1.0])
        """
        at, ac, phi, n = _harmonic_args(tip_amplitude, centre_amplitude, phase_deg,
                                        increments_per_cycle, "increments_per_cycle")
        if not (math.isfinite(startup) and 0.0 < startup <= 10.0):
            raise ParameterError(f"startup must be in (0, 10] cycles, got {startup!r}")
        j = np.arange(n + 1)
        theta = 0.5 * np.pi + 2.0 * np.pi * j / n
        wrapped = 0.5 * np.pi + 2.0 * np.pi * (j % n) / n  # equal samples one period apart
        ft = at * np.sin(wrapped)
        fc = ac * np.sin(wrapped + math.radians(phi))
        th, ft, fc, k0 = _ramp_to(theta, ft, fc, 0, max(1, round(startup * n)))
        return cls(th, ft, fc, k0, {"tip_amplitude_N": at, "centre_amplitude_N": ac,
                                    "phase_deg": phi, "increments_per_cycle": n})

    @classmethod
    def from_cycle(cls, times: ArrayLike, f_tip: ArrayLike, f_centre: ArrayLike, *,
                   startup_increments: int | None = None) -> LoadPath:
        """The path of one sampled cycle (strictly increasing ``times``, forces in N): closed
        if its last sample differs from its first, and reached from rest along a straight ramp
        of ``startup_increments`` (default a quarter of the cycle's; none from rest)."""
        t, ft, fc = _as_vectors(times, f_tip, f_centre)
        if t.size < 3:
            raise ParameterError(f"a cycle needs at least 3 samples, got {t.size}")
        if np.any(np.diff(t) <= 0.0):
            raise ParameterError("times must be strictly increasing")
        scale = max(float(np.max(np.abs(ft))), float(np.max(np.abs(fc))))
        if not scale > 0.0:
            raise ParameterError("a load path needs a non-zero force")
        if max(abs(ft[-1] - ft[0]), abs(fc[-1] - fc[0])) > CLOSE_TOL * scale:
            step = float(np.mean(np.diff(t)))
            t, ft, fc = np.r_[t, t[-1] + step], np.r_[ft, ft[0]], np.r_[fc, fc[0]]
        n = t.size - 1
        at_rest = max(abs(ft[0]), abs(fc[0])) <= CLOSE_TOL * scale
        if startup_increments is None:
            m = 0 if at_rest else max(1, n // 4)
        else:
            m = _count("startup_increments", startup_increments, 0)
        t, ft, fc, k0 = _ramp_to(t, ft, fc, 0, m)
        return cls(t, ft, fc, k0, {"startup_increments": m, "prepended_samples": max(m - 1, 0)})

    def from_rest(self, startup_increments: int | None = None) -> LoadPath:
        """This path, reached from rest: if its first sample is a jump from zero load (larger
        than every later increment of the path), a straight ramp of ``startup_increments``
        (default a quarter of the cycle's increments) is prepended and recorded in
        ``meta["prepended_samples"]``; otherwise the path itself."""
        f = np.column_stack([self.tip_force, self.centre_force])
        first = float(np.hypot(*f[0]))
        steps = np.hypot(*np.diff(f, axis=0).T)
        if first <= CLOSE_TOL * float(np.max(np.abs(f))) or first <= float(np.max(steps)) * (
                1.0 + CLOSE_TOL):
            return self
        m = (startup_increments if startup_increments is not None
             else max(1, self.samples_per_cycle // 4))
        th, ft, fc, k0 = _ramp_to(self.theta, self.tip_force, self.centre_force,
                                  self.cycle_start, _count("startup_increments", m, 0))
        return LoadPath(th, ft, fc, k0, {**self.meta, "startup_ramp_increments": m,
                                         "prepended_samples": max(m - 1, 0)})

    @property
    def cycle(self) -> slice:
        """The samples of the closed cycle."""
        return slice(self.cycle_start, None)

    @property
    def samples_per_cycle(self) -> int:
        """Increments of one cycle."""
        return int(self.theta.size - 1 - self.cycle_start)

    def forces(self) -> Mapping[str, FloatArray]:
        """The force of each component (:data:`COMPONENTS`), N."""
        return {"tip": self.tip_force, "centre": self.centre_force}

    @property
    def tip_amplitude(self) -> float:
        """Largest |F_tip| over the cycle, N."""
        return float(np.max(np.abs(self.tip_force[self.cycle])))

    @property
    def centre_amplitude(self) -> float:
        """Largest |F_centre| over the cycle, N."""
        return float(np.max(np.abs(self.centre_force[self.cycle])))

    @property
    def peak_resultant(self) -> float:
        """Largest |(F_tip, F_centre)| over the path, N."""
        return float(np.max(np.hypot(self.tip_force, self.centre_force)))

    def only(self, component: str) -> LoadPath:
        """The same path with every other component set to zero."""
        if component not in COMPONENTS:
            raise ParameterError(f"component must be one of {', '.join(COMPONENTS)}, got "
                                 f"{component!r}")
        f = {k: (v if k == component else np.zeros_like(v)) for k, v in self.forces().items()}
        return LoadPath(self.theta, f["tip"], f["centre"], self.cycle_start,
                        {**self.meta, "only": component})

    def repeated(self, cycles: int) -> tuple[FloatArray, FloatArray, FloatArray]:
        """theta, F_tip, F_centre of the start-up and ``cycles`` cycles (shared ends once).

        Sample 0 is the first sample of the path (applied from the clamped state); cycle c
        (0-based) occupies samples ``cycle_start + c n .. cycle_start + (c + 1) n``.
        """
        k0 = self.cycle_start
        period = float(self.theta[-1] - self.theta[k0])
        c = np.arange(cycles)
        th = np.concatenate([self.theta[:k0 + 1]]
                            + [self.theta[k0 + 1:] + period * (i + 1) - period for i in c])
        ft = np.concatenate([self.tip_force[:k0 + 1]] + [self.tip_force[k0 + 1:]] * cycles)
        fc = np.concatenate([self.centre_force[:k0 + 1]]
                            + [self.centre_force[k0 + 1:]] * cycles)
        return th, ft, fc
