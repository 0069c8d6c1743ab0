"""Forced response of a 1-DOF oscillator with a Jenkins joint: the single-harmonic balance
against the classical closed form, and 7 harmonics against time integration."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.optimize import minimize_scalar

from microslip import preset
from microslip.dynamics import clamp_joint, jenkins
from microslip.dynamics.continuation import MAX_ITERATIONS, arclength, newton
from microslip.dynamics.hb import HarmonicBalance
from microslip.dynamics.response import frequency_response
from microslip.dynamics.structure import one_mode
from microslip.dynamics.timeint import steady_state

M, F0 = 2.0, 100.0  # kg, Hz
KJ, FS = 300.0, 5.0  # N/mm, N
ONE = np.array([1.0])


def closed_form_gap(a, omega, force, zeta):
    """|[(k + K_eq - m w^2)^2 + (c w + D_eq)^2]^(1/2) A / F - 1| (REFERENCES.md)."""
    ds = FS / KJ
    beta = np.arccos(np.clip(1 - 2 * ds / a, -1, 1))
    k_eq = np.where(a > ds, KJ / np.pi * (beta - np.sin(2 * beta) / 2), KJ)
    d_eq = np.where(a > ds, 4 * FS * (a - ds) / (np.pi * a**2), 0.0)
    k = M * (2 * np.pi * F0) ** 2 * 1e-3
    c = 2 * zeta * M * 2 * np.pi * F0 * 1e-3
    return np.abs(np.hypot(k + k_eq - M * 1e-3 * omega**2, c * omega + d_eq) * a / force - 1)


def solve_at(hb, load, omega, guess):
    def fun(x):
        res = hb.residual(x, omega, load)
        return res.r, res.dx

    x, ok, _ = newton(fun, guess, np.full(guess.size, 0.01), 1e-12, max_iter=50)
    assert ok
    return x


def test_single_harmonic_balance_converges_to_the_closed_form():
    """The slip onset is a kink of the joint force in time, so the rectangle rule of the
    AFT scheme has an O(N^-2) error whose constant oscillates with where the kink falls
    between samples: bounded by (2 pi / N)^2 / 2, and 4 times more samples gain more than
    a factor 4 (measured 11)."""
    structure = one_mode(F0, M, 0.01, jenkins(KJ, FS))
    omegas = 2 * np.pi * np.array([100.0, 108.0, 112.0, 125.0])  # stuck, slipping, peak
    errors = []
    for n in (256, 1024):
        hb = HarmonicBalance(structure, 1, n)
        load = hb.excitation(ONE, 3.0)
        gaps = []
        for w in omegas:
            x = solve_at(hb, load, w, hb.stuck_guess(w, load))
            gaps.append(closed_form_gap(hb.amplitude(x)[0], w, 3.0, 0.01))
        assert max(gaps) < 0.5 * (2 * np.pi / n) ** 2
        assert gaps[0] < 1e-14  # stuck: linear, exact
        errors.append(max(gaps))
    assert errors[0] / errors[1] > 4


def test_the_curve_passes_the_slip_onset_and_ends_at_the_range_end():
    r = frequency_response(one_mode(F0, M, 0.01, jenkins(KJ, FS)), 3.0, ONE, (80.0, 140.0),
                           harmonics=1, samples=128)
    assert r.success and r.frequency[0] == 80.0 and r.frequency[-1] == 140.0
    assert r.amplitude.min() < FS / KJ < r.amplitude.max()
    assert np.all(closed_form_gap(r.amplitude, 2 * np.pi * r.frequency, 3.0, 0.01)
                  < 4 * (2 * np.pi / 128) ** 2)
    assert r.peak_amplitude >= r.amplitude.max()


def test_seven_harmonics_against_time_integration_to_steady_state():
    """Newmark (T/500 steps, 150 periods: transients decay below 1e-11) from rest."""
    structure = one_mode(F0, M, 0.02, jenkins(KJ, FS))
    force = 5.0
    r = frequency_response(structure, force, ONE, (80.0, 140.0), harmonics=7, samples=128)

    def minus_amplitude(f):
        s = steady_state(structure, force, f, periods=150, steps=500)
        assert s.change < 1e-8
        return -s.amplitude

    peak = minimize_scalar(minus_amplitude, bracket=(0.98 * r.peak_frequency,
                                                     r.peak_frequency),
                           options={"xtol": 1e-5})
    assert r.peak_frequency == pytest.approx(peak.x, rel=5e-3)
    assert r.peak_amplitude == pytest.approx(-peak.fun, rel=5e-3)
    # the whole curve, point by point (fewer periods off resonance are settled too)
    for i in range(0, r.frequency.size, 25):
        s = steady_state(structure, force, float(r.frequency[i]), periods=150, steps=500)
        assert s.amplitude == pytest.approx(r.amplitude[i], rel=1e-3)


@pytest.mark.parametrize("force", [20.0, 50.0])
def test_the_located_peak_is_where_the_slope_changes_sign(force):
    """dA/dw (implicit function theorem at the solved balance) is > 0 just below the
    located peak and < 0 just above it, 1e-10 of the frequency away, and A there is not
    below any continuation point: the tip joint's peak is a corner of A(w), where dA/dw
    jumps (the smooth peak is checked against Duffing's closed form in test_dynamics_hb)."""
    from microslip import preset
    from microslip.dynamics import clamp_joint

    s = one_mode(1000.0, 1.0, 0.002, clamp_joint("tip", preset("table1"), 1e5))
    band = (0.8 * float(s.linear_frequencies(stuck=False)[0]),
            float(s.linear_frequencies(stuck=True)[0]) / 0.8)
    r = frequency_response(s, force, ONE, band, 5, 64)
    hb = HarmonicBalance(s, 5, 64)
    load = hb.excitation(ONE, force)
    assert 0 < int(np.argmax(r.amplitude)) < r.amplitude.size - 1
    assert r.peak_amplitude >= r.amplitude.max()

    def slope(f):
        j = int(np.searchsorted(r.frequency, f))
        x = solve_at(hb, load, 2 * np.pi * f, r.coefficients[j])
        res = hb.residual(x, 2 * np.pi * f, load)
        return hb.amplitude(x)[1] @ np.linalg.solve(res.dx, -res.dw)

    assert slope(r.peak_frequency * (1 - 1e-10)) > 0.0 > slope(r.peak_frequency * (1 + 1e-10))


def _tip_balance():
    structure = one_mode(1000.0, 1.0, 0.002, clamp_joint("tip", preset("table1"), 1e5))
    hb = HarmonicBalance(structure, 7, 128)
    return hb, hb.excitation(ONE, 50.0)


def test_the_compiled_corrector_is_python_newton_on_the_augmented_system():
    """Corrector by corrector from predictors far off the curve (steps that need halving,
    some that fail), the compiled Newton agrees with :func:`newton` to rounding."""
    hb, load = _tip_balance()
    compiled = hb.corrector(load, MAX_ITERATIONS)
    assert compiled is not None
    n = hb.size
    w0 = 2 * np.pi * 1400.0
    x0 = solve_at(hb, load, w0, hb.stuck_guess(w0, load))
    scale = np.append(np.full(n, 0.005), 2 * np.pi * 1000.0)
    rng = np.random.default_rng(3)
    outcomes = set()
    for _ in range(40):
        y_pred = np.append(x0, w0) + rng.normal(size=n + 1) * scale * rng.choice([0.01, 0.3, 1])
        row = rng.normal(size=n + 1) / scale**2 * np.eye(n + 1)[-1]  # frequency fixed
        row += rng.normal(size=n + 1) / scale**2 * 0.1

        def aug(z, y_pred=y_pred, row=row):
            res = hb.residual(z[:-1], z[-1], load)
            return np.append(res.r, row @ (z - y_pred)), np.vstack([res.jac, row])

        y_py, ok_py, jac_py = newton(aug, y_pred, scale, 1e-10)
        y_c, ok_c, jac_c = compiled(y_pred, row, scale, 1e-10)
        assert ok_c == ok_py
        outcomes.add(ok_py)
        # the same iterates, converged or not (a failed one ends on the same last iterate)
        assert np.max(np.abs((y_c - y_py) / scale)) < 1e-9
        assert np.allclose(jac_c, jac_py, rtol=1e-9, atol=0.0)
    assert outcomes == {True, False}  # both branches exercised


def test_the_compiled_continuation_gives_the_python_one():
    """The whole curve with the compiled corrector and with the Python one: same points."""
    hb, load = _tip_balance()
    lo, hi = 2 * np.pi * 900.0, 2 * np.pi * 2000.0
    x0 = solve_at(hb, load, lo, hb.stuck_guess(lo, load))
    scale = np.append(np.full(hb.size, np.hypot(x0[1], x0[2])), hi - lo)
    direction = np.eye(hb.size + 1)[-1]

    def fun(y):
        res = hb.residual(y[:-1], y[-1], load)
        return res.r, res.jac

    curves = [arclength(fun, np.append(x0, lo), direction, 0.02, lambda y: y[-1] >= hi,
                        scale, tol=1e-10, corrector=c)
              for c in (None, hb.corrector(load, MAX_ITERATIONS))]
    assert curves[0].success and curves[1].success
    assert curves[0].points.shape == curves[1].points.shape
    assert np.max(np.abs((curves[0].points - curves[1].points) / scale)) < 1e-10
