"""The periodic-state passes of the 2-D Jenkins kernel (dynamics.kernels2d): the history's
derivative summed backwards over recorded slip events against the forward recursion it
replaces, and Newton's method started early against the full history of CYCLES passes."""

from __future__ import annotations

import math

import numpy as np
import pytest

from microslip.dynamics.kernels2d import (
    CYCLES,
    _advance,
    _history_derivative,
    _periodic_state,
    _solve,
    return_map,
)

N = 64
THETA = 2 * np.pi * np.arange(N) / N + 0.1234567
BASIS = np.column_stack([np.ones(N), *[g(j * THETA) for j in (1, 2, 3)
                                       for g in (np.cos, np.sin)]])


@pytest.mark.parametrize("seed", range(6))
def test_backward_sum_is_the_forward_recursion(seed):
    """``dz <- D dz + (I - D) E_t`` event by event from 0 (a virgin-state event restarting
    it), against the backward sum, to round-off, on random events and D."""
    rng = np.random.default_rng(seed)
    count = 300
    ev_t = rng.integers(0, N, count).astype(np.int64)
    ev_d = rng.uniform(-0.7, 0.7, (count, 4))
    if seed % 2:
        ev_t[-3] = -1 - ev_t[-3]  # the virgin state: earlier events drop
    h = BASIS.shape[1]
    forward = np.zeros((2, 2 * h))
    for i in range(count):
        t = int(ev_t[i])
        if t < 0:
            t = -1 - t
            forward[:, :] = 0.0
        _advance(forward, *ev_d[i], BASIS, t, h)
    backward = np.empty((2, 2 * h))
    _history_derivative(ev_t, ev_d, count, BASIS, np.empty((N, 2, 2)), backward)
    np.testing.assert_allclose(backward, forward, rtol=0, atol=1e-13 * abs(forward).max())


def _state(u, rho, ph, early):
    start = int(np.argmax(np.hypot(u[:, 0], u[:, 1])))
    virgin = math.hypot(u[start, 0], rho * u[start, 1]) > ph
    z0 = np.zeros(2)
    if virgin:
        z0[:] = return_map(u[start, 0], u[start, 1], 0.0, 0.0, rho, ph)
    dz0 = np.zeros((2, 2 * BASIS.shape[1]))
    ev_t = np.empty((CYCLES + 1) * N, dtype=np.int64)
    ev_d = np.empty(((CYCLES + 1) * N, 4))
    w = np.empty((N, 2, 2))
    if early is None:
        ok = _periodic_state(u, rho, ph, start, BASIS, z0, dz0, virgin, ev_t, ev_d, w)
    else:
        ok = _solve(u, rho, ph, start, BASIS, z0, dz0, virgin, ev_t, ev_d, w, early) == 1
    assert ok
    return z0, dz0


@pytest.mark.parametrize("seed", range(8))
@pytest.mark.parametrize("rho", [1.0, 0.05, 20.0])
def test_newton_started_early_is_the_full_history(seed, rho):
    """Per element, the periodic state and its derivative with Newton's method started as
    soon as the passes show they will not repeat, against the full CYCLES history passes:
    the same fixed point to round-off, on tilted elliptic orbits with an offset (some
    elements shake down) over slip displacements from deep slip to nearly stuck. The fixed
    point is found to 1e-15 of its scale, and (I - P)^-1 Q changes with it: up to 3.5e-11
    seen over 30 seeds."""
    rng = np.random.default_rng(seed)
    c = rng.normal(size=(BASIS.shape[1], 2))
    c[0] *= seed % 3  # an offset: shakedown for some
    u = BASIS @ c
    amp = float(np.hypot(u[:, 0], u[:, 1]).max())
    for ph in amp * np.geomspace(1e-3, 2.0, 25):
        z_full, dz_full = _state(u, rho, ph, False)
        z_early, dz_early = _state(u, rho, ph, None)
        scale = ph / min(1.0, rho) + amp
        np.testing.assert_allclose(z_early, z_full, rtol=0, atol=1e-13 * scale)
        np.testing.assert_allclose(dz_early, dz_full, rtol=0, atol=1e-10)
