"""Nodal Coulomb friction of the built-in solver against the Jenkins element's closed forms."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from microslip.closedform import jenkins_1d_dissipation, jenkins_2d_circular_dissipation
from microslip.fe.builtin.contact import friction_dissipation, return_map

K, FS = 2.0, 1.0  # spring stiffness N/mm, slip force N: d_s = 0.5 mm


def _orbit_work(g: np.ndarray) -> tuple[float, float]:
    """Drive one node along displacements g (n, 2) from zero slip; work of the last cycle
    (trapezoidal) and friction dissipation of the last cycle, N·mm. The last third of the
    samples is taken as the last cycle."""
    slip = np.zeros((1, 2))
    tau = np.zeros_like(g)
    diss = np.zeros(g.shape[0])
    for i, gi in enumerate(g):  # one node: a loop over time steps, not over nodes
        r = return_map(gi[None], slip, np.array([K]), np.array([FS]))
        diss[i] = friction_dissipation(r.force, slip, r.slip)
        slip, tau[i] = r.slip, r.force[0]
    n = (g.shape[0] - 1) // 3
    c = slice(2 * n, 3 * n + 1)
    work = float(np.sum(0.5 * (tau[c][1:] + tau[c][:-1]) * np.diff(g[c], axis=0)))
    return work, float(diss[c][1:].sum())


def _circle(radius: float, n: int) -> np.ndarray:
    th = 2.0 * np.pi * np.arange(3 * n + 1) / n
    ramp = np.minimum(th / (2.0 * np.pi), 1.0)  # spiral out over the first cycle
    return np.stack([radius * ramp * np.cos(th), radius * ramp * np.sin(th)], axis=1)


def test_circular_orbit_matches_2d_jenkins() -> None:
    """W = 2 pi f_s sqrt(A^2 - d_s^2) on a circular orbit; backward Euler is first order."""
    a = 1.7
    exact = jenkins_2d_circular_dissipation(a, FS, K)
    errs = []
    for n in (250, 500, 1000, 2000):
        work, diss = _orbit_work(_circle(a, n))
        errs.append(abs(work / exact - 1.0))
        assert abs(diss / exact - 1.0) < 10.0 / n
    assert errs[-1] < 5e-4
    slope = np.polyfit(np.log([250, 500, 1000, 2000]), np.log(errs), 1)[0]
    assert -1.2 < slope < -0.8


def test_decoupled_1d_elements_give_8fs() -> None:
    """Two 1-D elements on the x and y components of the same orbit: 8 f_s (A - d_s) exactly
    (the 1-D return map is exact at any step size)."""
    a, n = 1.7, 64
    g = _circle(a, n)
    total = 0.0
    for comp in (0, 1):
        one = np.zeros_like(g)
        one[:, comp] = g[:, comp]
        _, diss = _orbit_work(one)
        total += diss
    assert total == pytest.approx(2 * jenkins_1d_dissipation(a, FS, K), rel=1e-12)
    assert total == pytest.approx(8 * FS * (a - FS / K), rel=1e-12)


def test_inside_the_stick_circle_nothing_is_dissipated() -> None:
    work, diss = _orbit_work(_circle(0.9 * FS / K, 100))
    assert diss == 0.0
    assert abs(work) < 1e-12


finite = st.floats(-5.0, 5.0, allow_nan=False)


@settings(max_examples=60, deadline=None)
@given(gx=finite, gy=finite, sx=finite, sy=finite, k=st.floats(0.1, 10.0),
       lim=st.floats(0.01, 10.0))
def test_return_map_invariants(gx: float, gy: float, sx: float, sy: float, k: float,
                               lim: float) -> None:
    g, s = np.array([[gx, gy]]), np.array([[sx, sy]])
    r = return_map(g, s, np.array([k]), np.array([lim]))
    f = float(np.hypot(*r.force[0]))
    assert f <= lim * (1 + 1e-12)
    # The force is the spring force of the updated slip.
    np.testing.assert_allclose(r.force, k * (g - r.slip), atol=1e-12 * max(1.0, k * 10))
    assert friction_dissipation(r.force, s, r.slip) >= -1e-12
    d = np.array([[r.tangent[0, 0], r.tangent[0, 1]], [r.tangent[0, 1], r.tangent[0, 2]]])
    assert np.all(np.linalg.eigvalsh(d) >= -1e-12 * k)
    if r.slipping[0]:
        assert f == pytest.approx(lim, rel=1e-12)


def test_consistent_tangent_matches_finite_differences() -> None:
    rng = np.random.default_rng(1)
    g = rng.normal(size=(50, 2))
    s = rng.normal(size=(50, 2)) * 0.3
    k = rng.uniform(0.5, 2.0, 50)
    lim = rng.uniform(0.1, 1.5, 50)
    r = return_map(g, s, k, lim)
    h = 1e-7
    for comp, cols in ((0, (0, 1)), (1, (1, 2))):
        dg = np.zeros_like(g)
        dg[:, comp] = h
        fd = (return_map(g + dg, s, k, lim).force - return_map(g - dg, s, k, lim).force) / (2 * h)
        far = np.abs(np.hypot(*(k[:, None] * (g - s)).T) - lim) > 1e-4  # off the kink
        np.testing.assert_allclose(fd[far, 0], r.tangent[far, cols[0]], rtol=1e-5, atol=1e-7)
        np.testing.assert_allclose(fd[far, 1], r.tangent[far, cols[1]], rtol=1e-5, atol=1e-7)
    assert math.isfinite(float(r.tangent.sum()))
