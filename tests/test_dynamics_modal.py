"""Nonlinear modal analysis: energy method, extended periodic motion concept (EPMC), the
hysteresis loop's W_d / (4 pi U) and the stuck linear limit."""

from __future__ import annotations

import numpy as np
import pytest

from microslip.dynamics import jenkins
from microslip.dynamics.distributions import iwan4_segalman
from microslip.dynamics.modal import METHODS, energy_method, epmc
from microslip.dynamics.structure import one_mode
from microslip.errors import ParameterError

M, F0 = 2.0, 100.0  # kg, Hz
IWAN = iwan4_segalman(300.0, 5.0, -0.5, 0.1, 100)
AMPS = np.geomspace(1e-3, 0.3, 12)  # mm


@pytest.mark.parametrize("joint", [jenkins(300.0, 5.0), IWAN], ids=["jenkins", "iwan"])
def test_epmc_with_one_harmonic_is_the_energy_method(joint):
    """Same describing function, same quadrature: equal to solver tolerance."""
    s = one_mode(F0, M, 0.02, joint, participation=0.7)
    e, en = epmc(s, AMPS, 1, 256), energy_method(s, AMPS, 256)
    np.testing.assert_allclose(e.frequency, en.frequency, rtol=1e-12)
    np.testing.assert_allclose(e.damping_ratio, en.damping_ratio, rtol=1e-10)


def test_energy_method_and_epmc_agree_where_damping_is_light():
    s = one_mode(F0, M, 0.0, IWAN)
    e, en = epmc(s, AMPS, 7, 256), energy_method(s, AMPS, 256)
    assert e.damping_ratio.max() < 0.035
    np.testing.assert_allclose(en.frequency, e.frequency, rtol=1e-4)
    np.testing.assert_allclose(en.damping_ratio, e.damping_ratio, rtol=3e-3)


def loop_damping(joint, a, omega, samples=20_000):
    """W_d / (4 pi U) of the joint's own hysteresis loop at amplitude a, traced from the
    virgin state by the operator's history (second cycle), U = m w^2 a^2 / 2."""
    theta = 2 * np.pi * np.arange(2 * samples + 1) / samples
    x = a * np.cos(theta)
    f = joint.force_history(x).force
    xs, fs = x[samples:], f[samples:]
    w_d = np.sum(0.5 * (fs[1:] + fs[:-1]) * np.diff(xs))  # closed integral f dx
    u = 0.5 * M * omega**2 * (a * 1e-3) ** 2  # J = N m
    return w_d * 1e-3 / (4 * np.pi * u)


@pytest.mark.parametrize("joint", [jenkins(300.0, 5.0), IWAN], ids=["jenkins", "iwan"])
def test_damping_ratio_is_w_d_over_4_pi_u_of_the_loop(joint):
    s = one_mode(F0, M, 0.0, joint)
    curve = energy_method(s, AMPS, 2048)
    for a, f, zeta in zip(curve.amplitude, curve.frequency, curve.damping_ratio,
                          strict=True):
        ref = loop_damping(joint, a, 2 * np.pi * f)
        assert zeta == pytest.approx(ref, rel=0.5 * (2 * np.pi / 2048) ** 2, abs=1e-15)


def test_stuck_limit_is_the_linear_mode_with_its_damping():
    zeta = 0.03
    s = one_mode(F0, M, zeta, jenkins(300.0, 5.0))
    f_stuck = float(s.linear_frequencies(stuck=True)[0])
    assert f_stuck == pytest.approx(np.sqrt(F0**2 + 300e3 / M / (2 * np.pi) ** 2), rel=1e-14)
    for name, method in METHODS.items():
        c = method(s, np.array([1e-3, 1e-2]), 5, 64)  # below slip, 5 / 300 mm
        np.testing.assert_allclose(c.frequency, f_stuck, rtol=1e-12, err_msg=name)
        np.testing.assert_allclose(c.damping_ratio, zeta * F0 / f_stuck, rtol=1e-10,
                                   err_msg=name)


def test_bad_amplitudes_are_refused():
    s = one_mode(F0, M, 0.0, IWAN)
    with pytest.raises(ParameterError, match="> 0 mm"):
        epmc(s, [0.1, -1.0], 3)
    with pytest.raises(ParameterError, match="> 0 mm"):
        energy_method(s, [np.nan])
