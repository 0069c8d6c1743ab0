"""The EPMC reaches a point that Newton on H harmonics misses from the last point through the
same point on fewer harmonics (issue 35, item 3). On the penalty bracket (examples/bracket.inp,
normal slope 1e5, mode 1) 7 harmonics wandered from the first amplitude to the second,
0.0164 mm (frequency iterates -2900 and 8500 Hz, a residual stuck at 1e2, "did not
converge") where 3 reach it and 7 converge from it: 1861.45 Hz, zeta 4.70e-4 (145 s; not run
here)."""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest

import microslip.dynamics.modal as modal
from microslip.dynamics import jenkins
from microslip.dynamics.modal import epmc
from microslip.dynamics.structure import one_mode

AMPS = np.geomspace(1e-3, 0.3, 6)  # mm; the joint slips from about 0.01 mm
STRUCTURE = one_mode(100.0, 2.0, 0.02, jenkins(300.0, 5.0), participation=0.7)


def test_a_point_missed_on_seven_harmonics_is_reached_from_three(
        monkeypatch: pytest.MonkeyPatch) -> None:
    """A Newton on 7 harmonics that converges only from a start without harmonics above 3
    (a point of the 3-harmonic balance, lifted) still gives the unrestricted curve."""
    free = epmc(STRUCTURE, AMPS, 7, 128)
    real = modal.newton
    lifted = []

    def newton(fun: Any, y0: Any, scale: Any, tol: float, max_iter: int = 12,
               factors: Any = None) -> Any:
        y, ok, jac = real(fun, y0, scale, tol, max_iter=max_iter, factors=factors)
        if y0.size == 15 + 2 and float(scale[0]) > AMPS[0]:  # 7 harmonics, past the first
            if np.any(y0[7:15] != 0.0):
                return y0, False, jac
            lifted.append(float(scale[0]))
        return y, ok, jac

    monkeypatch.setattr(modal, "newton", newton)
    c = epmc(STRUCTURE, AMPS, 7, 128)
    assert lifted == list(AMPS[1:])  # every later amplitude went through 3 harmonics
    np.testing.assert_allclose(c.frequency, free.frequency, rtol=1e-9)
    np.testing.assert_allclose(c.damping_ratio, free.damping_ratio, rtol=1e-7, atol=1e-12)
