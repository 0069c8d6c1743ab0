"""The paper's load step: F = F0 sin(2 pi t / T), t = 0 .. 1.25 T, in equal increments.

Section 4: 125 % of a 1 Hz period in 50 equal substeps, quasi-static. The first quarter
period takes the bar from rest onto the loop; the remaining full period, t = T/4 .. 5T/4, is
the closed hysteresis loop. One harmonic convention for every solver: the phase of sample k
is 2 pi (k mod m) / m with m = 4 n / 5 samples per period, so the force at t = T/4 and at
t = 5T/4 is the same number, bit for bit.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from ..errors import ParameterError
from ..named import result
from ..params import check_amplitude

__all__ = ["PERIOD", "PERIODS", "PaperSine", "paper_sine"]

#: Period of the load, s (the paper's 1 Hz; quasi-static, so only the shape of F(t) matters).
PERIOD = 1.0
#: Load duration in periods (the paper's 125 %).
PERIODS = 1.25

FloatArray = NDArray[np.float64]


def _increments(n: object) -> int:
    if (not isinstance(n, (int, np.integer)) or isinstance(n, bool) or n < 10 or n % 5
            or n > 100_000):
        raise ParameterError(f"increments must be a multiple of 5 in [10, 100000] (quarter "
                             f"periods), got {n!r}")
    return int(n)


@result
class PaperSine:
    """The sampled load step; validated on construction.

    Attributes
    ----------
    amplitude : float
        F0, N (> 0).
    increments : int
        Equal increments over t = 0 .. 1.25 T, a multiple of 5 in [10, 100000].
    time : ndarray, shape (increments + 1,)
        t_k = k T / m, s (0: the unloaded state).
    force : ndarray, shape (increments + 1,)
        F0 sin(2 pi (k mod m) / m), N.

    Examples
    --------
    >>> s = PaperSine.sampled(2.0, 10)
    >>> float(s.time[s.quarter]), bool(s.force[s.quarter] == s.force[-1]), s.force.size
    (0.25, True, 11)
    """

    amplitude: float
    increments: int
    time: FloatArray
    force: FloatArray

    @classmethod
    def sampled(cls, amplitude: float, increments: int = 50) -> PaperSine:
        """The load step of amplitude F0 (N) in ``increments`` equal increments."""
        f0 = check_amplitude(amplitude)
        n = _increments(increments)
        per = 4 * n // 5
        k = np.arange(n + 1)
        return cls(f0, n, k / per * PERIOD, f0 * np.sin(2.0 * np.pi * (k % per) / per))

    @property
    def quarter(self) -> int:
        """Increments per quarter period: the loop is samples ``quarter`` .. ``increments``."""
        return self.increments // 5

    @property
    def loop(self) -> slice:
        """Samples of the closed loop t = T/4 .. 5T/4."""
        return slice(self.quarter, self.increments + 1)


def paper_sine(amplitude: float, increments: int = 50) -> tuple[FloatArray, FloatArray]:
    """``(t, F)`` of :class:`PaperSine` (s, N)."""
    s = PaperSine.sampled(amplitude, increments)
    return s.time, s.force
