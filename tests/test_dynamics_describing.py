"""Describing function: the Jenkins closed form, the rigid-bar dissipation, invariants."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import microslip
from microslip.dynamics.describing import amplitude_for_force, describing_function
from microslip.dynamics.distributions import clamp_joint, iwan4_segalman
from microslip.dynamics.operators import jenkins
from microslip.errors import ParameterError

K, FS = 100.0, 5.0  # N/mm, N
DS = FS / K


def jenkins_closed_form(a: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """REFERENCES.md: K_eq = (k/pi)(beta - sin(2 beta)/2), D_eq = 4 f_s (A - d_s)/(pi A^2)."""
    beta = np.arccos(np.clip(1.0 - 2.0 * DS / a, -1.0, 1.0))
    slipping = a > DS
    k_eq = np.where(slipping, K / np.pi * (beta - np.sin(2.0 * beta) / 2.0), K)
    d_eq = np.where(slipping, 4.0 * FS * (a - DS) / (np.pi * a**2), 0.0)
    return k_eq, d_eq


AMPS = np.array([0.3, 0.9, 1.07, 1.5, 3.3, 20.0, 1000.0]) * DS


@pytest.mark.parametrize("samples", [1024, 4096])
def test_jenkins_describing_function_closed_form(samples):
    """Exact up to the rectangle rule's error on a force with slope kinks, O(N^-2):
    |error| <= 4 k / N^2 (measured up to 1.7 k / N^2 on these amplitudes)."""
    r = describing_function(jenkins(K, FS), AMPS, samples)
    k_eq, d_eq = jenkins_closed_form(AMPS)
    bound = 4.0 * K / samples**2
    np.testing.assert_allclose(r.stiffness, k_eq, rtol=0, atol=bound)
    np.testing.assert_allclose(r.damping, d_eq, rtol=0, atol=bound)
    w_exact = 4.0 * FS * np.maximum(AMPS - DS, 0.0)
    assert np.all(np.abs(r.dissipated_energy - w_exact) <= bound * np.pi * AMPS**2)


def test_jenkins_stuck_is_exact():
    a = np.array([0.1, 0.5, 1.0]) * DS
    r = describing_function(jenkins(K, FS), a, 64)
    np.testing.assert_allclose(r.stiffness, K, rtol=1e-14)
    np.testing.assert_allclose(r.damping, 0.0, atol=1e-12 * K)
    np.testing.assert_allclose(r.force, K * a, rtol=1e-14)


def test_tip_joint_dissipation_is_the_rigid_bar_closed_form():
    """W_d = 2 F0^3/(3 E A q) (Goodman & Klumpp): the series spring stores but does not
    dissipate. Error of the 1600-element interpolation of the backbone ~ n^-2."""
    p = microslip.preset("table1")
    opt = microslip.ModelOptions(poisson="off", length_update=False)
    op = clamp_joint("tip", p, 1.0e6, elements=1600, options=opt)
    f0 = np.array([50.0, 150.0, 300.0])
    r = describing_function(op, amplitude_for_force(op, f0), 2048)
    np.testing.assert_allclose(r.force, f0, rtol=1e-13)
    exact = 2.0 * f0**3 / (3.0 * p.axial_stiffness * p.friction_per_length)
    np.testing.assert_allclose(r.dissipated_energy, exact, rtol=2e-5)


@settings(max_examples=30, deadline=None)
@given(chi=st.floats(-0.9, 0.0), beta=st.floats(0.0, 5.0),
       amp=st.floats(1e-4, 1e2))
def test_iwan_describing_function_invariants(chi, beta, amp):
    """0 <= D_eq, 0 < K_eq <= K_T, W_d <= 4 F_S A (rigid-plastic bound), eta >= 0."""
    kt, fs = 1000.0, 10.0
    op = iwan4_segalman(kt, fs, chi, beta, elements=40)
    a = np.array([amp]) * fs / kt
    r = describing_function(op, a, 256)
    assert 0.0 < r.stiffness[0] <= kt * (1.0 + 1e-12)
    assert r.damping[0] >= -1e-9 * kt
    assert r.dissipated_energy[0] <= 4.0 * fs * a[0] * (1.0 + 1e-9)
    assert r.loss_factor[0] >= -1e-9


def test_amplitude_for_force_inverts_the_virgin_curve():
    op = iwan4_segalman(1000.0, 10.0, -0.3, 0.2, elements=30)
    f = np.array([0.5, 5.0, 9.99])
    a = amplitude_for_force(op, f)
    np.testing.assert_allclose(op.backbone_force(a), f, rtol=1e-13)


def test_force_at_macroslip_is_refused():
    with pytest.raises(ParameterError, match="below the joint's macroslip force 5 N"):
        amplitude_for_force(jenkins(K, FS), [5.0])


@pytest.mark.parametrize("bad", [[0.0], [-1.0], [np.nan], []])
def test_bad_amplitudes_are_refused(bad):
    with pytest.raises(ParameterError, match="amplitudes must be finite and > 0 mm"):
        describing_function(jenkins(K, FS), bad)
