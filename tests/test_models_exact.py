"""The 1-D models against the exact rigid-foundation results (shared/REFERENCES.md)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from microslip import (
    STRAIN_ENERGY,
    MacroslipError,
    ModelOptions,
    ParameterError,
    damping,
    first_loading,
    macroslip_force,
    masing_loop,
    preset,
)
from microslip import closedform as cf

P1 = preset("table1")
EA, Q = P1.axial_stiffness, P1.friction_per_length
F0 = 267.0
OFF = ModelOptions.uncorrected()


def rel(a: float, b: float) -> float:
    return abs(a - b) / abs(b)


@pytest.mark.parametrize(
    ("model", "d_exact", "w_exact", "tol_d", "tol_w"),
    [
        ("tip", cf.tip_displacement, cf.tip_dissipated_energy, 0.002, 0.005),
        ("centre", cf.centre_displacement, cf.centre_dissipated_energy, 0.005, 0.01),
    ],
)
def test_table1_uncorrected_matches_closed_form(model, d_exact, w_exact, tol_d, tol_w):
    r = damping(model, P1, F0, 2000, OFF)
    # The acceptance tolerances ...
    assert rel(r.peak_displacement, d_exact(F0, EA, Q)) < tol_d
    assert rel(r.dissipated_energy, w_exact(F0, EA, Q)) < tol_w
    # ... and what the algebra promises: the backbone is exact at any increment size and the
    # trapezoidal loop area is off by exactly 1/n^2 of W_d for a quadratic virgin curve.
    assert rel(r.peak_displacement, d_exact(F0, EA, Q)) < 1e-12
    assert rel(r.dissipated_energy, w_exact(F0, EA, Q) * (1 - 1 / 2000**2)) < 1e-9


def test_tip_backbone_and_slip_length_exact_at_every_increment():
    b = first_loading("tip", P1, F0, 37, OFF)
    np.testing.assert_allclose(b.displacement, cf.tip_displacement(b.force, EA, Q), rtol=1e-13)
    np.testing.assert_allclose(b.slip_length[:, 0], cf.tip_slip_length(b.force, Q), rtol=1e-13)
    np.testing.assert_allclose(b.stored_energy[-1], cf.tip_stored_energy(F0, EA, Q), rtol=1e-13)


def test_tip_unloading_branch_is_goodman_klumpp():
    loop = masing_loop(first_loading("tip", P1, F0, 40, OFF))
    down = slice(0, 41)  # the descending branch comes first
    np.testing.assert_allclose(
        loop.displacement[down],
        cf.tip_unloading_displacement(loop.force[down], F0, EA, Q),
        rtol=1e-12, atol=1e-18,
    )


@pytest.mark.parametrize("reading", ["physical", "paper"])
def test_centre_displacement_exact_in_both_readings(reading):
    b = first_loading("centre", P1, F0, 25, ModelOptions(poisson="off", length_update=False,
                                                         centre=reading))
    np.testing.assert_allclose(b.displacement, cf.centre_displacement(b.force, EA, Q), rtol=1e-13)
    np.testing.assert_allclose(b.stored_energy[-1], cf.centre_stored_energy(F0, EA, Q),
                               rtol=1e-13)


def test_centre_slip_length_physical_is_exact_paper_reading_is_half():
    opts = dict(poisson="off", length_update=False)
    phys = first_loading("centre", P1, F0, 10, ModelOptions(**opts, centre="physical"))
    paper = first_loading("centre", P1, F0, 10, ModelOptions(**opts, centre="paper"))
    exact = cf.centre_slip_length(phys.force, Q)
    np.testing.assert_allclose(phys.slip_length, np.c_[exact, exact], rtol=1e-13)
    np.testing.assert_allclose(paper.slip_length, 0.5 * phys.slip_length, rtol=1e-13)


@pytest.mark.parametrize("model", ["tip", "centre"])
@pytest.mark.parametrize("kind", list(STRAIN_ENERGY))
def test_loss_factor_of_quadratic_backbone(model, kind):
    r = damping(model, P1, F0, 2000, OFF, kind)
    assert rel(r.loss_factor, cf.LOSS_FACTOR_QUADRATIC[kind]) < 1e-5


@pytest.mark.parametrize("model", ["tip", "centre"])
@pytest.mark.parametrize("n", [1, 2, 7, 2000])
def test_secant_loss_factor_is_4_over_3pi(model, n):
    """Parabolic virgin curve, trapezoidal loop of n increments: W_d = 4 F0 d0 (1 - 1/n^2) / 3
    exactly, so eta = 4/(3 pi) (1 - 1/n^2) to rounding (2.5e-7 below 4/(3 pi) at n = 2000)."""
    r = damping(model, P1, F0, n, OFF, "secant")
    exact = 4 / (3 * math.pi) * (1 - 1 / n**2)
    if n == 1:
        assert r.loss_factor == 0.0
    else:
        assert rel(r.loss_factor, exact) < 2e-14


def test_masing_energy_identity():
    """W_d = 4 F0 d0 - 8 integral g dF, with the integral by the same trapezoidal rule."""
    b = first_loading("tip", preset("table2-tip"), 6000.0, 300)
    r = damping("tip", preset("table2-tip"), 6000.0, 300)
    integral = float(np.sum(0.5 * (b.displacement[1:] + b.displacement[:-1]) * np.diff(b.force)))
    w = cf.masing_dissipation(b.amplitude, b.peak_displacement, integral)
    assert rel(r.dissipated_energy, w) < 1e-12


class TestMacroslip:
    def test_limits(self):
        assert macroslip_force("tip", P1) == pytest.approx(0.8 * 445)
        assert macroslip_force("centre", P1) == pytest.approx(0.8 * 445)
        assert macroslip_force("centre", P1, ModelOptions(centre="paper")) == pytest.approx(712)

    @pytest.mark.parametrize("model", ["tip", "centre"])
    def test_at_limit_is_an_error_not_nan(self, model):
        with pytest.raises(MacroslipError, match="macroslip"):
            first_loading(model, P1, 356.0, 10)

    def test_paper_reading_of_centre_reaches_past_mu_fn(self):
        b = first_loading("centre", P1, 500.0, 10, ModelOptions(centre="paper"))
        assert np.isfinite(b.peak_displacement)
        with pytest.raises(MacroslipError):
            first_loading("centre", P1, 712.0, 10, ModelOptions(centre="paper"))

    def test_tip_slip_length_reaches_length_exactly_at_eq5(self):
        b = first_loading("tip", P1, 355.9, 50, ModelOptions())
        length = P1.length + b.displacement[-2]
        assert b.slip_length[-1, 0] / length == pytest.approx(355.9 / 356.0, rel=1e-12)


@pytest.mark.parametrize(
    "kwargs",
    [dict(increments=0), dict(increments=2.5), dict(amplitude=-1.0), dict(amplitude=float("nan")),
     dict(model="edge")],
)
def test_bad_arguments_raise_parameter_error(kwargs):
    args = dict(model="tip", params=P1, amplitude=100.0, increments=10) | kwargs
    with pytest.raises(ParameterError):
        first_loading(**args)
