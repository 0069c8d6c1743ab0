"""Harmonics chosen by an error estimate (:mod:`microslip.dynamics.harmonics`): on one mass
with a Jenkins element the adaptive EPMC converges to the exact periodic orbit (closed form
per stick and slip phase) and its estimate bounds its true error; the ladder, the samples,
the warm start and the cap; fixed harmonics untouched."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.integrate import quad
from scipy.optimize import brentq

from microslip.dynamics import jenkins
from microslip.dynamics.harmonics import (
    DAMPING_FLOOR,
    HarmonicControl,
    adaptive_epmc,
    adaptive_quasi_static,
    adaptive_response,
    cap_warning,
    change,
    transfer,
)
from microslip.dynamics.hb import HarmonicBalance
from microslip.dynamics.modal import epmc, quasi_static
from microslip.dynamics.modal_odd import epmc_odd
from microslip.dynamics.response import frequency_response
from microslip.dynamics.structure import SI_PER_MM, one_mode
from microslip.errors import ParameterError

F0, MASS, KJ, FS = 100.0, 2.0, 800.0, 5.0  # Hz, kg, N/mm, N


@pytest.fixture(scope="module")
def mass_jenkins():
    return one_mode(F0, MASS, 0.0, jenkins(KJ, FS))


class _Phase:
    """``m q'' - xi m q' + kappa q = load`` (N, mm, s) from ``q0``, ``v0``: closed form."""

    def __init__(self, m: float, xi: float, kappa: float, load: float, q0: float,
                 v0: float) -> None:
        self.p = load / kappa
        self.al = xi / 2.0
        self.be = np.sqrt(kappa / m - self.al**2)
        self.a = q0 - self.p
        self.b = (v0 - self.al * self.a) / self.be

    def q(self, t: float) -> float:
        return float(self.p + np.exp(self.al * t) * (self.a * np.cos(self.be * t)
                                                     + self.b * np.sin(self.be * t)))

    def v(self, t: float) -> float:
        al, be, a, b = self.al, self.be, self.a, self.b
        return float(np.exp(al * t) * ((al * a + be * b) * np.cos(be * t)
                                       + (al * b - be * a) * np.sin(be * t)))

    def rest(self) -> float:
        """The first t > 0 with q'(t) = 0."""
        al, be, a, b = self.al, self.be, self.a, self.b
        t = float(np.arctan2(-(al * a + be * b), al * b - be * a)) % np.pi / be
        return t if t > 1e-12 / be else t + np.pi / be


def _exact_orbit(x_turn: float) -> tuple[float, float, float]:
    """The EPMC's exact periodic orbit of the mass with the Jenkins element at turning
    amplitude ``x_turn`` (mm; > FS / KJ: the element slips): its output's first-harmonic
    amplitude (mm), frequency (Hz) and damping ratio xi / (2 w).

    Half-wave symmetric: from rest at q = X (the slider just stopped, force +FS), the
    element sticks (stiffness K + KJ, force FS + KJ (q - X)) until q = X - 2 FS / KJ, then
    slips (force -FS) until rest, which must be at q = -X; xi is the negative damping that
    makes it so (each phase a linear ODE in closed form)."""
    m = MASS * SI_PER_MM
    k = MASS * (2 * np.pi * F0) ** 2 * SI_PER_MM

    def half(xi: float) -> tuple[_Phase, float, _Phase, float]:
        stick = _Phase(m, xi, k + KJ, KJ * x_turn - FS, x_turn, 0.0)
        level = x_turn - 2 * FS / KJ
        t1 = brentq(lambda t: stick.q(t) - level, 0.0, stick.rest(), xtol=1e-16, rtol=1e-15)
        slip = _Phase(m, xi, k, FS, stick.q(t1), stick.v(t1))
        return stick, t1, slip, slip.rest()

    def miss(xi: float) -> float:
        _, _, slip, t2 = half(xi)
        return slip.q(t2) + x_turn

    xi = brentq(miss, 0.0, 2 * np.pi * F0, xtol=1e-14, rtol=1e-15)
    stick, t1, slip, t2 = half(xi)
    period = 2 * (t1 + t2)
    w = 2 * np.pi / period

    def coeff(f):  # 4/T int_0^{T/2} q f(w t) dt: half-wave symmetry
        one = quad(lambda t: stick.q(t) * f(w * t), 0.0, t1, epsabs=1e-18, epsrel=1e-13)[0]
        two = quad(lambda t: slip.q(t) * f(w * (t + t1)), 0.0, t2, epsabs=1e-18,
                   epsrel=1e-13)[0]
        return 4.0 / period * (one + two)

    return float(np.hypot(coeff(np.cos), coeff(np.sin))), w / (2 * np.pi), xi / (2 * w)


def test_exact_orbit_at_first_harmonic_limit():
    """The reference itself: with the slip barely begun the orbit is the stuck linear one
    (w = the stuck frequency, zeta -> 0)."""
    a, f, z = _exact_orbit(FS / KJ * (1 + 1e-9))
    stuck = F0 * np.sqrt(1 + KJ / (MASS * (2 * np.pi * F0) ** 2 * SI_PER_MM))
    assert f == pytest.approx(stuck, rel=1e-8)
    assert abs(z) < 1e-7 and a == pytest.approx(FS / KJ, rel=1e-6)


@pytest.mark.parametrize("x_turn", [0.0075, 0.018, 0.04, 0.1])
def test_adaptive_epmc_converges_to_the_exact_orbit(mass_jenkins, x_turn):
    """Against the exact orbit: every accepted point is within the tolerance, and the
    estimate bounds the true error of the damping ratio and the frequency. The describing
    function (one harmonic) misses by more than the tolerance at the first two."""
    a, f, z = _exact_orbit(x_turn)
    for tol in (5e-3, 1e-3):
        c = adaptive_epmc(mass_jenkins, [a], HarmonicControl(tolerance=tol), odd=True)
        err = max(abs(c.damping_ratio[0] / z - 1), abs(c.frequency[0] / f - 1))
        est = float(c.harmonic_error_estimate[0])
        assert est < tol
        assert err <= est, (tol, err, est, int(c.point_harmonics[0]))
    one = epmc_odd(mass_jenkins, [a], 1)
    if x_turn < 0.1:
        assert abs(one.damping_ratio[0] / z - 1) > 5e-3


def test_the_ladder_samples_and_checks():
    c = HarmonicControl()
    assert c.ladder == (1, 3, 7, 15, 31, 63)
    assert [c.samples(h) for h in c.ladder] == [32, 64, 128, 256, 512, 1024]
    assert HarmonicControl(cap=15).ladder == (1, 3, 7, 15)
    for bad in ({"tolerance": 0.0}, {"tolerance": 0.5}, {"tolerance": float("nan")},
                {"cap": 8}, {"cap": 1}, {"cap": 511}, {"max_unknowns": 15}):
        with pytest.raises(ParameterError):
            HarmonicControl(**bad)  # type: ignore[arg-type]


def test_change_measures_damping_against_a_floor():
    assert change((100.0, 101.0), (0.02, 0.02)) == pytest.approx(1 / 101)
    assert change((100.0, 100.0), (0.0102, 0.01)) == pytest.approx(0.02)
    # a stuck structure without damping: rounding, not a change
    assert change((100.0, 100.0), (1e-18, -3e-18)) < 1e-9
    assert change((100.0, 100.0), (0.0, 2 * DAMPING_FLOOR)) == pytest.approx(1.0)


def test_transfer_keeps_the_series(mass_jenkins):
    """The warm start of a larger balance is the same periodic function (odd and full)."""
    rng = np.random.default_rng(1)
    for odd in (False, True):
        small = HarmonicBalance(mass_jenkins, 3, 64, odd=odd)
        large = HarmonicBalance(mass_jenkins, 7, 128, odd=odd)
        x = rng.normal(size=small.size)
        y = transfer(small, large, x)
        theta = np.linspace(0, 2 * np.pi, 17)
        def series(hb, x, theta=theta):
            full = hb.expand(x)
            k = np.arange(1, hb.harmonics + 1)
            return (full[0] + np.cos(np.outer(theta, k)) @ full[1::2]
                    + np.sin(np.outer(theta, k)) @ full[2::2])
        np.testing.assert_allclose(series(large, y), series(small, x), rtol=0, atol=1e-13)


def test_cap_is_reached_with_a_warning(mass_jenkins):
    """A tolerance the cap cannot meet: the points keep the cap's answer, their estimate
    above the tolerance, and the warning says so."""
    control = HarmonicControl(tolerance=1e-6, cap=7)
    c = adaptive_epmc(mass_jenkins, [0.02, 0.05], control, odd=True)
    assert list(c.point_harmonics) == [7, 7] and c.harmonics == 7 and c.samples == 128
    assert np.all(c.harmonic_error_estimate > 1e-6)
    text = cap_warning(c.harmonic_error_estimate, c.harmonics, control)
    assert text is not None and "reached 7 (the cap)" in text and "2 amplitude(s)" in text
    fixed = epmc_odd(mass_jenkins, [0.02, 0.05], 7)  # the cap's answer is the fixed one
    np.testing.assert_allclose(c.damping_ratio, fixed.damping_ratio, rtol=1e-9)
    assert cap_warning([1e-3, 2e-3], 63, HarmonicControl()) is None


def test_the_balance_size_caps_the_ladder(mass_jenkins):
    """A structure too large for a level stops below it (never below 3 harmonics); the
    warning names the size limit."""
    control = HarmonicControl(max_unknowns=16)
    assert control.levels(1, True) == (1, 3, 7, 15)  # 1 DOF x (H + 1) <= 16 (odd)
    assert control.levels(1, False) == (1, 3, 7)  # 1 DOF x (2H + 1) <= 16
    assert control.levels(100, True) == (1, 3)
    tight = HarmonicControl(1e-6, max_unknowns=16)
    c = adaptive_epmc(mass_jenkins, [0.02], tight)
    assert list(c.point_harmonics) == [7]
    text = cap_warning(c.harmonic_error_estimate, c.harmonics, tight)
    assert text is not None and "within 16 unknowns" in text


def test_stuck_points_stop_at_three_harmonics(mass_jenkins):
    """Below the slip amplitude the orbit is linear: 1 and 3 harmonics agree to rounding."""
    c = adaptive_epmc(mass_jenkins, [1e-3, 5e-3], odd=True)
    assert list(c.point_harmonics) == [3, 3]
    assert np.all(c.harmonic_error_estimate < 1e-9)


def test_full_and_odd_adaptive_agree(mass_jenkins):
    a = [0.02, 0.05]
    full, odd = adaptive_epmc(mass_jenkins, a), adaptive_epmc(mass_jenkins, a, odd=True)
    assert list(full.point_harmonics) == list(odd.point_harmonics)
    np.testing.assert_allclose(full.damping_ratio, odd.damping_ratio, rtol=1e-8)


def test_adaptive_quasi_static_settles(mass_jenkins):
    """QSMA with harmonics chosen: each point's answer within its estimate of a far finer
    fixed balance (63 harmonics, 2048 samples), the estimate under the tolerance."""
    q = np.array([300.0, 1000.0, 3000.0])
    c = adaptive_quasi_static(mass_jenkins, q)
    ref = quasi_static(mass_jenkins, q, 63, 2048)
    assert np.all(c.harmonic_error_estimate < 5e-3)
    err = np.maximum(np.abs(c.damping_ratio / ref.damping_ratio - 1),
                     np.abs(c.frequency / ref.frequency - 1))
    assert np.all(err <= c.harmonic_error_estimate + 2e-4)


def test_adaptive_response_per_curve(mass_jenkins):
    """The forced response with harmonics chosen per curve: the accepted curve is the fixed
    balance's at its harmonics and samples; the estimate is the change of the peak from the
    level below."""
    shape = np.ones(1)
    r = adaptive_response(mass_jenkins, 3.0, shape, (110.0, 150.0))
    h = r.response.harmonics
    assert r.levels[-1] == h and len(r.levels) >= 2 and r.harmonic_error_estimate < 5e-3
    fixed = frequency_response(mass_jenkins, 3.0, shape, (110.0, 150.0), h,
                               HarmonicControl.samples(h))
    assert r.response.peak_amplitude == fixed.peak_amplitude
    lower = frequency_response(mass_jenkins, 3.0, shape, (110.0, 150.0), r.levels[-2],
                               HarmonicControl.samples(r.levels[-2]))
    assert r.harmonic_error_estimate == change(
        (lower.peak_frequency, fixed.peak_frequency), (lower.peak_amplitude,
                                                       fixed.peak_amplitude))


def test_fixed_harmonics_report_no_estimate(mass_jenkins):
    c = epmc(mass_jenkins, [0.02], 7)
    assert c.point_harmonics is None and c.harmonic_error_estimate is None


def test_a_level_that_does_not_converge_keeps_the_one_below(mass_jenkins, monkeypatch):
    """If the next level's balance does not converge, the point keeps the level below's
    answer with a NaN estimate, and the warning says so."""
    import microslip.dynamics.harmonics as hm

    solve = hm.epmc_point

    def failing(hb, a, guess, omega0):
        if hb.harmonics >= 15:
            raise ParameterError("did not converge")
        return solve(hb, a, guess, omega0)

    monkeypatch.setattr(hm, "epmc_point", failing)
    control = HarmonicControl(tolerance=1e-7)
    c = adaptive_epmc(mass_jenkins, [0.02, 0.03], control, odd=True)
    assert list(c.point_harmonics) == [7, 7] and np.all(np.isnan(c.harmonic_error_estimate))
    fixed = epmc_odd(mass_jenkins, [0.02, 0.03], 7)
    np.testing.assert_allclose(c.damping_ratio, fixed.damping_ratio, rtol=1e-9)
    text = cap_warning(c.harmonic_error_estimate, c.harmonics, control)
    assert text is not None and "2 amplitude(s) the next level of harmonics did not" in text
