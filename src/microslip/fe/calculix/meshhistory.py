"""The load history of a CalculiX run on the user's own mesh: the increment ends and each
load's factor A sin(2 pi t + phi) at them, after a start-up from rest (:data:`STARTUPS`),
as :func:`~microslip.fe.calculix.meshdeck.build_mesh_deck` writes them into ``*AMPLITUDE``
tables. Time in cycles (1 s per cycle).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ...errors import ParameterError
from ..meshload import MeshLoad

__all__ = ["STARTUPS", "LoadHistory", "load_factors", "load_history", "load_times"]

FloatArray = NDArray[np.float64]


def load_times(increments_per_cycle: int, cycles: int) -> FloatArray:
    """Increment ends of the load step, cycles: 0, 1/n, ..., cycles + 1/4.

    The first quarter cycle brings the loads from zero onto their cycle (:func:`load_factors`);
    then ``cycles`` full cycles follow, from t = 1/4 to cycles + 1/4. The last of them is the
    settled one whose work is reported. One cycle is the paper's load step (t = 0 .. 1.25 s).

    >>> load_times(8, 1).tolist()
    [0.0, 0.125, 0.25, 0.375, 0.5, 0.625, 0.75, 0.875, 1.0, 1.125, 1.25]
    """
    n = increments_per_cycle
    if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 4 or n % 4:
        raise ParameterError(f"increments_per_cycle must be a multiple of 4 (>= 4), got {n!r}")
    c = cycles
    if isinstance(c, bool) or not isinstance(c, (int, np.integer)) or not 1 <= c <= 100:
        raise ParameterError(f"cycles must be an integer in [1, 100], got {c!r}")
    return np.arange(int(n) * int(c) + int(n) // 4 + 1) / float(n)


def load_factors(load: MeshLoad, times: ArrayLike) -> FloatArray:
    """F_l(t) / A_l at the increment ends: sin(2 pi t + phi) from t = 1/4 on, and before it the
    straight ramp sin(2 pi t) cos(phi) from zero to the cycle's value at t = 1/4.

    For phi = 0 this is the paper's sine over the whole step (PaperSine); for several loads it
    is a straight ramp in force space to their values at t = 1/4, then the cycles.

    >>> from microslip.fe.meshload import MeshLoad
    >>> load_factors(MeshLoad("a", (1, 0, 0), 1.0, 90.0), [0, .25, .5]).round(12).tolist()
    [0.0, 0.0, -1.0]
    """
    t = np.asarray(times, dtype=float)
    phi = math.radians(load.phase_deg)
    cyc = np.sin(2 * np.pi * np.mod(t, 1.0) + phi)  # exact zeros at whole cycles
    ramp = np.sin(2 * np.pi * np.minimum(t, 0.25)) * math.cos(phi)
    return np.where(t < 0.25, ramp, cyc)


@dataclass(frozen=True, eq=False)
class LoadHistory:
    """The load samples of step 2: one per increment end.

    Attributes
    ----------
    time : ndarray, shape (k + 1,)
        Time of each sample, cycles (negative during a start-up ramp before t = 0).
    factors : ndarray, shape (k + 1, loads)
        F_l / A_l at each sample.
    increments_per_cycle : int
    first_cycle : int
        Index of the first sample of the first full cycle; the cycles follow back to back and
        the last one ends at the last sample.
    """

    time: FloatArray
    factors: FloatArray
    increments_per_cycle: int
    first_cycle: int

    @property
    def step_time(self) -> FloatArray:
        """CalculiX's step time of each sample, s (1 s per cycle, from 0)."""
        return self.time - self.time[0]

    @property
    def cycles(self) -> int:
        return (self.time.size - 1 - self.first_cycle) // self.increments_per_cycle


def _quarter(loads: Sequence[MeshLoad], n: int, cycles: int) -> LoadHistory:
    t = load_times(n, cycles)
    return LoadHistory(t, np.column_stack([load_factors(ld, t) for ld in loads]), n, n // 4)


def _ramp(loads: Sequence[MeshLoad], n: int, cycles: int) -> LoadHistory:
    load_times(n, cycles)  # the same checks
    t = np.arange(n * cycles + 1) / n
    f = np.column_stack([ld.force(t) / ld.amplitude for ld in loads])
    if float(np.max(np.abs(f[0]))) <= 1e-12:
        f[0] = 0.0
        return LoadHistory(t, f, n, 0)
    m = n // 4
    ramp = np.arange(m) / m
    return LoadHistory(np.concatenate([(ramp - 1.0) / 4.0, t]),
                       np.concatenate([ramp[:, None] * f[0][None, :], f]), n, m)


#: How step 2 starts, name -> history(loads, increments_per_cycle, cycles). ``quarter``: the
#: paper's load step (:func:`load_times`, :func:`load_factors`: a quarter-cycle start, cycles
#: from t = 1/4). ``ramp``: the built-in own-mesh solver's sine cycles: cycles from t = 0, a
#: straight ramp of a quarter cycle's increments from rest to the loads at t = 0 only when a
#: phase makes them non-zero there.
STARTUPS = {"quarter": _quarter, "ramp": _ramp}
_STARTUP_TEXT = {"quarter": "a quarter-cycle start", "ramp": "a straight ramp if needed"}


def load_history(loads: Sequence[MeshLoad], increments_per_cycle: int, cycles: int,
                 startup: str = "quarter") -> LoadHistory:
    """The samples of step 2 (:data:`STARTUPS`).

    >>> from microslip.fe.meshload import MeshLoad
    >>> h = load_history([MeshLoad("a", (1, 0, 0), 1.0, 90.0)], 4, 1, "ramp")
    >>> h.time.tolist(), h.factors[:, 0].round(12).tolist(), h.first_cycle, h.cycles
    ([-0.25, 0.0, 0.25, 0.5, 0.75, 1.0], [0.0, 1.0, 0.0, -1.0, -0.0, 1.0], 1, 1)
    """
    if startup not in STARTUPS:
        raise ParameterError(f"startup must be one of {', '.join(STARTUPS)}, got {startup!r}")
    return STARTUPS[startup](loads, increments_per_cycle, cycles)
