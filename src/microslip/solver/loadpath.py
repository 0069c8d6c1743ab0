"""Load histories for the built-in solver: the paper's 1-D sine and planar cyclic paths.

A :class:`CyclicPath` is a start-up from the unloaded, clamped state followed by one closed
cycle of the two in-plane forces, sampled arbitrarily (the solver is rate-independent:
only the order of the samples matters). The solver repeats the cycle until the energy
dissipated per cycle settles.

* ``tip`` force: along the bar (x) on the end face x = L, N;
* ``centre`` force: on the mid-length section x = L/2, across the bar (y, in the plane of
  the interface) unless the solver is told ``centre_direction="axial"``, N.

:func:`as_cyclic_path` accepts a :class:`CyclicPath`, the planar model's
``microslip.planar.loadpath.LoadPath`` (anything with ``theta``, ``tip_force``,
``centre_force`` and ``cycle_start``: duck-typed, no import), or plain arrays of one cycle.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..errors import ParameterError

__all__ = [
    "CyclicPath",
    "as_cyclic_path",
    "harmonic_path",
]

FloatArray = NDArray[np.float64]

#: Relative tolerance on the closure of a cycle's forces (the last sample is snapped).
CLOSE_TOL = 1e-9


def _count(name: str, value: Any, lower: int, upper: int = 10_000_000) -> int:
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)) \
            or not lower <= value <= upper:
        raise ParameterError(f"{name} must be a whole number in [{lower}, {upper}], got {value!r}")
    return int(value)


def _amplitude(value: Any, name: str) -> float:
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise ParameterError(f"{name} must be a number >= 0 N, got {value!r}") from None
    if not (math.isfinite(v) and v >= 0.0):
        raise ParameterError(f"{name} must be finite and >= 0 N, got {value!r}")
    return v


@dataclass(frozen=True, eq=False)
class CyclicPath:
    """Start-up samples, then one closed cycle of the tip and centre forces.

    Attributes
    ----------
    theta : ndarray, shape (K,)
        Load parameter of every sample (radians for harmonic paths, or time), non-decreasing.
    f_tip, f_centre : ndarray, shape (K,)
        Forces, N.
    cycle_start : int
        Samples ``cycle_start .. K - 1`` are the closed cycle (first and last forces equal);
        the samples before it lead from the unloaded state to the cycle's start.
    meta : dict
    """

    theta: FloatArray
    f_tip: FloatArray
    f_centre: FloatArray
    cycle_start: int
    meta: dict[str, Any] = field(default_factory=dict)

    def __post_init__(self) -> None:
        th = np.array(self.theta, dtype=float)
        ft = np.array(self.f_tip, dtype=float)
        fc = np.array(self.f_centre, dtype=float)
        if th.ndim != 1 or th.shape != ft.shape or th.shape != fc.shape:
            raise ParameterError(
                f"theta, f_tip and f_centre must be 1-D of equal length, got shapes "
                f"{th.shape}, {ft.shape}, {fc.shape}")
        if not (np.all(np.isfinite(th)) and np.all(np.isfinite(ft)) and np.all(np.isfinite(fc))):
            raise ParameterError("a load path's theta and forces must be finite numbers")
        if np.any(np.diff(th) < 0.0):
            raise ParameterError("a load path's theta (time) must be non-decreasing")
        k0 = _count("cycle_start", self.cycle_start, 0, max(th.size - 3, 0))
        if th.size - k0 < 3:
            raise ParameterError(f"the cycle needs at least 3 samples, got {th.size - k0}")
        scale = max(float(np.max(np.abs(ft))), float(np.max(np.abs(fc))), 1e-300)
        for name, f in (("tip", ft), ("centre", fc)):
            if abs(f[-1] - f[k0]) > CLOSE_TOL * scale:
                raise ParameterError(
                    f"the {name} force of the cycle does not close: {f[k0]:g} N at its start, "
                    f"{f[-1]:g} N at its end")
            f[-1] = f[k0]
        if scale <= 1e-300:
            raise ParameterError("a load path needs a non-zero force")
        for a in (th, ft, fc):
            a.setflags(write=False)
        object.__setattr__(self, "theta", th)
        object.__setattr__(self, "f_tip", ft)
        object.__setattr__(self, "f_centre", fc)
        object.__setattr__(self, "cycle_start", k0)

    @property
    def samples_per_cycle(self) -> int:
        """Increments of one cycle."""
        return int(self.theta.size - 1 - self.cycle_start)

    @property
    def cycle(self) -> slice:
        return slice(self.cycle_start, None)

    @property
    def peak_resultant(self) -> float:
        """Largest |(F_tip, F_centre)| over the path, N."""
        return float(np.max(np.hypot(self.f_tip, self.f_centre)))

    def only(self, component: str) -> CyclicPath:
        """The same path with the other component set to zero (``tip`` or ``centre``)."""
        if component == "tip":
            return CyclicPath(self.theta, self.f_tip, np.zeros_like(self.f_centre),
                              self.cycle_start, {**self.meta, "only": "tip"})
        if component == "centre":
            return CyclicPath(self.theta, np.zeros_like(self.f_tip), self.f_centre,
                              self.cycle_start, {**self.meta, "only": "centre"})
        raise ParameterError(f"component must be 'tip' or 'centre', got {component!r}")

    def repeated(self, cycles: int) -> tuple[FloatArray, FloatArray, FloatArray]:
        """theta, F_tip, F_centre of the start-up and ``cycles`` cycles (shared ends once).

        Sample 0 is the first sample of the path (applied from the clamped state); cycle c
        (0-based) occupies samples ``cycle_start + c n .. cycle_start + (c + 1) n``.
        """
        k0, n = self.cycle_start, self.samples_per_cycle
        period = float(self.theta[-1] - self.theta[k0])
        c = np.arange(cycles)
        th = np.concatenate([self.theta[:k0 + 1]]
                            + [self.theta[k0 + 1:] + period * (i + 1) - period for i in c])
        ft = np.concatenate([self.f_tip[:k0 + 1]] + [self.f_tip[k0 + 1:]] * cycles)
        fc = np.concatenate([self.f_centre[:k0 + 1]] + [self.f_centre[k0 + 1:]] * cycles)
        assert ft.size == k0 + 1 + n * cycles
        return th, ft, fc


def _ramp_to(theta: FloatArray, ft: FloatArray, fc: FloatArray, k0: int, m: int
             ) -> tuple[FloatArray, FloatArray, FloatArray, int]:
    """Prepend a straight ramp of ``m`` increments from zero load to the first sample."""
    if m <= 1:
        return theta, ft, fc, k0
    s = np.arange(1, m) / m
    step = float(theta[1] - theta[0]) if theta.size > 1 and theta[1] > theta[0] else 1.0
    th = np.r_[theta[0] - step * np.arange(m - 1, 0, -1), theta]
    return th, np.r_[ft[0] * s, ft], np.r_[fc[0] * s, fc], k0 + m - 1


def harmonic_path(tip_amplitude: float, centre_amplitude: float, phase_deg: float = 0.0,
                  increments_per_cycle: int = 64, startup: float = 0.25) -> CyclicPath:
    """F_tip = A_t sin(theta), F_centre = A_c sin(theta + phi); cycles from theta = pi/2.

    The cycles start at theta = pi/2 (the tip force's peak, like the paper's t = 0.25 s) and
    are reached from the unloaded state along a straight ramp of ``startup`` cycles' worth of
    increments. For phi = 0 that ramp is the paper's first quarter period (a monotonic
    proportional loading, so the same states); for other phases it avoids a jump from zero to
    a finite force in one increment.

    Parameters
    ----------
    tip_amplitude, centre_amplitude : float
        A_t, A_c, N (>= 0, not both 0).
    phase_deg : float
        phi, degrees: 0 is a straight line in the force plane (the paper's zero phase), 90
        an ellipse with axes along the bar and across it.
    increments_per_cycle : int
        Samples per cycle (>= 8).
    startup : float
        Length of the ramp in cycles (> 0; default a quarter).

    Examples
    --------
    >>> p = harmonic_path(2.0, 1.0, 90.0, 8)
    >>> p.cycle_start, p.f_tip[:4].round(3).tolist(), p.f_centre[:4].round(3).tolist()
    (1, [1.0, 2.0, 1.414, 0.0], [0.0, 0.0, -0.707, -1.0])
    """
    at = _amplitude(tip_amplitude, "tip amplitude")
    ac = _amplitude(centre_amplitude, "centre amplitude")
    if at == 0.0 and ac == 0.0:
        raise ParameterError("at least one of the tip and centre amplitudes must be > 0 N")
    try:
        phi = float(phase_deg)
    except (TypeError, ValueError):
        raise ParameterError(f"phase must be an angle in degrees, got {phase_deg!r}") from None
    if not math.isfinite(phi):
        raise ParameterError(f"phase must be a finite angle in degrees, got {phase_deg!r}")
    n = _count("increments_per_cycle", increments_per_cycle, 8)
    if not (math.isfinite(startup) and 0.0 < startup <= 10.0):
        raise ParameterError(f"startup must be in (0, 10] cycles, got {startup!r}")
    j = np.arange(n + 1)
    theta = 0.5 * np.pi + 2.0 * np.pi * j / n
    wrapped = 0.5 * np.pi + 2.0 * np.pi * (j % n) / n  # equal samples one period apart
    ft = at * np.sin(wrapped)
    fc = ac * np.sin(wrapped + math.radians(phi))
    th, ft, fc, k0 = _ramp_to(theta, ft, fc, 0, max(1, round(startup * n)))
    return CyclicPath(th, ft, fc, k0, {"tip_amplitude_N": at, "centre_amplitude_N": ac,
                                       "phase_deg": phi, "increments_per_cycle": n})


def as_cyclic_path(path: Any, f_tip: ArrayLike | None = None,
                   f_centre: ArrayLike | None = None, *, startup_increments: int | None = None
                   ) -> CyclicPath:
    """A :class:`CyclicPath` from a path object or from arrays of one cycle.

    Parameters
    ----------
    path : CyclicPath, LoadPath-like, or array_like
        A :class:`CyclicPath`; an object with ``theta``, ``tip_force``, ``centre_force`` and
        ``cycle_start`` (the planar model's LoadPath); or the times (any increasing samples)
        of one cycle, with ``f_tip`` and ``f_centre`` the forces at them. A cycle given as
        arrays is closed if its last sample differs from its first, and is preceded by a
        straight ramp from zero load to its first sample (so is a path object whose first
        sample is not at zero load).
    f_tip, f_centre : array_like, optional
        Forces, N, when ``path`` is the array of times.
    startup_increments : int, optional
        Increments of that ramp (default: a quarter of the cycle's, at least 1; none if the
        cycle starts at zero load).
    """
    if isinstance(path, CyclicPath) and f_tip is None and f_centre is None:
        return path
    if all(hasattr(path, a) for a in ("theta", "tip_force", "centre_force", "cycle_start")) \
            and f_tip is None and f_centre is None:
        th = np.asarray(path.theta, dtype=float)
        pt = np.asarray(path.tip_force, dtype=float)
        pc = np.asarray(path.centre_force, dtype=float)
        k0 = int(path.cycle_start)
        meta = dict(getattr(path, "meta", {}) or {})
        if th.ndim == 1 and th.size >= 3 and pt.shape == th.shape and pc.shape == th.shape:
            scale = max(float(np.max(np.abs(pt))), float(np.max(np.abs(pc))))
            if max(abs(pt[0]), abs(pc[0])) > CLOSE_TOL * scale:
                m = startup_increments if startup_increments is not None else max(
                    1, (th.size - 1 - k0) // 4)
                th, pt, pc, k0 = _ramp_to(th, pt, pc, k0, _count("startup_increments", m, 0))
                meta["startup_ramp_increments"] = m
                meta["prepended_samples"] = max(m - 1, 0)
        return CyclicPath(th, pt, pc, k0, meta)
    if f_tip is None or f_centre is None:
        raise ParameterError("give a load path object, or times with f_tip and f_centre arrays")
    try:
        t = np.asarray(path, dtype=float)
        ft = np.asarray(f_tip, dtype=float)
        fc = np.asarray(f_centre, dtype=float)
    except (TypeError, ValueError):
        raise ParameterError("times, f_tip and f_centre must be numeric arrays") from None
    if t.ndim != 1 or t.shape != ft.shape or t.shape != fc.shape or t.size < 3:
        raise ParameterError(
            f"times, f_tip and f_centre must be 1-D arrays of equal length >= 3, got shapes "
            f"{t.shape}, {ft.shape}, {fc.shape}")
    if not (np.all(np.isfinite(t)) and np.all(np.isfinite(ft)) and np.all(np.isfinite(fc))):
        raise ParameterError("times and forces must be finite numbers")
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
    return CyclicPath(t, ft, fc, k0, {"startup_increments": m,
                                      "prepended_samples": max(m - 1, 0)})
