"""Harmonic balance (AFT): transforms, analytic Jacobians, and the Duffing oscillator's
closed-form single-harmonic solutions (exact: a cubic's harmonics are exact on the grid)."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.optimize import brentq

from microslip.dynamics import jenkins
from microslip.dynamics.hb import HarmonicBalance, from_time, to_time
from microslip.dynamics.modal import epmc
from microslip.dynamics.response import frequency_response
from microslip.dynamics.structure import JointLink, Structure, one_mode
from microslip.errors import ParameterError

M, F0, ZETA = 2.0, 100.0, 0.01  # kg, Hz, -
K3 = 50.0  # N/mm^3


class Cubic:
    """A hardening spring f = k3 x^3 (N, x in mm): the Duffing oscillator's joint."""

    name = "cubic"
    initial_stiffness = 0.0

    def __init__(self, k3: float) -> None:
        self.k3 = k3

    def periodic_force(self, x):
        return self.k3 * x**3, np.diag(3.0 * self.k3 * x**2)

    def backbone_force(self, a):
        return self.k3 * np.asarray(a) ** 3


def duffing(zeta: float = ZETA) -> Structure:
    return one_mode(F0, M, zeta, Cubic(K3))  # type: ignore[arg-type]


def stiffness_n_per_mm() -> float:
    return M * (2 * np.pi * F0) ** 2 * 1e-3


@given(st.lists(st.floats(-1e3, 1e3), min_size=15, max_size=15))
def test_to_time_and_from_time_are_inverse(coeffs):
    c = np.array(coeffs)
    np.testing.assert_allclose(from_time(to_time(c, 32), 7), c, rtol=0,
                               atol=1e-12 * (1.0 + np.abs(c).max()))


def test_to_time_is_the_fourier_series():
    theta = 2 * np.pi * np.arange(16) / 16
    c = np.array([0.5, 1.0, -2.0, 0.25, 3.0])
    expected = 0.5 + np.cos(theta) - 2 * np.sin(theta) + 0.25 * np.cos(2 * theta) \
        + 3 * np.sin(2 * theta)
    np.testing.assert_allclose(to_time(c, 16), expected, rtol=0, atol=1e-14)


def two_dofs() -> Structure:
    """Two masses, a Jenkins joint to ground and a Jenkins joint between them."""
    m = np.diag([1.0, 2.0])
    k = np.array([[3e5, -1e5], [-1e5, 2e5]])
    return Structure(mass=m, damping=1e-4 * k, stiffness=k,
                     joints=(JointLink(jenkins(200.0, 3.0), np.array([1.0, 0.0])),
                             JointLink(jenkins(100.0, 2.0), np.array([-1.0, 1.0]))),
                     output=np.array([0.0, 1.0]))


@settings(max_examples=25, deadline=None)
@given(seed=st.integers(0, 2**32 - 1), omega=st.floats(300.0, 1500.0),
       xi=st.floats(-5.0, 5.0))
def test_analytic_jacobians_match_finite_differences(seed, omega, xi):
    hb = HarmonicBalance(two_dofs(), 3, 64)
    x = np.random.default_rng(seed).normal(size=hb.size) * 0.05
    load = hb.excitation(np.array([1.0, 0.5]), 2.0)
    res = hb.residual(x, omega, load, xi)
    h = 1e-7
    num = np.column_stack([(hb.residual(x + h * e, omega, load, xi).r
                            - hb.residual(x - h * e, omega, load, xi).r) / (2 * h)
                           for e in np.eye(hb.size)])
    # the joint force is piecewise linear: a difference across a slip event is off by
    # O(k h) in one column; elsewhere it is exact to rounding
    scale = np.abs(res.dx).max()
    assert np.median(np.abs(num - res.dx)) <= 1e-7 * scale
    dw = (hb.residual(x, omega + 1e-3, load, xi).r
          - hb.residual(x, omega - 1e-3, load, xi).r) / 2e-3
    np.testing.assert_allclose(res.dw, dw, rtol=0, atol=1e-7 * np.abs(res.dw).max())
    dxi = (hb.residual(x, omega, load, xi + 1e-3).r
           - hb.residual(x, omega, load, xi - 1e-3).r) / 2e-3
    np.testing.assert_allclose(res.dxi, dxi, rtol=0, atol=1e-9 * np.abs(res.dxi).max())


def assembled(hb, x, omega, load, xi):
    """The residual and dr/dx assembled with numpy from the formula of
    :class:`HarmonicBalance` (matrices, kron) and each joint's time-domain ``periodic_force``
    (the operator's own N x N Jacobian, no compiled AFT step)."""
    s, n_h = hb.structure, 2 * hb.harmonics + 1
    order = np.zeros(n_h)
    order[1::2] = order[2::2] = np.arange(1, hb.harmonics + 1)
    d = np.zeros((n_h, n_h))
    for k in range(1, hb.harmonics + 1):
        d[2 * k - 1, 2 * k], d[2 * k, 2 * k - 1] = k, -k
    dyn = 1e-3 * (np.kron(s.stiffness, np.eye(n_h)) - omega**2 * np.kron(s.mass, np.diag(order**2))
                  + omega * np.kron(s.damping - xi * s.mass, d))
    synth = to_time(np.eye(n_h), hb.samples).T
    r, jac = dyn @ x - load, dyn.copy()
    for link in s.joints:
        b = np.kron(link.participation[:, None], np.eye(n_h))
        f, j = link.operator.periodic_force(synth @ (b.T @ x))
        r += b @ from_time(f, hb.harmonics)
        jac += b @ from_time(j.T, hb.harmonics).T @ synth @ b.T
    return r, jac


@settings(max_examples=25, deadline=None)
@given(seed=st.integers(0, 2**32 - 1), omega=st.floats(300.0, 1500.0),
       xi=st.floats(-5.0, 5.0), cubic=st.booleans())
def test_compiled_residual_is_the_assembled_balance(seed, omega, xi, cubic):
    s = two_dofs()
    if cubic:  # a joint the compiled call does not take, added in Python on top
        s = Structure(mass=s.mass, damping=s.damping, stiffness=s.stiffness,
                      joints=(*s.joints, JointLink(Cubic(K3), np.array([0.5, 1.0]))),
                      output=s.output)
    hb = HarmonicBalance(s, 3, 64)
    x = np.random.default_rng(seed).normal(size=hb.size) * 0.05
    load = hb.excitation(np.array([1.0, 0.5]), 2.0)
    res = hb.residual(x, omega, load, xi)
    r, jac = assembled(hb, x, omega, load, xi)
    np.testing.assert_allclose(res.r, r, rtol=0, atol=1e-12 * np.abs(r).max())
    np.testing.assert_allclose(res.dx, jac, rtol=0, atol=1e-12 * np.abs(jac).max())


def test_duffing_backbone_single_harmonic_is_exact():
    a = np.geomspace(0.01, 2.0, 12)
    curve = epmc(duffing(0.0), a, harmonics=1, samples=16)
    k = stiffness_n_per_mm()
    omega2 = (k + 0.75 * K3 * a**2) / (M * 1e-3)
    np.testing.assert_allclose(curve.frequency, np.sqrt(omega2) / (2 * np.pi), rtol=1e-12)
    np.testing.assert_allclose(curve.damping_ratio, 0.0, atol=1e-12)


def test_duffing_frf_single_harmonic_matches_the_closed_form_and_its_peak():
    force = 2.0  # N
    r = frequency_response(duffing(), force, np.array([1.0]), (80.0, 160.0), harmonics=1,
                           samples=16)
    assert r.success and r.frequency[-1] == 160.0
    a, w = r.amplitude, 2 * np.pi * r.frequency
    k, m, c = stiffness_n_per_mm(), M * 1e-3, 2 * ZETA * M * 2 * np.pi * F0 * 1e-3
    lhs = np.hypot(k + 0.75 * K3 * a**2 - m * w**2, c * w) * a
    np.testing.assert_allclose(lhs, force, rtol=1e-9)

    # closed-form peak: dA/dw = 0 where k + 3/4 k3 A^2 - m w^2 = c^2 / (2 m)
    def gap(amp):
        w2 = (k + 0.75 * K3 * amp**2 - c**2 / (2 * m)) / m
        return np.hypot(c**2 / (2 * m), c * np.sqrt(w2)) * amp - force

    amp = brentq(gap, 1e-6, 10.0, xtol=1e-15)
    w_peak = np.sqrt((k + 0.75 * K3 * amp**2 - c**2 / (2 * m)) / m)
    assert r.peak_amplitude == pytest.approx(amp, rel=1e-9)
    assert r.peak_frequency == pytest.approx(w_peak / (2 * np.pi), rel=1e-9)
    assert r.peak_amplitude >= a.max()


def test_bad_balance_settings_are_refused():
    with pytest.raises(ParameterError, match="samples must be"):
        HarmonicBalance(duffing(), 7, 15)
    with pytest.raises(ParameterError, match="harmonics must be"):
        HarmonicBalance(duffing(), 0)


def test_amplitudes_at_once_are_the_amplitudes_one_by_one():
    """:meth:`HarmonicBalance.amplitudes` against :meth:`amplitude` on random coefficients
    of a 3-DOF structure with a mixed output coordinate."""
    structure = Structure(mass=np.eye(3), stiffness=4e6 * np.eye(3), damping=np.eye(3),
                          joints=(JointLink(jenkins(300.0, 5.0), np.array([1.0, 0.0, 0.0])),),
                          output=np.array([0.3, -1.0, 2.0]))
    hb = HarmonicBalance(structure, 3, 16)
    xs = np.random.default_rng(1).normal(size=(5, hb.size))
    one_by_one = [hb.amplitude(x)[0] for x in xs]
    assert np.allclose(hb.amplitudes(xs), one_by_one, rtol=1e-15, atol=0.0)
