"""Convergence in the increment size, and the paper-literal reading pinned at 50 increments."""

from __future__ import annotations

import numpy as np
import pytest

from microslip import ModelOptions, damping, first_loading, preset
from microslip import closedform as cf

TIP = preset("table2-tip")
CENTRE = preset("table2-centre")


def slope(ns, errors) -> float:
    return float(np.polyfit(np.log(ns), np.log(errors), 1)[0])


def test_corrected_tip_converges_250_vs_4000_increments():
    coarse = damping("tip", TIP, 8000.0, 250)
    fine = damping("tip", TIP, 8000.0, 4000)
    assert abs(coarse.peak_displacement / fine.peak_displacement - 1) < 0.005
    assert abs(coarse.loss_factor / fine.loss_factor - 1) < 0.005


def test_paper_literal_tip_does_not_converge():
    """Eqs 6-7 with the total force at each increment: the section shrinks once per increment."""
    lit = ModelOptions(poisson="paper-literal")
    coarse = damping("tip", TIP, 8000.0, 250, lit)
    fine = damping("tip", TIP, 8000.0, 1000, lit)
    assert fine.peak_displacement / coarse.peak_displacement - 1 > 0.10


@pytest.mark.parametrize(("model", "params", "amp"), [("tip", TIP, 8000.0),
                                                      ("centre", CENTRE, 12000.0)])
def test_backward_difference_is_first_order(model, params, amp):
    """Peak displacement error against a 64 000-increment reference falls as h^1."""
    ref = first_loading(model, params, amp, 64000).peak_displacement
    ns = [25, 50, 100, 200, 400]
    err = [abs(first_loading(model, params, amp, n).peak_displacement / ref - 1) for n in ns]
    assert slope(ns, err) == pytest.approx(-1.0, abs=0.1)


def test_loop_area_is_second_order_without_corrections():
    """Trapezoidal loop area on the exact quadratic backbone: error exactly W/n^2."""
    ea, q = TIP.axial_stiffness, TIP.friction_per_length
    exact = cf.tip_dissipated_energy(8000.0, ea, q)
    ns = [10, 20, 40, 80, 160]
    err = [abs(damping("tip", TIP, 8000.0, n, ModelOptions.uncorrected()).dissipated_energy
               / exact - 1) for n in ns]
    assert slope(ns, err) == pytest.approx(-2.0, abs=0.01)


def _tip_paper_literal_by_hand(p, f0: float, n: int) -> float:
    """Eqs 4, 6, 7, 9, 10 written out once more in plain Python, literally as printed."""
    w, t, delta = p.width, p.thickness, 0.0
    for i in range(1, n + 1):
        f = f0 * i / n
        u = f * (p.length + delta) / (p.normal_force * p.friction)  # Eq. 4
        w, t = (w - p.poisson_ratio * w * f / (p.modulus * w * t),  # Eq. 6
                t - p.poisson_ratio * t * f / (p.modulus * w * t))  # Eq. 7
        k = w * t * 2 * p.modulus / u  # Eq. 9
        delta = f / k  # Eq. 10
    return delta


def _centre_paper_literal_by_hand(p, f0: float, n: int) -> float:
    """Eqs 11-18 as printed (factor 4, Eq. 15's + sign, full F per domain in Eq. 17)."""
    nu, dt, dc, ut, uc = p.poisson_ratio, 0.0, 0.0, 0.0, 0.0
    delta = 0.0
    for i in range(1, n + 1):
        f = f0 * i / n
        et, ec = (dt / ut if ut else 0.0), (dc / uc if uc else 0.0)
        wc, tc = p.width * (1 + nu * ec), p.thickness * (1 + nu * ec)  # Eqs 12-13
        wt, tt = p.width * (1 - nu * et), p.thickness * (1 + nu * et)  # Eqs 14-15
        ut = f * (p.length + dt) / (4 * p.normal_force * p.friction)  # Eq. 11
        uc = f * (p.length + dc) / (4 * p.normal_force * p.friction)
        kt, kc = wt * tt * 2 * p.modulus / ut, wc * tc * 2 * p.modulus / uc  # Eq. 16
        dt, dc = f / kt, f / kc  # Eq. 17
        delta = (kc * dc + kt * dt) / (kc + kt)  # Eq. 18
    return delta


def test_paper_literal_tip_pinned_at_50_increments():
    b = first_loading("tip", TIP, 8000.0, 50, ModelOptions.paper())
    assert b.peak_displacement == pytest.approx(_tip_paper_literal_by_hand(TIP, 8000.0, 50),
                                                rel=1e-12)
    # 0.042092 mm: 4.9 % above the convergent reading (0.040108 mm) and 5.2 % above the
    # uncorrected F0^2/(2EAq) = 0.04 mm. The literal Poisson update applies nu F_i/(E A) once per
    # increment: with F_i = 8000 i/50 N its sum is nu F0 (n+1)/(2 E A) = 2.45 % per side.
    assert b.peak_displacement == pytest.approx(0.0420924, rel=1e-6)
    assert b.peak_displacement / 0.04 - 1 == pytest.approx(0.0523, abs=0.0005)


def test_paper_literal_centre_pinned_at_50_increments():
    b = first_loading("centre", CENTRE, 16000.0, 50, ModelOptions.paper())
    assert b.peak_displacement == pytest.approx(
        _centre_paper_literal_by_hand(CENTRE, 16000.0, 50), rel=1e-12)
    ea, q = CENTRE.axial_stiffness, CENTRE.friction_per_length
    # Eqs 12-15 use the mean strain delta/u of the previous increment, which does not
    # accumulate: the result stays within 1 % of the uncorrected F0^2/(8 E A q) = 0.02 mm.
    assert cf.centre_displacement(16000.0, ea, q) == pytest.approx(0.02)
    assert b.peak_displacement == pytest.approx(0.02, rel=0.01)
