"""Many degrees of freedom, several joints, two-directional joints: the circular Iwan
operator against the 1-D operator and the 2-D Jenkins closed form, harmonic balance of
2-DOF systems against time integration to steady state, the one-mode structure as a
special case of the matrix structure."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import assume, example, given, settings
from hypothesis import strategies as st
from scipy.optimize import minimize_scalar

from microslip import preset
from microslip.dynamics import clamp_joint, jenkins
from microslip.dynamics.hb import to_time
from microslip.dynamics.modal import energy_method, epmc
from microslip.dynamics.operators2d import circular
from microslip.dynamics.response import frequency_response
from microslip.dynamics.structure import JointLink, Structure, one_mode
from microslip.dynamics.timeint import steady_state, transient

KJ, FS = 100.0, 5.0  # N/mm, N
DS = FS / KJ  # mm
TIP = clamp_joint("tip", preset("table1"), 1e5, elements=60)


@settings(max_examples=20, deadline=None)
@given(coef=st.lists(st.floats(-1.0, 1.0, allow_nan=False), min_size=7, max_size=7),
       scale=st.floats(0.05, 3.0), axis=st.sampled_from([0, 1]))
@example(coef=[1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0], scale=1.0, axis=0)
@example(coef=[0.9, 0.0, 0.1, 0.0, 0.0, 0.0, 0.0], scale=0.7, axis=1)
def test_circular_operator_along_one_axis_is_the_1d_operator(coef, scale, axis):
    """Force and Jacobian (J @ E) to 1e-12; no force across the axis. A motion whose peak or
    half range lands on a slider's slip displacement (to 1e-9) is left out: there the
    Jacobian has a kink, and the two operators may take either one-sided derivative (the
    example below, peak = the last slider's slip, found by hypothesis, is such a tie)."""
    x = to_time(np.asarray(coef) * float(TIP.slip.max()) * scale, 64)
    tie = 1e-9 * float(TIP.slip.max())
    for level in (np.abs(x).max(), 0.5 * (x.max() - x.min())):
        assume(np.all(np.abs(TIP.slip - level) > tie))
    basis = np.ascontiguousarray(to_time(np.eye(7), 64).T)
    f1, j1 = TIP.periodic_force_projected(x, basis)
    u = np.zeros((64, 2))
    u[:, axis] = x
    f2, j2 = circular(TIP).periodic_force_projected(u, basis)
    np.testing.assert_allclose(f2[:, axis], f1, rtol=0, atol=1e-12 * TIP.slip_force)
    np.testing.assert_array_equal(f2[:, 1 - axis], 0.0)
    np.testing.assert_allclose(j2[:, axis, axis], j1, rtol=0,
                               atol=1e-12 * TIP.initial_stiffness)
    np.testing.assert_array_equal(j2[:, 1 - axis, axis], 0.0)


@pytest.mark.parametrize("radius", [0.06, 0.2, 1.0])
def test_circular_orbit_against_the_2d_jenkins_closed_form(radius):
    """W_d = 2 pi f_s sqrt(A^2 - d_s^2) (REFERENCES.md). The radial return follows the
    chord between samples, so the sampled loop converges like N^-1: measured error
    pi d_s / (N sqrt(A^2 - d_s^2)) (half the bound asserted), a factor 4 per 4 N."""
    op = circular(jenkins(KJ, FS))
    exact = 2 * np.pi * FS * np.sqrt(radius**2 - DS**2)
    errors = []
    for n in (1024, 4096):
        theta = 2 * np.pi * np.arange(n) / n
        u = radius * np.column_stack([np.cos(theta), np.sin(theta)])
        f = op.periodic_force(u)
        w_d = np.sum(0.5 * (f + np.roll(f, -1, axis=0)) * (np.roll(u, -1, axis=0) - u))
        assert np.allclose(np.hypot(f[:, 0], f[:, 1]), FS, rtol=1e-15)  # always slipping
        err = abs(w_d / exact - 1)
        assert err < 2 * np.pi * DS / (n * np.sqrt(radius**2 - DS**2))
        errors.append(err)
    assert 3.5 < errors[0] / errors[1] < 4.5


def chain(joint_dofs: tuple[int, int]) -> Structure:
    """2 DOFs, 1 kg and 0.5 kg in a chain, 100 Hz scale, 2 % damping of the first mode; a
    Jenkins joint between ``joint_dofs`` (-1 ground)."""
    k = (2 * np.pi * 100.0) ** 2
    m = np.diag([1.0, 0.5])
    kk = np.array([[2 * k, -k], [-k, k]])
    w = np.zeros(2)
    w[joint_dofs[0]] = 1.0
    if joint_dofs[1] >= 0:
        w[joint_dofs[1]] = -1.0
    return Structure(mass=m, damping=0.02 / (2 * np.pi * 100.0) * kk, stiffness=kk,
                     joints=(JointLink(jenkins(KJ, FS), w),), output=np.array([1.0, 0.0]))


def planar(coupled: bool) -> Structure:
    """Two modes of a 1 kg mass at 100 and 101.5 Hz (bending in two planes), 1 % damping,
    a 2-D Jenkins joint to the ground: circular or two 1-D elements."""
    m = np.eye(2)
    k = np.diag([1.0, 1.03]) * (2 * np.pi * 100.0) ** 2
    c = 2 * 0.01 * 2 * np.pi * 100.0 * m
    op = jenkins(KJ, FS)
    links = ((JointLink(circular(op), np.eye(2)),) if coupled
             else (JointLink(op, np.eye(2)[0]), JointLink(op, np.eye(2)[1])))
    return Structure(mass=m, damping=c, stiffness=k, joints=links, output=np.array([1.0, 0.0]))


def peak_by_time_integration(structure, load, guess, steps):
    def minus(f):
        s = transient(structure, load, f, periods=400, steps=steps)
        assert s.change < 1e-6
        return -s.amplitude

    r = minimize_scalar(minus, bracket=(0.995 * guess, guess), options={"xtol": 1e-5})
    return r.x, -r.fun


@pytest.mark.slow
@pytest.mark.parametrize(("name", "structure", "load", "band", "samples"), [
    ("1-D joint between DOFs", chain((0, 1)), np.array([0.0, 4.0]), (60.0, 100.0), 128),
    ("coupled 2-D joint", planar(True), np.array([3.0, 3.0]), (85.0, 135.0), 512),
])
def test_two_dof_harmonic_balance_against_time_integration(name, structure, load, band,
                                                           samples):
    """Peak amplitude and frequency within 0.5 % (7 harmonics). The circular joint's AFT
    converges like N^-1 (test above), so it takes 512 samples."""
    r = frequency_response(structure, 1.0, load, band, 7, samples)
    assert r.success
    f_ti, a_ti = peak_by_time_integration(structure, load, r.peak_frequency, 1000)
    assert r.peak_frequency == pytest.approx(f_ti, rel=5e-3)
    assert r.peak_amplitude == pytest.approx(a_ti, rel=5e-3)


def test_explicit_integration_is_the_newmark_reference_for_one_dof():
    s = one_mode(100.0, 2.0, 0.02, jenkins(300.0, 5.0))
    a = steady_state(s, 5.0, 110.0, periods=150, steps=500)
    b = transient(s, np.array([5.0]), 110.0, periods=150, steps=500)
    assert b.amplitude == pytest.approx(a.amplitude, rel=(2 * np.pi / 500) ** 2)


def test_one_mode_is_a_one_dof_matrix_structure():
    """The same structure built from matrices gives the same curve, bit for bit."""
    s = one_mode(100.0, 2.0, 0.01, jenkins(300.0, 5.0))
    same = Structure(mass=np.array(s.mass), damping=np.array(s.damping),
                     stiffness=np.array(s.stiffness),
                     joints=(JointLink(jenkins(300.0, 5.0), np.array([1.0])),),
                     output=np.array([1.0]))
    a = frequency_response(s, 3.0, np.ones(1), (90.0, 130.0), 3, 64)
    b = frequency_response(same, 3.0, np.ones(1), (90.0, 130.0), 3, 64)
    np.testing.assert_array_equal(a.amplitude, b.amplitude)


def test_decoupled_joint_damps_less_on_a_line_than_on_an_ellipse():
    """Along one mode the joint moves on a line: circular and decoupled are the same
    joint there (energy method, which follows the linear mode)."""
    amps = np.geomspace(0.01, 0.5, 6)
    c, d = energy_method(planar(True), amps), energy_method(planar(False), amps)
    np.testing.assert_allclose(c.damping_ratio, d.damping_ratio, rtol=1e-13)
    e = epmc(planar(True), amps, 3, 64)
    np.testing.assert_allclose(e.frequency, epmc(planar(False), amps, 3, 64).frequency,
                               rtol=1e-9)
