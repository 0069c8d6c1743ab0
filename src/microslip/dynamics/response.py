"""Forced response: the frequency-response curve by harmonic balance and arclength
continuation, and its peak.

Units: force N, displacement mm, frequency Hz (rad/s inside).
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

from ..blas import single_threaded_blas
from ..errors import ParameterError
from ..named import result
from .condense import Condensed, condensable
from .continuation import MAX_ITERATIONS, arclength, newton
from .hb import DEFAULT_HB_SAMPLES, HarmonicBalance
from .operators3d import Contact3D
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
                       max_points: int = 10_000, odd: bool = False) -> FrequencyResponse:
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

    With ``odd`` the balance runs on the odd harmonics only (:class:`~.hb.HarmonicBalance`
    with ``odd``; the even ones are zero in ``coefficients``): the same curve when every
    joint force is odd and the excitation ``cos(w t)`` is (half-wave symmetry,
    :mod:`.modal_odd`), at a fraction of the cost. Refused for the 3-D contact element,
    whose normal lift-off is not odd. The balance is then never condensed.
    """
    with single_threaded_blas():  # small dense solves: threads cost 10x on a shared machine
        return _frequency_response(structure, force, shape, frequency_range, harmonics,
                                   samples, step, max_points, odd)


def _frequency_response(structure: Structure, force: float, shape: Array,
                        frequency_range: tuple[float, float], harmonics: int, samples: int,
                        step: float, max_points: int, odd: bool = False
                        ) -> FrequencyResponse:
    if not (math.isfinite(force) and force > 0.0):
        raise ParameterError(f"force must be finite and > 0 N, got {force!r}")
    lo, hi = (2.0 * np.pi * f for f in frequency_range)
    if not (math.isfinite(lo) and math.isfinite(hi) and 0.0 < lo < hi):
        raise ParameterError(f"frequency range must satisfy 0 < MIN < MAX (Hz), got "
                             f"{frequency_range!r}")
    if odd and any(isinstance(link.operator, Contact3D) for link in structure.joints):
        raise ParameterError("the odd-harmonic forced response needs odd joint forces; the "
                             "3-D contact element's normal lift-off is not: leave out odd")
    hb = HarmonicBalance(structure, harmonics, samples, odd=odd)
    load = hb.excitation(shape, force)
    system = Condensed(hb, load) if not odd and condensable(hb) else _Full(hb, load)
    start = _solve_at(system, lo, system.joints(hb.stuck_guess(lo, load)))
    if start is None:
        raise ParameterError(f"no harmonic-balance solution found at {frequency_range[0]:g} "
                             "Hz; start the frequency range elsewhere")
    u0 = start[0]
    a_ref = max(system.reach(u0), 1e-300)

    def rescale(y: Array, scale: Array) -> Array:
        out = scale.copy()
        out[:-1] = max(scale[0], system.reach(y[:-1]))
        return out

    scale = np.full(system.size + 1, a_ref)
    scale[-1] = hi - lo
    direction = np.zeros(system.size + 1)
    direction[-1] = 1.0
    corrector = hb.corrector(load, MAX_ITERATIONS) if isinstance(system, _Full) else None
    curve = arclength(system.residual, np.append(u0, lo), direction, step,
                      lambda y: y[-1] >= hi, scale, rescale, tol=TOLERANCE,
                      max_points=max_points, corrector=corrector)
    points = np.array(curve.points)
    if curve.success and len(points) > 1 and points[-1, -1] > hi:  # end exactly at MAX
        u = (hi - points[-2, -1]) / (points[-1, -1] - points[-2, -1])
        end = _solve_at(system, hi, (1.0 - u) * points[-2, :-1] + u * points[-1, :-1])
        if end is not None:
            points[-1] = np.append(end[0], hi)
    omega = points[:, -1]
    coeffs = system.along(points)
    amps = hb.amplitudes(coeffs)
    if odd:
        coeffs = hb.expand(coeffs)
    peak_a, peak_w = _peak(system, points, amps)
    return FrequencyResponse(force=float(force), frequency=omega / (2.0 * np.pi),
                             amplitude=amps, coefficients=coeffs, peak_amplitude=peak_a,
                             peak_frequency=peak_w / (2.0 * np.pi), harmonics=harmonics,
                             samples=samples, success=curve.success, message=curve.message)


class _Full:
    """The balance in all the structure's coefficients (the unknowns are x itself)."""

    def __init__(self, hb: HarmonicBalance, load: Array) -> None:
        self.hb, self.load, self.size = hb, load, hb.size

    def residual(self, y: Array) -> tuple[Array, Array]:
        jac = np.zeros((self.size, self.size + 1), order="F")  # as LAPACK takes it
        res = self.hb.residual(y[:-1], float(y[-1]), self.load, out=jac)
        return res.r, res.jac

    def joints(self, x: Array) -> Array:
        return x

    def along(self, points: Array) -> Array:
        """The coefficients at every row ``[x, w]`` of ``points``: x itself."""
        return points[:, :-1].copy()

    def amplitude(self, y: Array) -> tuple[float, Array]:
        """First-harmonic amplitude (mm) of the output coordinate and its gradient in
        ``y = [x, w]``."""
        a, grad = self.hb.amplitude(y[:-1])
        return a, np.append(grad, 0.0)

    def reach(self, x: Array) -> float:
        """The amplitude the continuation's norm scales the unknowns by (that of the
        output coordinate), mm."""
        q = x.reshape(self.hb.structure.dofs, -1)
        out, c = self.hb.structure.output, self.hb.first
        return float(np.hypot(out @ q[:, c], out @ q[:, c + 1]))


def _solve_at(system: _Full | Condensed, omega: float, guess: Array
              ) -> tuple[Array, Array] | None:
    """The system's unknowns at the fixed frequency ``omega`` (rad/s) and ``[dR/du | dR/dw]``
    at Newton's last iterate (one step from them), or None."""
    last = []

    def fun(u: Array) -> tuple[Array, Array]:
        r, jac = system.residual(np.append(u, omega))
        last.append(jac)
        return r, jac[:, :-1]

    scale = np.full(guess.size, max(float(np.max(np.abs(guess))), 1e-300))
    u, ok, _ = newton(fun, guess, scale, TOLERANCE, max_iter=50)
    return (u, last[-1]) if ok else None


class _Point:
    """A solution at one frequency: w (rad/s), unknowns u, amplitude A (mm), dA/dw and
    du/dw along the curve."""

    def __init__(self, system: _Full | Condensed, omega: float, u: Array, jac: Array
                 ) -> None:
        self.omega, self.u = omega, u
        self.dudw = -np.linalg.solve(jac[:, :-1], jac[:, -1])
        self.a, grad = system.amplitude(np.append(u, omega))
        self.slope = float(grad[:-1] @ self.dudw + grad[-1])


def _peak(system: _Full | Condensed, points: Array, amps: Array) -> tuple[float, float]:
    """Largest first-harmonic amplitude (mm) and its frequency (rad/s).

    Notes
    -----
    The sign change of dA/dw between the neighbours of the largest continuation point,
    bracketed down to 1e-13 of the frequency. A(w) is piecewise smooth (an Iwan joint's
    elements start to slip one by one) and its peak is often a corner where dA/dw jumps, so
    each round tries the two points that are exact for the two cases: where the tangent
    lines of A at the bracket's ends cross (a corner) and where the secant of dA/dw
    vanishes (a smooth maximum), then halves the bracket if they did not. Each point is
    solved by Newton from the tangent predictor of the nearer end, its slope taken with
    the Jacobian of Newton's last iterate.
    """
    omega = points[:, -1]
    i = int(np.argmax(amps))
    if i == 0 or i == amps.size - 1 or not omega[i - 1] < omega[i] < omega[i + 1]:
        return float(amps[i]), float(omega[i])

    def solve(w: float, near: _Point) -> _Point:
        found = _solve_at(system, w, near.u + near.dudw * (w - near.omega))
        if found is None:
            raise ParameterError(f"harmonic balance did not converge at {w / 2 / np.pi:g} Hz "
                                 "while locating the peak")
        return _Point(system, w, *found)

    def at(j: int) -> _Point:
        y = points[j]
        return _Point(system, float(y[-1]), y[:-1], system.residual(y)[1])

    lo, hi = at(i - 1), at(i + 1)
    for p in (lo, hi):
        if p.slope == 0.0:
            return p.a, p.omega
    if not lo.slope > 0.0 > hi.slope:
        return float(amps[i]), float(omega[i])
    xtol = 1e-13 * omega[i]
    while hi.omega - lo.omega > xtol:
        width = hi.omega - lo.omega
        for rule in (_corner, _secant, _middle):
            if rule is _middle and hi.omega - lo.omega <= 0.5 * width:
                continue
            w = rule(lo, hi)
            if not lo.omega < w < hi.omega:
                w = _middle(lo, hi)
            p = solve(w, lo if w - lo.omega < hi.omega - w else hi)
            if p.slope == 0.0:
                return p.a, p.omega
            lo, hi = (p, hi) if p.slope > 0.0 else (lo, p)
            if hi.omega - lo.omega <= xtol:
                break
    best = lo if lo.a >= hi.a else hi
    return best.a, best.omega


def _corner(lo: _Point, hi: _Point) -> float:
    """Where the tangent lines of A at ``lo`` and ``hi`` cross (rad/s)."""
    return (hi.a - lo.a + lo.slope * lo.omega - hi.slope * hi.omega) / (lo.slope - hi.slope)


def _secant(lo: _Point, hi: _Point) -> float:
    """Where the secant of dA/dw between ``lo`` and ``hi`` vanishes (rad/s)."""
    return lo.omega + lo.slope * (hi.omega - lo.omega) / (lo.slope - hi.slope)


def _middle(lo: _Point, hi: _Point) -> float:
    return 0.5 * (lo.omega + hi.omega)
