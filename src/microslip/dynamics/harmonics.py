"""The number of harmonics chosen by an error estimate: EPMC, quasi-static modal analysis and
forced response with their harmonics (and AFT samples) raised until the answer settles.

The harmonics climb a ladder ``H_0 = 1, H_{n+1} = 2 H_n + 1`` (1, 3, 7, 15, 31, 63, ...:
each level at least doubles the harmonics, and keeps the odd ones of a half-wave symmetric
balance odd), up to a cap and to the largest balance the structure's size allows
(:meth:`HarmonicControl.levels`). At each point (amplitude or modal force) the balance is
solved at neighbouring levels, each warm-started from the one below (its new harmonics
zero). The estimate is the relative change (:func:`change`) of the damping ratio and the
frequency from the level below to the larger, or a third of the change from two levels
below (where there are two; :data:`TWO_LEVEL_RATIO`), whichever is larger; the point keeps
the larger level's solution once the estimate is below the tolerance, else climbs a level.
Two changes, because the convergence in H is not monotone: the error changes sign, and one
pair of levels can straddle the answer by chance (on a Jenkins element at 0.1 mm, 3 and 7
harmonics agree to 1.3e-5 while 7 errs by 2.5e-4; 1 to 7 change by 4.4e-3); the level two
below costs an eighth or less of the larger one (a dense solve, (n H)^3). With a monotone
error ~ C H^-p, p >= 1, both are bounds of the larger level's error. The next point starts
at the same levels (never lower: the harmonics a point needed are kept for the next,
larger one, where slip only spreads).

Why the change bounds the error of the larger level's answer: with an error falling as
``C H^-p``, the change from H to 2H + 1 is about ``C H^-p (1 - 2^-p)`` and the larger
level's own error ``C H^-p 2^-p``, their ratio ``1 / (2^p - 1)``: at most 1 when p >= 1.
It is an estimate, not a bound: where a harmonic reaches a mode of the structure (the
contact nodes' own modes of a ROM) the answer can still move at higher levels
(docs/interpretation.md, "Harmonic convergence").

The AFT's samples follow the harmonics: ``16 (H + 1)`` rounded up to a power of two
(:meth:`HarmonicControl.samples`: 32, 64, 128, 256, 512, 1024 for 1 to 63 harmonics; 128
at 7, the fixed default's), so that each level doubles the samples with the harmonics and
the estimate measures the AFT's own error (on a Jenkins element the sampled stick-slip
transitions cost more than the dropped harmonics: 7 harmonics err by 7e-4 with 128
samples, 1e-6 with 4096).

Units: amplitude mm, frequency Hz, damping ratio (-), modal force sqrt(t)·mm/s^2.
"""

from __future__ import annotations

import contextlib
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..blas import single_threaded_blas
from ..errors import ParameterError
from ..named import result
from .hb import HarmonicBalance, harmonic_columns
from .modal import (
    ModalCurve,
    _amplitudes,
    epmc_point,
    epmc_start,
    qsma_odd,
    qsma_point,
    qsma_start,
    qsma_values,
)
from .operators3d import Contact3D
from .response import DEFAULT_STEP, FrequencyResponse, frequency_response
from .structure import Structure

__all__ = ["DAMPING_FLOOR", "DEFAULT_CAP", "DEFAULT_TOLERANCE", "AdaptiveResponse",
           "HarmonicControl", "adaptive_epmc", "adaptive_quasi_static",
           "adaptive_response", "cap_warning", "change", "transfer"]

Array = NDArray[np.float64]

#: Default tolerance on the relative change of the damping ratio and frequency (-).
DEFAULT_TOLERANCE = 0.005

#: Default largest number of harmonics (a level of the ladder 1, 3, 7, 15, 31, 63).
DEFAULT_CAP = 63

#: Largest balance (unknown coefficients) of a level unless given: its dense solve about
#: 0.05 TFLOP and 134 MB, some 8x a 7-harmonic balance of the 24x6x2 cantilever's ROM (186
#: DOF on the odd harmonics), which then climbs to 15 harmonics, not 31 (64x).
DEFAULT_MAX_UNKNOWNS = 4096

#: Damping ratio (-) below which a change is measured against this floor instead of the
#: damping ratio itself: a stuck structure without linear damping has zeta ~ 1e-17 of
#: rounding, whose relative change means nothing.
DAMPING_FLOOR = 1e-8

#: The change over two levels (about 4x the harmonics) is at least this many times the
#: larger level's error when the error falls monotonically at least like 1/H (4 - 1); the
#: estimate takes that change divided by it beside the one-level change.
TWO_LEVEL_RATIO = 3.0

#: AFT samples per period of the highest harmonic kept (at least).
SAMPLES_PER_HARMONIC = 16


@dataclass(frozen=True)
class HarmonicControl:
    """How the harmonics are chosen.

    Attributes
    ----------
    tolerance : float
        Largest relative change of damping ratio and frequency between two levels of the
        ladder that a point accepts, in (0, 0.5) (default 0.005).
    cap : int
        Largest harmonics, a level of the ladder 1, 3, 7, 15, 31, 63, 127, 255 (default 63);
        a point that has not settled there keeps the cap's answer and its estimate, and
        :func:`cap_warning` says so.
    max_unknowns : int
        Largest balance (unknown coefficients, n_dof times the columns per DOF) a level may
        have, >= 16 (default 4096: a dense solve of about 0.05 TFLOP, 134 MB); the levels
        above it are left out for this structure, as above the cap (:meth:`levels`).
    """

    tolerance: float = DEFAULT_TOLERANCE
    cap: int = DEFAULT_CAP
    max_unknowns: int = DEFAULT_MAX_UNKNOWNS

    def __post_init__(self) -> None:
        if (isinstance(self.tolerance, bool) or not isinstance(self.tolerance, float | int)
                or not 0.0 < self.tolerance < 0.5):
            raise ParameterError(f"harmonic tolerance must be in (0, 0.5), got "
                                 f"{self.tolerance!r}")
        levels = _levels(255)
        if self.cap not in levels[1:]:
            raise ParameterError(f"the harmonics' cap must be one of "
                                 f"{', '.join(map(str, levels[1:]))}, got {self.cap!r}")
        if not (isinstance(self.max_unknowns, int) and self.max_unknowns >= 16):
            raise ParameterError(f"max_unknowns must be a whole number >= 16, got "
                                 f"{self.max_unknowns!r}")

    @property
    def ladder(self) -> tuple[int, ...]:
        """The levels of harmonics, 1, 3, 7, ... up to the cap."""
        return _levels(self.cap)

    def levels(self, dofs: int, odd: bool) -> tuple[int, ...]:
        """The ladder for a structure of ``dofs`` DOF (``odd``: on the odd harmonics): the
        levels up to the cap whose balance has at most ``max_unknowns`` unknowns, and never
        fewer than the two lowest (1 and 3 harmonics)."""
        fits = [h for h in self.ladder
                if dofs * harmonic_columns(h, odd).size <= self.max_unknowns]
        return tuple(fits) if len(fits) >= 2 else self.ladder[:2]

    @staticmethod
    def samples(harmonics: int) -> int:
        """AFT samples at ``harmonics``: ``16 (H + 1)`` rounded up to a power of two."""
        return 1 << int(np.ceil(np.log2(SAMPLES_PER_HARMONIC * (harmonics + 1))))


def _levels(cap: int) -> tuple[int, ...]:
    out = [1]
    while 2 * out[-1] + 1 <= cap:
        out.append(2 * out[-1] + 1)
    return tuple(out)


def change(frequency: tuple[float, float], damping: tuple[float, float]) -> float:
    """The error estimate: the larger relative change, from the smaller level (first) to
    the larger (second), of the frequency and of the damping ratio (the latter against
    :data:`DAMPING_FLOOR` where the damping ratio is below it)."""
    df = abs(frequency[0] - frequency[1]) / abs(frequency[1])
    dz = abs(damping[0] - damping[1]) / max(abs(damping[1]), DAMPING_FLOOR)
    return float(max(df, dz))


def transfer(small: HarmonicBalance, large: HarmonicBalance, x: Array) -> Array:
    """Coefficients ``x`` (mm, ``small``'s layout) in ``large``'s layout, the harmonics
    ``small`` does not have zero: the warm start of the larger level."""
    dofs = small.structure.dofs
    full = small.expand(x).reshape(dofs, 2 * small.harmonics + 1)
    out = np.zeros((dofs, 2 * large.harmonics + 1))
    out[:, :full.shape[1]] = full
    return large.restrict(out.ravel())


def cap_warning(estimates: ArrayLike | None, harmonics: int, control: HarmonicControl,
                what: str = "amplitude(s)") -> str | None:
    """The warning when some points (their ``estimates``, -) did not settle within the
    ladder's top level, ``harmonics`` (the cap, or the largest balance the structure's size
    allows: :meth:`HarmonicControl.levels`), or whose next level did not converge (estimate
    NaN), or None."""
    est = np.atleast_1d(np.asarray(estimates, dtype=np.float64))
    bad = np.flatnonzero(est >= control.tolerance)
    failed = int(np.count_nonzero(np.isnan(est)))
    parts = []
    if bad.size:
        why = ("the cap" if harmonics == control.cap else "the most this structure's "
               f"balance takes within {control.max_unknowns} unknowns")
        parts.append(f"the harmonics reached {harmonics} ({why}) at {bad.size} {what} "
                     f"without settling: the damping ratio or frequency still changes by up "
                     f"to {100 * float(np.max(est[bad])):.3g} % (tolerance "
                     f"{100 * control.tolerance:.3g} %) on the last levels; the answer there "
                     f"is {harmonics} harmonics'")
    if failed:
        parts.append(f"at {failed} {what} the next level of harmonics did not converge: the "
                     "answer there is the level below's, without an error estimate (null)")
    return "; ".join(parts) if parts else None


class _Ladder:
    """The balances of the ladder's levels, built when first needed."""

    def __init__(self, structure: Structure, control: HarmonicControl, odd: bool) -> None:
        self.structure, self.control, self.odd = structure, control, odd
        self.harmonics = control.levels(structure.dofs, odd)
        self._built: dict[int, HarmonicBalance] = {}

    def __getitem__(self, level: int) -> HarmonicBalance:
        if level not in self._built:
            h = self.harmonics[level]
            self._built[level] = HarmonicBalance(self.structure, h, self.control.samples(h),
                                                 odd=self.odd)
        return self._built[level]


def _climb(ladder: _Ladder, level: int, guesses: dict[int, Array],
           solve: Callable[[HarmonicBalance, Array], Array],
           measure: Callable[[HarmonicBalance, Array], tuple[float, float]]
           ) -> tuple[int, dict[int, Array], float]:
    """One point: solve at ``level`` and ``level + 1`` (and up) until the change of
    ``measure`` (frequency Hz, damping ratio) is below the tolerance or the cap is reached.
    ``guesses`` maps levels to starting unknowns (in that level's layout); ``solve(hb,
    guess) -> y``. Returns the accepted level, the solutions by level, the estimate."""
    top = len(ladder.harmonics) - 1
    sols: dict[int, Array] = {}
    lo = min(level, top - 1)
    if lo > 0:  # the level below too: a second change, at an eighth of the cost or less
        tries = [guesses[lo - 1]] if lo - 1 in guesses else []
        with contextlib.suppress(ParameterError):  # then the one change from ``lo``
            sols[lo - 1] = _first(ladder, lo - 1, solve, [
                *tries, _drop(ladder, lo, lo - 1, guesses[lo])])
    sols[lo] = _first(ladder, lo, solve, [guesses[lo], *(
        [_lift(ladder, lo - 1, lo, sols[lo - 1])] if lo - 1 in sols else [])])
    while True:
        hi = lo + 1
        lifted = _lift(ladder, lo, hi, sols[lo])
        try:
            sols[hi] = _first(ladder, hi, solve, [guesses[hi], lifted] if hi in guesses
                              else [lifted])
        except ParameterError:  # keep the level below's answer, without an estimate
            return lo, sols, float("nan")
        f1, z1 = measure(ladder[hi], sols[hi])
        est = 0.0
        for below, share in ((lo - 1, 1.0 / TWO_LEVEL_RATIO), (lo, 1.0)):
            if below in sols:
                f0, z0 = measure(ladder[below], sols[below])
                est = max(est, share * change((f0, f1), (z0, z1)))
        if est < ladder.control.tolerance or hi == top:
            return hi, sols, est
        lo = hi


def _first(ladder: _Ladder, level: int, solve: Callable[[HarmonicBalance, Array], Array],
           starts: list[Array]) -> Array:
    """``solve`` at ``level`` from the first of ``starts`` it converges from (the previous
    point's solution at this level, then the one below's lifted); the last failure, naming
    the harmonics, if none."""
    for k, start in enumerate(starts):
        try:
            return solve(ladder[level], start)
        except ParameterError as err:
            if k == len(starts) - 1:
                raise ParameterError(f"{err} with {ladder.harmonics[level]} harmonics "
                                     "(--harmonics auto)") from None
    raise AssertionError("no start")  # starts is never empty


def _drop(ladder: _Ladder, hi: int, lo: int, y: Array) -> Array:
    """Unknowns ``[x, extra...]`` of level ``hi`` truncated to level ``lo``."""
    small, large = ladder[lo], ladder[hi]
    dofs = large.structure.dofs
    full = large.expand(y[:large.size]).reshape(dofs, 2 * large.harmonics + 1)
    x = small.restrict(np.ascontiguousarray(full[:, :2 * small.harmonics + 1]).ravel())
    return np.concatenate([x, y[large.size:]])


def _lift(ladder: _Ladder, lo: int, hi: int, y: Array) -> Array:
    """Unknowns ``[x, extra...]`` of level ``lo`` as a start at level ``hi``."""
    small, large = ladder[lo], ladder[hi]
    return np.concatenate([transfer(small, large, y[:small.size]), y[small.size:]])


def adaptive_epmc(structure: Structure, amplitude: ArrayLike,
                  control: HarmonicControl = HarmonicControl(), mode: int = 0,
                  odd: bool = False) -> ModalCurve:
    """:func:`~.modal.epmc` (``odd``: :func:`~.modal_odd.epmc_odd`) with the harmonics chosen
    per amplitude (the module's notes); ``point_harmonics`` and ``harmonic_error_estimate``
    say what each amplitude took and how far its answer may still be."""
    a = _amplitudes(amplitude)
    if odd and any(isinstance(link.operator, Contact3D) for link in structure.joints):
        raise ParameterError("the odd-harmonic EPMC needs odd joint forces; the 3-D contact "
                             "element's normal lift-off is not: use epmc")
    with single_threaded_blas():
        return _adaptive_epmc(structure, a, control, mode, odd)


def _adaptive_epmc(structure: Structure, a: Array, control: HarmonicControl, mode: int,
                   odd: bool) -> ModalCurve:
    ladder = _Ladder(structure, control, odd)
    start, omega0 = epmc_start(structure, ladder[0], mode)
    guesses = {0: start}
    level, previous = 0, 1.0
    freq, zeta, est = np.empty(a.size), np.empty(a.size), np.empty(a.size)
    used = np.empty(a.size, dtype=np.int64)

    def measure(hb: HarmonicBalance, y: Array) -> tuple[float, float]:
        return float(y[hb.size] / (2.0 * np.pi)), float(y[hb.size + 1] / (2.0 * y[hb.size]))

    for i, ai in enumerate(a):
        scaled = {lv: _scaled(y, ladder[lv].size, ai / previous) for lv, y in guesses.items()}
        if level not in scaled:  # the level below the accepted one was never solved here
            below = max(lv for lv in scaled if lv < level)
            scaled[level] = _lift(ladder, below, level, scaled[below])
        def solve(hb: HarmonicBalance, guess: Array, ai: float = float(ai)) -> Array:
            return epmc_point(hb, ai, guess, omega0)

        top, sols, est[i] = _climb(ladder, level, scaled, solve, measure)
        freq[i], zeta[i] = measure(ladder[top], sols[top])
        used[i] = ladder.harmonics[top]
        level, guesses, previous = top - 1, sols, float(ai)
    h = int(used.max())
    return ModalCurve(method="epmc", amplitude=a, frequency=freq, damping_ratio=zeta,
                      harmonics=h, samples=control.samples(h), point_harmonics=used,
                      harmonic_error_estimate=est)


def _scaled(y: Array, size: int, factor: float) -> Array:
    out = y.copy()
    out[:size] *= factor
    return out


def adaptive_quasi_static(structure: Structure, force: ArrayLike,
                          control: HarmonicControl = HarmonicControl(), mode: int = 0
                          ) -> ModalCurve:
    """:func:`~.modal.quasi_static` with the harmonics chosen per modal force (the module's
    notes)."""
    q = np.asarray(force, dtype=np.float64).reshape(-1)
    if not (q.size and np.all(np.isfinite(q)) and np.all(q > 0.0)):
        raise ParameterError("modal forces must be finite and > 0")
    with single_threaded_blas():
        return _adaptive_quasi_static(structure, q, control, mode)


def _adaptive_quasi_static(structure: Structure, q: Array, control: HarmonicControl,
                           mode: int) -> ModalCurve:
    ladder = _Ladder(structure, control, qsma_odd(structure))
    phi, start = qsma_start(structure, ladder[0], mode)
    guesses = {0: start}
    level, previous = 0, 1.0
    amp, freq, zeta, est = (np.empty(q.size) for _ in range(4))
    used = np.empty(q.size, dtype=np.int64)
    for i, qi in enumerate(q):
        qf = float(qi)
        scaled = {lv: y * (qf / previous) for lv, y in guesses.items()}
        if level not in scaled:
            below = max(lv for lv in scaled if lv < level)
            scaled[level] = _lift(ladder, below, level, scaled[below])

        def measure(hb: HarmonicBalance, y: Array, qf: float = qf) -> tuple[float, float]:
            return qsma_values(hb, qf, y, phi)[1:]

        def solve(hb: HarmonicBalance, guess: Array, qf: float = qf) -> Array:
            return qsma_point(hb, qf, guess, phi)

        top, sols, est[i] = _climb(ladder, level, scaled, solve, measure)
        amp[i], freq[i], zeta[i] = qsma_values(ladder[top], qf, sols[top], phi)
        used[i] = ladder.harmonics[top]
        level, guesses, previous = top - 1, sols, qf
    h = int(used.max())
    return ModalCurve(method="qsma", amplitude=amp, frequency=freq, damping_ratio=zeta,
                      harmonics=h, samples=control.samples(h), point_harmonics=used,
                      harmonic_error_estimate=est)


@result
class AdaptiveResponse:
    """A frequency-response curve with its harmonics chosen by an error estimate.

    Attributes
    ----------
    response : FrequencyResponse
        The curve at the accepted harmonics (its ``harmonics`` and ``samples``).
    harmonic_error_estimate : float
        Relative change of the peak amplitude and peak frequency from the level below (-).
    levels : tuple of int
        The harmonics of every curve computed, ascending.
    """

    response: FrequencyResponse
    harmonic_error_estimate: float
    levels: tuple[int, ...]


def adaptive_response(structure: Structure, force: float, shape: Array,
                      frequency_range: tuple[float, float],
                      control: HarmonicControl = HarmonicControl(), step: float = DEFAULT_STEP,
                      odd: bool = False, start: int = 1) -> AdaptiveResponse:
    """:func:`~.response.frequency_response` with the harmonics chosen per curve: the whole
    curve at two levels of the ladder from ``start`` (a level's harmonics), up until the
    peak amplitude and peak frequency change by less than the tolerance (the peak amplitude
    is inversely proportional to the damping there). Per curve, not per point: a
    continuation in frequency would otherwise switch balances mid-curve."""
    ladder = control.levels(structure.dofs, odd)
    if start not in ladder:
        raise ParameterError(f"start must be a level of {ladder}, got {start!r}")
    i = ladder.index(start)
    i = min(i, len(ladder) - 2)

    def run(h: int) -> FrequencyResponse:
        return frequency_response(structure, force, shape, frequency_range, h,
                                  control.samples(h), step, odd=odd)

    low = run(ladder[i])
    while True:
        high = run(ladder[i + 1])
        est = change((low.peak_frequency, high.peak_frequency),
                     (low.peak_amplitude, high.peak_amplitude))
        if est < control.tolerance or i + 1 == len(ladder) - 1:
            return AdaptiveResponse(response=high, harmonic_error_estimate=est,
                                    levels=ladder[ladder.index(start):i + 2])
        low, i = high, i + 1
