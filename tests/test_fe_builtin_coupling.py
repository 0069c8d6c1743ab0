"""The headline coupling ratio W_coupled / (W_tip-only + W_centre-only) of the built-in solver.

Exact reference: one contact node is a 2-D Jenkins element (stick stiffness k in series with a
Coulomb slider of circular limit f_s). Driven around a circle of radius u0 > e = f_s / k it
settles to a slider circle of radius sqrt(u0^2 - e^2) with the force f_s tangent to it, so
W_coupled = 2 pi f_s sqrt(u0^2 - e^2) per cycle; along one axis alone W = 4 f_s (u0 - e). The
coupling ratio of the two uni-axial parts is pi sqrt(u0^2 - e^2) / (4 (u0 - e)).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from microslip import preset
from microslip.fe.builtin import coupling_study
from microslip.fe.builtin.contact import friction_dissipation, return_map

K, FS = 1.0e3, 2.0  # N/mm, N


def jenkins_work(gx, gy, samples: int) -> float:
    """Friction work of the last of the cycles in (gx, gy) (``samples`` per cycle), N·mm."""
    slip = np.zeros((1, 2))
    works = np.zeros(gx.size)
    k, fs = np.array([K]), np.array([FS])
    for i, g in enumerate(np.column_stack([gx, gy])):
        r = return_map(g[None, :], slip, k, fs)
        works[i] = friction_dissipation(r.force, slip, r.slip)
        slip = r.slip
    return float(works[-samples:].sum())


def closed_form_ratio(u0: float) -> float:
    e = FS / K
    return math.pi * math.sqrt(u0 * u0 - e * e) / (4.0 * (u0 - e))


def circle_works(u0: float, n: int, cycles: int = 3) -> tuple[float, float]:
    """(W_coupled, W_x + W_y) of the last cycle, ``n`` samples per cycle, N·mm."""
    th = 2.0 * np.pi * np.arange(1, cycles * n + 1) / n
    x, y = u0 * np.sin(th), u0 * np.cos(th)
    return jenkins_work(x, y, n), jenkins_work(x, 0 * x, n) + jenkins_work(0 * y, y, n)


@pytest.mark.parametrize("u0", [3e-3, 1e-2])
def test_single_node_coupling_ratio_is_the_jenkins_closed_form(u0):
    e = FS / K
    (c1, d1), (c2, d2) = circle_works(u0, 1024), circle_works(u0, 2048)
    # uni-axial: the slider reverses at the sampled peaks, which are exact: no time error
    assert d1 == pytest.approx(8 * FS * (u0 - e), rel=1e-12)
    assert d2 == pytest.approx(d1, rel=1e-12)
    # on the circle the backward-Euler return lags the force by half a sample: an error
    # of first order in 1/n, which Richardson's 2 W(2n) - W(n) removes to O(1/n^2) ~ 1e-6
    exact = 2 * np.pi * FS * math.sqrt(u0 * u0 - e * e)
    assert (c1 - exact) / (c2 - exact) == pytest.approx(2.0, rel=1e-2)
    assert 2 * c2 - c1 == pytest.approx(exact, rel=1e-5)
    assert (2 * c2 - c1) / d2 == pytest.approx(closed_form_ratio(u0), rel=1e-5)


def test_coupling_ratio_of_a_small_mesh_is_the_recorded_value():
    """Regression (tiny mesh, 90 degrees, 150 N each, 3 cycles of 32 increments): recorded with
    the coupled solver of commit 6f9c4e4. Newton stops at 1e-9 mu F_N per dof, so the cycle
    works, and their ratio, are reproducible to about 1e-8; 1e-7 leaves room for BLAS order."""
    r = coupling_study(preset("table1"), 150.0, 150.0, 90.0, mesh="tiny", cycles=3,
                       increments_per_cycle=32)
    assert r.converged
    assert r.coupling_ratio == pytest.approx(1.0332162671175356, rel=1e-7)
