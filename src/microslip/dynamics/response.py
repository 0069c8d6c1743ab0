"""Forced response: the frequency-response curve by harmonic balance and arclength
continuation, and its peak.

Units: force N, displacement mm, frequency Hz (rad/s inside).
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray
from scipy.optimize import brentq

from ..errors import ParameterError
from ..named import result
from ..solver.solve import single_threaded_blas
from .condense import Condensed, condensable
from .continuation import arclength, newton
from .hb import DEFAULT_HB_SAMPLES, HarmonicBalance
from .structure import Structure

__all__ = ["DEFAULT_STEP", "FrequencyResponse", "frequency_response"]

Array = NDArray[np.float64]

#: Largest continuation step: arclength in units of the frequency range and of the
#: largest amplitude reached so far (about 100-200 points per curve).
DEFAULT_STEP = 0.02

#: Newton tolerance, relative to the largest amplitude and to the frequency range.
TOLERANCE = 1e-10


@result
class FrequencyResponse:
    """One frequency-response curve at one excitation level.

    Attributes
    ----------
    force : float
        Excitation amplitude, N (``force * shape * cos(w t)``).
    frequency : ndarray, shape (m,)
        Excitation frequency along the curve, Hz.
    amplitude : ndarray, shape (m,)
        First-harmonic amplitude of the output coordinate, mm.
    coefficients : ndarray, shape (m, n_dof (2H + 1))
        Harmonic coefficients of every point, mm (layout of :mod:`.hb`).
    peak_amplitude, peak_frequency : float
        The curve's largest first-harmonic amplitude (mm) and its frequency (Hz), located
        where dA/dw = 0 between the continuation points.
    harmonics, samples : int
        Harmonics and AFT samples per period.
    success : bool
        True if the continuation crossed the whole frequency range.
    message : str
        Why the continuation stopped.
    """

    force: float
    frequency: np.ndarray
    amplitude: np.ndarray
    coefficients: np.ndarray
    peak_amplitude: float
    peak_frequency: float
    harmonics: int
    samples: int
    success: bool
    message: str


def frequency_response(structure: Structure, force: float, shape: Array,
                       frequency_range: tuple[float, float], harmonics: int,
                       samples: int = DEFAULT_HB_SAMPLES, step: float = DEFAULT_STEP,
                       max_points: int = 10_000) -> FrequencyResponse:
    """Frequency response to ``force * shape * cos(w t)`` over ``frequency_range`` (Hz).

    Notes
    -----
    Harmonic balance (:class:`~.hb.HarmonicBalance`) continued in frequency by
    pseudo-arclength (:func:`~.continuation.arclength`) from the lower end of the range,
    starting from Newton's method at the stuck linear response. Where the structure allows
    (:func:`~.condense.condensable`) the continuation runs on the joints' harmonics only
    (:class:`~.condense.Condensed`), its step then scaled by the largest joint amplitude.
    The peak is refined to the zero of dA/dw = a . dX/dw with dX/dw = -(dR/dX)^-1 dR/dw
    (implicit function theorem), A the first-harmonic amplitude of the output coordinate,
    by Brent's method between the neighbours of the largest continuation point.
    """
    with single_threaded_blas():  # small dense solves: threads cost 10x on a shared machine
        return _frequency_response(structure, force, shape, frequency_range, harmonics,
                                   samples, step, max_points)


def _frequency_response(structure: Structure, force: float, shape: Array,
                        frequency_range: tuple[float, float], harmonics: int, samples: int,
                        step: float, max_points: int) -> FrequencyResponse:
    if not (math.isfinite(force) and force > 0.0):
        raise ParameterError(f"force must be finite and > 0 N, got {force!r}")
    lo, hi = (2.0 * np.pi * f for f in frequency_range)
    if not (math.isfinite(lo) and math.isfinite(hi) and 0.0 < lo < hi):
        raise ParameterError(f"frequency range must satisfy 0 < MIN < MAX (Hz), got "
                             f"{frequency_range!r}")
    hb = HarmonicBalance(structure, harmonics, samples)
    load = hb.excitation(shape, force)
    x0 = _solve_at(hb, load, lo, hb.stuck_guess(lo, load))
    if x0 is None:
        raise ParameterError(f"no harmonic-balance solution found at {frequency_range[0]:g} "
                             "Hz; start the frequency range elsewhere")
    system = Condensed(hb, load) if condensable(hb) else _Full(hb, load)
    a_ref = max(system.reach(system.joints(x0)), 1e-300)

    def rescale(y: Array, scale: Array) -> Array:
        out = scale.copy()
        out[:-1] = max(scale[0], system.reach(y[:-1]))
        return out

    scale = np.full(system.size + 1, a_ref)
    scale[-1] = hi - lo
    direction = np.zeros(system.size + 1)
    direction[-1] = 1.0
    curve = arclength(system.residual, np.append(system.joints(x0), lo), direction, step,
                      lambda y: y[-1] >= hi, scale, rescale, tol=TOLERANCE,
                      max_points=max_points)
    omega = np.array(curve.points[:, -1])
    coeffs = np.array([system.coefficients(y[:-1], y[-1]) for y in curve.points])
    coeffs[0] = x0
    if curve.success and omega.size > 1 and omega[-1] > hi:  # end exactly at MAX
        u = (hi - omega[-2]) / (omega[-1] - omega[-2])
        end = _solve_at(hb, load, hi, (1.0 - u) * coeffs[-2] + u * coeffs[-1])
        if end is not None:
            coeffs[-1], omega[-1] = end, hi
    amps = np.array([hb.amplitude(x)[0] for x in coeffs])
    peak_a, peak_w = _peak(hb, load, coeffs, omega, amps)
    return FrequencyResponse(force=float(force), frequency=omega / (2.0 * np.pi),
                             amplitude=amps, coefficients=coeffs, peak_amplitude=peak_a,
                             peak_frequency=peak_w / (2.0 * np.pi), harmonics=harmonics,
                             samples=samples, success=curve.success, message=curve.message)


class _Full:
    """The balance in all the structure's coefficients (the unknowns are x itself)."""

    def __init__(self, hb: HarmonicBalance, load: Array) -> None:
        self.hb, self.load, self.size = hb, load, hb.size

    def residual(self, y: Array) -> tuple[Array, Array]:
        res = self.hb.residual(y[:-1], float(y[-1]), self.load)
        return res.r, np.column_stack([res.dx, res.dw])

    def joints(self, x: Array) -> Array:
        return x

    def coefficients(self, x: Array, omega: float) -> Array:
        return x

    def reach(self, x: Array) -> float:
        """The amplitude the continuation's norm scales the unknowns by (that of the
        output coordinate), mm."""
        q = x.reshape(self.hb.structure.dofs, -1)
        out = self.hb.structure.output
        return float(np.hypot(out @ q[:, 1], out @ q[:, 2]))


def _solve_at(hb: HarmonicBalance, load: Array, omega: float, guess: Array) -> Array | None:
    """Coefficients (mm) at the fixed frequency ``omega`` (rad/s), or None."""
    def fun(x: Array) -> tuple[Array, Array]:
        res = hb.residual(x, omega, load)
        return res.r, res.dx

    scale = np.full(guess.size, max(float(np.max(np.abs(guess))), 1e-300))
    x, ok, _ = newton(fun, guess, scale, TOLERANCE, max_iter=50)
    return x if ok else None


def _peak(hb: HarmonicBalance, load: Array, coeffs: Array, omega: Array, amps: Array
          ) -> tuple[float, float]:
    """Largest first-harmonic amplitude (mm) and its frequency (rad/s)."""
    i = int(np.argmax(amps))
    if i == 0 or i == amps.size - 1 or not omega[i - 1] < omega[i] < omega[i + 1]:
        return float(amps[i]), float(omega[i])

    def solve(w: float) -> Array:
        j = i - 1 if w < omega[i] else i
        u = (w - omega[j]) / (omega[j + 1] - omega[j])
        x = _solve_at(hb, load, w, (1.0 - u) * coeffs[j] + u * coeffs[j + 1])
        if x is None:
            raise ParameterError(f"harmonic balance did not converge at {w / 2 / np.pi:g} Hz "
                                 "while locating the peak")
        return x

    def slope(w: float) -> float:
        x = solve(w)
        res = hb.residual(x, w, load)
        _, grad = hb.amplitude(x)
        return float(grad @ np.linalg.solve(res.dx, -res.dw))

    if slope(omega[i - 1]) * slope(omega[i + 1]) > 0.0:
        return float(amps[i]), float(omega[i])
    w = float(brentq(slope, omega[i - 1], omega[i + 1], xtol=1e-13 * omega[i], rtol=1e-14))
    return hb.amplitude(solve(w))[0], w
