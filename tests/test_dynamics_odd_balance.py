"""The harmonic balance built on the odd harmonics (``HarmonicBalance(..., odd=True)``): its
residual, Jacobian and AFT equal the full balance's restricted to the odd coefficients at
an input without even ones, and the full balance's even rows vanish there (half-wave
symmetry of odd joint forces). The full balance's compiled residual, which no longer forms
the Kronecker products, is checked against them formed."""

from __future__ import annotations

import numpy as np
import pytest

from microslip.dynamics import jenkins
from microslip.dynamics.hb import HarmonicBalance, harmonic_columns
from microslip.dynamics.modal import epmc, quasi_static
from microslip.dynamics.modal_odd import epmc_odd
from microslip.dynamics.operators2d import CircularIwan
from microslip.dynamics.response import frequency_response
from microslip.dynamics.structure import SI_PER_MM, JointLink, Structure

H, N = 5, 64


def chain(damped: bool = True) -> Structure:
    """Three masses in a chain (kg, N/m), a 1-D Jenkins element on DOF 0 (the compiled
    path), a circular Jenkins element between DOFs 1 and 2 in two directions (Python), and
    a damping matrix that is not proportional."""
    m = np.diag([1.0, 1.5, 0.8])
    k = 1e6 * np.array([[2.0, -1.0, 0.0], [-1.0, 2.0, -1.0], [0.0, -1.0, 1.2]])
    c = (np.array([[3.0, -1.0, 0.0], [-1.0, 2.0, 0.5], [0.0, 0.5, 1.0]]) if damped
         else np.zeros((3, 3)))
    planar = CircularIwan("j", np.array([300.0]), np.array([0.02]))
    w2 = np.zeros((3, 2))
    w2[1], w2[2] = (1.0, 0.3), (-1.0, 0.5)
    joints = (JointLink(jenkins(200.0, 0.01), np.array([1.0, 0.0, 0.0])),
              JointLink(planar, w2))
    return Structure(mass=m, damping=c, stiffness=k, joints=joints,
                     output=np.array([0.0, 0.0, 1.0]))


def odd_input(seed: int) -> np.ndarray:
    rng = np.random.default_rng(seed)
    return 0.05 * rng.standard_normal(3 * harmonic_columns(H, odd=True).size)


def test_columns_are_the_odd_harmonics_cos_and_sin():
    assert harmonic_columns(5, odd=True).tolist() == [1, 2, 5, 6, 9, 10]
    assert harmonic_columns(4, odd=True).tolist() == [1, 2, 5, 6]
    assert harmonic_columns(3).tolist() == list(range(7))
    hb = HarmonicBalance(chain(), H, N, odd=True)
    assert (hb.width, hb.first, hb.size) == (6, 0, 18)
    x = odd_input(0)
    full = hb.expand(x).reshape(3, 2 * H + 1)
    assert np.all(full[:, [0, 3, 4, 7, 8]] == 0.0)
    np.testing.assert_array_equal(hb.restrict(hb.expand(x)), x)


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_odd_balance_is_the_full_balance_restricted(seed):
    s = chain()
    full, odd = HarmonicBalance(s, H, N), HarmonicBalance(s, H, N, odd=True)
    keep = np.flatnonzero(np.isin(np.arange(full.size) % (2 * H + 1), odd.columns))
    x, w, xi = odd_input(seed), 2 * np.pi * 150.0, 3.0
    load_full = full.excitation(np.array([1.0, 0.5, -0.2]), 4.0)
    load = odd.excitation(np.array([1.0, 0.5, -0.2]), 4.0)
    np.testing.assert_array_equal(load, load_full[keep])
    rf = full.residual(odd.expand(x), w, load_full, xi)
    ro = odd.residual(x, w, load, xi)
    scale = np.max(np.abs(rf.r))
    assert scale > 1.0  # the joints slip: not a linear check
    np.testing.assert_allclose(ro.r, rf.r[keep], rtol=0, atol=1e-13 * scale)
    np.testing.assert_allclose(ro.dx, rf.dx[np.ix_(keep, keep)], rtol=0,
                               atol=1e-13 * np.max(np.abs(rf.dx)))
    np.testing.assert_allclose(ro.dw, rf.dw[keep], rtol=0, atol=1e-13 * np.max(np.abs(rf.dw)))
    np.testing.assert_allclose(ro.dxi, rf.dxi[keep], rtol=0,
                               atol=1e-13 * np.max(np.abs(rf.dxi)))
    # half-wave symmetry: the even harmonics of the full balance vanish on an odd input
    even = np.setdiff1d(np.arange(full.size), keep)
    assert np.max(np.abs(rf.r[even])) <= 1e-12 * scale
    np.testing.assert_allclose(odd.stuck_guess(w, load),
                               full.stuck_guess(w, load_full)[keep], rtol=1e-13, atol=0)
    assert odd.amplitude(x)[0] == pytest.approx(full.amplitude(odd.expand(x))[0], rel=1e-15)


def test_compiled_residual_is_the_formed_kronecker_balance():
    """The residual's linear part, summed blockwise in the kernel, against the matrices
    ``K kron I - w^2 M kron k^2 + w (C - xi M) kron d/dtheta`` formed (joints removed)."""
    s = chain()
    bare = Structure(mass=s.mass, damping=s.damping, stiffness=s.stiffness, joints=(),
                     output=s.output)
    for odd in (False, True):
        hb = HarmonicBalance(bare, H, N, odd=odd)
        cols = hb.columns
        order = (cols + 1) // 2
        dc = np.zeros((cols.size, cols.size))
        for a, col in enumerate(cols):
            if col > 0:
                b = a + 1 if col % 2 else a - 1
                dc[a, b] = order[a] if col % 2 else -order[a]
        w, xi = 900.0, 2.0
        lin = SI_PER_MM * (np.kron(s.stiffness, np.eye(cols.size))
                           - w**2 * np.kron(s.mass, np.diag(order**2.0))
                           + w * np.kron(s.damping - xi * s.mass, dc))
        x = np.random.default_rng(4).standard_normal(hb.size)
        load = hb.excitation(np.ones(3), 2.0)
        res = hb.residual(x, w, load, xi)
        np.testing.assert_allclose(res.dx, lin, rtol=1e-14, atol=1e-12)
        np.testing.assert_allclose(res.r, lin @ x - load, rtol=0,
                                   atol=1e-12 * np.max(np.abs(res.r)))


def test_odd_epmc_and_qsma_match_the_full_balance():
    s = chain()
    a = np.geomspace(5e-3, 5e-2, 4)
    full, odd = epmc(s, a, H, N, mode=0), epmc_odd(s, a, H, N, mode=0)
    assert odd.damping_ratio[-1] > 2 * odd.damping_ratio[0]  # the joints dissipate
    np.testing.assert_allclose(odd.frequency, full.frequency, rtol=1e-10)
    np.testing.assert_allclose(odd.damping_ratio, full.damping_ratio, rtol=1e-8)
    q = quasi_static(s, [50.0, 300.0], H, N)
    assert np.all(np.isfinite(q.damping_ratio)) and q.damping_ratio[-1] > 0.0


def test_odd_forced_response_is_the_full_one():
    s = chain(damped=False)  # not condensable: the balance on every coefficient
    shape = np.array([0.0, 0.0, 1.0])
    full = frequency_response(s, 3.0, shape, (120.0, 200.0), 3, 32)
    odd = frequency_response(s, 3.0, shape, (120.0, 200.0), 3, 32, odd=True)
    assert odd.coefficients.shape[1] == full.coefficients.shape[1] == 3 * 7
    assert full.success and odd.success
    assert odd.peak_frequency == pytest.approx(full.peak_frequency, rel=1e-9)
    assert odd.peak_amplitude == pytest.approx(full.peak_amplitude, rel=1e-9)
    even = odd.coefficients.reshape(len(odd.frequency), 3, 7)[:, :, [0, 3, 4]]
    assert np.all(even == 0.0)
