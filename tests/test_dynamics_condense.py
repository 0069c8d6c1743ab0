"""Harmonic balance condensed onto the joints' harmonics: the same solutions as the balance
in all coefficients, its Jacobian against finite differences."""

from __future__ import annotations

import numpy as np
import pytest

from microslip import preset
from microslip.dynamics import clamp_joint, condense, response
from microslip.dynamics.condense import Condensed, condensable
from microslip.dynamics.hb import HarmonicBalance
from microslip.dynamics.operators2d import circular
from microslip.dynamics.structure import JointLink, Structure

TIP = clamp_joint("tip", preset("table1"), 1e5, elements=60)


def chain(n: int = 4, planar: bool = False, dashpot: float = 0.0) -> Structure:
    """A fixed-free chain of n masses (0.1 kg, 4e7 N/m, C = 1e-5 K, plus ``dashpot`` N s/m
    from DOF 0 to the ground: damping no longer proportional); a tip joint from DOF 1 to
    the ground and one between the last two DOFs (two-directional if ``planar``: the second
    direction on DOF 0)."""
    k = 4e7
    kk = (np.diag(np.full(n, 2 * k)) - np.diag(np.full(n - 1, k), 1)
          - np.diag(np.full(n - 1, k), -1))
    kk[-1, -1] = k
    second = np.zeros(n)
    second[-1], second[-2] = 1.0, -1.0
    if planar:
        w = np.zeros((n, 2))
        w[:, 0] = second
        w[0, 1] = 1.0
        last = JointLink(circular(TIP), w)
    else:
        last = JointLink(TIP, second)
    cc = 1e-5 * kk
    cc[0, 0] += dashpot
    return Structure(mass=0.1 * np.eye(n), damping=cc, stiffness=kk,
                     joints=(JointLink(TIP, np.eye(n)[1]), last), output=np.eye(n)[-1])


@pytest.mark.parametrize(("planar", "dashpot"), [(False, 0.0), (True, 0.0), (False, 200.0)])
def test_condensed_residual_vanishes_at_the_full_solution_and_rebuilds_it(planar, dashpot):
    """Proportional damping (modal sums) and not (a solve per harmonic)."""
    s = chain(planar=planar, dashpot=dashpot)
    hb = HarmonicBalance(s, 5, 64)
    assert condensable(hb)
    modes = condense._modes(s.stiffness, s.mass, s.damping)
    assert (modes is None) == (dashpot > 0.0)
    load = hb.excitation(np.full(s.dofs, 40.0), 1.0)
    w = 2 * np.pi * 0.95 * float(s.linear_frequencies(stuck=True)[0])
    x, _ = response._solve_at(response._Full(hb, load), w, hb.stuck_guess(w, load))
    c = Condensed(hb, load)
    u = c.joints(x)
    r, _ = c.residual(np.append(u, w))
    np.testing.assert_allclose(r, 0.0, rtol=0, atol=1e-12 * np.abs(u).max())
    np.testing.assert_allclose(c.coefficients(u, w), x, rtol=0, atol=1e-12 * np.abs(x).max())


def test_condensed_jacobian_matches_finite_differences():
    s = chain()
    hb = HarmonicBalance(s, 3, 64)
    load = hb.excitation(np.full(s.dofs, 40.0), 1.0)
    c = Condensed(hb, load)
    rng = np.random.default_rng(1)
    w = 2 * np.pi * float(s.linear_frequencies(stuck=True)[0])
    y = np.append(2e-3 * rng.standard_normal(c.size), w)
    _, jac = c.residual(y)
    for i in range(y.size):
        step = 1e-7 * (w if i == c.size else 2e-3)
        e = np.zeros(y.size)
        e[i] = step
        fwd = (c.residual(y + e)[0] - c.residual(y)[0]) / step
        bwd = (c.residual(y)[0] - c.residual(y - e)[0]) / step
        if np.allclose(fwd, bwd, rtol=0, atol=1e-6 * np.abs(jac).max()):  # no kink
            np.testing.assert_allclose(jac[:, i], 0.5 * (fwd + bwd), rtol=0,
                                       atol=1e-6 * np.abs(jac).max())


def test_condensed_modal_sums_are_the_solves_per_harmonic(monkeypatch):
    s = chain(planar=True)
    hb = HarmonicBalance(s, 3, 64)
    load = hb.excitation(np.full(s.dofs, 40.0), 1.0)
    rng = np.random.default_rng(3)
    modal = Condensed(hb, load)
    monkeypatch.setattr(condense, "_modes", lambda k, m, c: None)
    solved = Condensed(hb, load)
    y = np.append(2e-3 * rng.standard_normal(modal.size), 0.0)
    ys = []
    for f in (0.3, 1.0, 2.5):
        y[-1] = 2 * np.pi * f * float(s.linear_frequencies(stuck=True)[0])
        (r, jac), (r_ref, jac_ref) = modal.residual(y), solved.residual(y)
        np.testing.assert_allclose(r, r_ref, rtol=0, atol=1e-13 * np.abs(r_ref).max())
        np.testing.assert_allclose(jac, jac_ref, rtol=0, atol=1e-13 * np.abs(jac_ref).max())
        x, x_ref = modal.coefficients(y[:-1], y[-1]), solved.coefficients(y[:-1], y[-1])
        np.testing.assert_allclose(x, x_ref, rtol=0, atol=1e-13 * np.abs(x_ref).max())
        ys.append(y.copy())
    xs, xs_ref = modal.along(np.array(ys)), solved.along(np.array(ys))
    for x, x_ref, y in zip(xs, xs_ref, ys, strict=True):  # each point its own
        assert np.array_equal(x_ref, solved.coefficients(y[:-1], y[-1]))
        np.testing.assert_allclose(x, x_ref, rtol=0, atol=1e-13 * np.abs(x_ref).max())


def test_condensed_amplitude_is_that_of_the_rebuilt_coefficients_and_its_gradient():
    s = chain()
    hb = HarmonicBalance(s, 3, 64)
    load = hb.excitation(np.full(s.dofs, 40.0), 1.0)
    c = Condensed(hb, load)
    rng = np.random.default_rng(2)
    w = 2 * np.pi * float(s.linear_frequencies(stuck=True)[0])
    y = np.append(2e-3 * rng.standard_normal(c.size), w)
    a, grad = c.amplitude(y)
    assert a == pytest.approx(hb.amplitude(c.coefficients(y[:-1], w))[0], rel=1e-13)
    for i in range(y.size):
        step = 1e-7 * (w if i == c.size else 2e-3)
        e = np.zeros(y.size)
        e[i] = step
        fwd = (c.amplitude(y + e)[0] - a) / step
        bwd = (a - c.amplitude(y - e)[0]) / step
        if abs(fwd - bwd) <= 1e-6 * np.abs(grad).max():  # no kink
            assert grad[i] == pytest.approx(0.5 * (fwd + bwd), rel=0,
                                            abs=1e-6 * np.abs(grad).max())


@pytest.mark.slow
def test_condensed_frequency_response_is_the_full_one(monkeypatch):
    """Same peak to the solver's tolerance; every point solves the full balance."""
    s = chain()
    band = (0.9 * float(s.linear_frequencies(stuck=False)[0]),
            float(s.linear_frequencies(stuck=True)[0]) / 0.9)
    load = np.full(s.dofs, 10.0)
    a = response.frequency_response(s, 1.0, load, band, 5, 64)
    hb = HarmonicBalance(s, 5, 64)
    p = hb.excitation(load, 1.0)
    for x, f in zip(a.coefficients, a.frequency, strict=True):
        r = hb.residual(x, 2 * np.pi * f, p).r
        assert np.abs(r).max() < 1e-8 * np.abs(p).max()
    monkeypatch.setattr(response, "condensable", lambda hb: False)
    b = response.frequency_response(s, 1.0, load, band, 5, 64)
    assert a.success and b.success
    assert a.peak_amplitude == pytest.approx(b.peak_amplitude, rel=1e-9)
    assert a.peak_frequency == pytest.approx(b.peak_frequency, rel=1e-9)


def test_not_condensed_without_damping_or_when_no_smaller():
    s = chain()
    undamped = Structure(mass=s.mass, damping=0.0 * s.damping, stiffness=s.stiffness,
                         joints=s.joints, output=s.output)
    assert not condensable(HarmonicBalance(undamped, 3, 64))
    two = Structure(mass=s.mass[:2, :2], damping=s.damping[:2, :2],
                    stiffness=s.stiffness[:2, :2],
                    joints=(JointLink(TIP, np.array([1.0, 0.0])),
                            JointLink(TIP, np.array([1.0, -1.0]))),
                    output=np.array([1.0, 0.0]))
    assert not condensable(HarmonicBalance(two, 3, 64))
