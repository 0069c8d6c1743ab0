"""The planar model: trajectories and levels, the paper's coupling (Eqs 19-23), work-based energy.

Exact references first (eccentricities, level mapping, closed forms in the rigid-foundation
limit), then the work-based identities, then invariants for random cases (hypothesis).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from microslip import (
    MacroslipError,
    ModelOptions,
    ParameterError,
    damping,
    first_loading,
    masing_loop,
    planar,
    preset,
)
from microslip import closedform as cf
from microslip.planar import (
    PAPER_RATIOS,
    ComponentEnergy,
    LoadPath,
    analytical_response,
    eccentricity,
    paper_levels,
    planar_damping,
)

TIP, CENTRE = preset("table2-tip"), preset("table2-centre")
UNCORRECTED = ModelOptions(poisson="off", length_update=False, centre="paper")
READ = ModelOptions(centre="paper")  # the reading of the reproduction


# -- trajectories, eccentricity, levels ------------------------------------------------------
def test_eccentricities_are_the_papers():
    # Fig. 1 prints 0, 0.86, 0.94, 0.97 (sqrt(3)/2 = 0.866 is printed truncated).
    printed = {1.0: 0.0, 2.0: 0.86, 3.0: 0.94, 4.0: 0.97}
    for r, e in printed.items():
        assert abs(eccentricity(r) - e) < 0.01
        assert eccentricity(1.0 / r) == pytest.approx(eccentricity(r), rel=1e-15)
    assert eccentricity(2.0) == pytest.approx(math.sqrt(3.0) / 2.0, rel=1e-15)
    assert eccentricity(3.0) == pytest.approx(math.sqrt(8.0) / 3.0, rel=1e-15)
    assert eccentricity(4.0) == pytest.approx(math.sqrt(15.0) / 4.0, rel=1e-15)


@pytest.mark.parametrize("r", PAPER_RATIOS)
def test_ratio_from_eccentricity_inverts(r):
    major = "tip" if r >= 1 else "centre"
    assert planar.ratio_from_eccentricity(eccentricity(r), major) == pytest.approx(r, rel=1e-12)


def test_paper_levels_base_and_top():
    base = {r: paper_levels(r) for r in PAPER_RATIOS}
    assert base[1.0] == (2000.0, 4000.0)
    assert base[4.0] == (8000.0, 4000.0)
    assert base[0.25] == (2000.0, 16000.0)
    # every paper amplitude (Section 5) is used, each model's four levels once
    tips = sorted({a for a, _ in base.values()})
    centres = sorted({c for _, c in base.values()})
    assert tips == [2000.0, 4000.0, 6000.0, 8000.0]
    assert centres == [4000.0, 8000.0, 12000.0, 16000.0]
    top = [planar.paper_level_pair(r, "top") for r in PAPER_RATIOS]
    assert top == [(4, 4), (4, 2), (3, 1), (4, 1), (2, 4), (1, 3), (1, 4)]
    for r in PAPER_RATIOS:  # R is the ratio of normalised forces, and of the total forces
        for scheme in planar.LEVEL_SCHEMES:
            at, ac = paper_levels(r, scheme)
            assert planar.force_ratio(at, ac) == pytest.approx(r, rel=1e-12)


def test_bad_ratios_and_schemes_are_one_line_errors():
    with pytest.raises(ParameterError, match="not a ratio of two whole levels"):
        paper_levels(1.7, "top")
    with pytest.raises(ParameterError, match="unknown level scheme"):
        paper_levels(1.0, "middle")
    with pytest.raises(ParameterError, match="R must be finite and > 0"):
        eccentricity(-1.0)
    with pytest.raises(ParameterError, match=r"eccentricity must be in \[0, 1\)"):
        planar.ratio_from_eccentricity(1.0)


def test_trajectory_is_the_ellipse_at_90_degrees_and_a_line_at_0():
    t = planar.trajectory(3.0, phase_deg=90.0, samples=721)
    # (x / 3)^2 + (y / 1)^2 = 1 on the ellipse with semi-axes the levels
    np.testing.assert_allclose((t.tip / 3.0) ** 2 + t.centre**2, 1.0, rtol=1e-12)
    line = planar.trajectory(3.0, phase_deg=0.0)
    np.testing.assert_allclose(line.tip, 3.0 * line.centre, rtol=1e-12, atol=1e-12)


# -- the paper's coupling ---------------------------------------------------------------------
def test_quadratic_backbones_give_the_same_eta_at_every_ratio():
    """Corrections off: each loop is quadratic, the resultant a scaled copy, eta constant."""
    sweep = planar.loss_factor_vs_ratio(PAPER_RATIOS, increments=400, options=UNCORRECTED,
                                        samples_per_cycle=256)
    assert all(c.result is not None for c in sweep.cases)
    for kind in ("branch", "secant", "backbone"):
        eta = sweep.loss_factor("paper", kind)
        one_d = sweep.cases[0].result.tip  # same n, same shape
        ref = damping("tip", TIP, 2000.0, 400, UNCORRECTED, kind).loss_factor
        np.testing.assert_allclose(eta, ref, rtol=1e-12)
        assert one_d.strain_energy_kind == "secant"  # the one default of loop, planar, sweep
    np.testing.assert_allclose(sweep.normalised_loss_factor("paper"), 1.0, rtol=1e-12)
    # and the quadratic-curve values, to the discretisation error W_d/n^2 of the loop
    assert sweep.loss_factor("paper", "secant")[0] == pytest.approx(4 / (3 * math.pi), rel=1e-5)
    assert sweep.loss_factor("paper", "branch")[0] == pytest.approx(4 / (5 * math.pi), rel=1e-4)


def test_resultant_loop_matches_the_closed_forms():
    at, ac = 6000.0, 4000.0
    n = 2000
    t = first_loading("tip", TIP, at, n, UNCORRECTED)
    c = first_loading("centre", CENTRE, ac, n, UNCORRECTED)
    r = planar.paper_coupling(t, c, "secant")
    dt = cf.tip_displacement(at, TIP.axial_stiffness, TIP.friction_per_length)
    dc = cf.centre_displacement(ac, CENTRE.axial_stiffness, CENTRE.friction_per_length)
    assert r.amplitude == pytest.approx(math.hypot(at, ac), rel=1e-14)
    assert r.peak_displacement == pytest.approx(math.hypot(dt, dc), rel=1e-12)
    # a scaled copy of the tip loop: W_r = W_t (F_r0 / F_t0) (d_r0 / d_t0)
    wt = cf.tip_dissipated_energy(at, TIP.axial_stiffness, TIP.friction_per_length)
    w_exact = wt * (math.hypot(at, ac) / at) * (math.hypot(dt, dc) / dt)
    assert r.dissipated_energy == pytest.approx(w_exact, rel=2e-6)  # trapezoid: W/n^2
    loop = r.loop
    assert loop.force[0] == loop.force[-1] and loop.displacement[0] == loop.displacement[-1]


def test_resultant_follows_eqs_19_20_point_by_point():
    t = first_loading("tip", TIP, 8000.0, 100, READ)
    c = first_loading("centre", CENTRE, 16000.0, 100, READ)
    lt, lc = masing_loop(t), masing_loop(c)
    r = planar.resultant_loop(lt, lc)
    np.testing.assert_allclose(np.abs(r.force), np.hypot(lt.force, lc.force), rtol=1e-15)
    np.testing.assert_allclose(np.abs(r.displacement), np.hypot(lt.displacement,
                                                                lc.displacement), rtol=1e-15)
    nz = lt.displacement != 0
    assert np.all(np.sign(r.displacement[nz]) == np.sign(lt.displacement[nz]))


def test_coupling_refuses_loops_at_different_load_fractions():
    t = first_loading("tip", TIP, 2000.0, 100, READ)
    c = first_loading("centre", CENTRE, 4000.0, 120, READ)
    with pytest.raises(ParameterError, match="same number of points"):
        planar.paper_coupling(t, c)


# -- the work of the load ---------------------------------------------------------------------
@pytest.mark.parametrize("phase", [0.0, 45.0, 90.0])
def test_work_is_the_sum_of_the_component_loops_at_any_phase(phase):
    r = planar_damping(TIP, CENTRE, 6000.0, 8000.0, increments=1000, options=READ,
                       phase_deg=phase)
    w_sum = 2 * r.tip.dissipated_energy + r.centre.dissipated_energy  # two tip halves
    assert r.work_dissipated_energy == pytest.approx(w_sum, rel=1e-5)
    assert r.work.tip_dissipated_energy == pytest.approx(2 * r.tip.dissipated_energy, rel=1e-5)
    assert r.work.centre_dissipated_energy == pytest.approx(r.centre.dissipated_energy,
                                                            rel=1e-5)
    assert r.work.closure_error < 1e-12
    one = planar_damping(TIP, CENTRE, 6000.0, 8000.0, increments=1000, options=READ,
                         phase_deg=phase, tip_symmetry=1)
    assert one.work_dissipated_energy == pytest.approx(
        one.tip.dissipated_energy + one.centre.dissipated_energy, rel=1e-5)


@pytest.mark.parametrize("phase", [0.0, 45.0, 90.0])
def test_work_matches_the_closed_forms(phase):
    at, ac = 8000.0, 12000.0
    r = planar_damping(TIP, CENTRE, at, ac, increments=1000, options=UNCORRECTED,
                       phase_deg=phase)
    exact = (2 * cf.tip_dissipated_energy(at, TIP.axial_stiffness, TIP.friction_per_length)
             + cf.centre_dissipated_energy(ac, CENTRE.axial_stiffness,
                                           CENTRE.friction_per_length))
    assert r.work_dissipated_energy == pytest.approx(exact, rel=1e-5)


def test_strain_energy_of_the_combined_motion():
    at, ac = 8000.0, 12000.0
    kw = {"increments": 1000, "options": UNCORRECTED, "strain_energy": "secant"}
    zero = planar_damping(TIP, CENTRE, at, ac, work_energy="peak", **kw)
    u_t, u_c = 2 * zero.tip.strain_energy, zero.centre.strain_energy
    # at zero phase both combinations are U_tip(A_t) + U_centre(A_c)
    assert zero.work_strain_energy == pytest.approx(u_t + u_c, rel=1e-12)
    summed = planar_damping(TIP, CENTRE, at, ac, phase_deg=90.0, work_energy="sum", **kw)
    assert summed.work_strain_energy == pytest.approx(u_t + u_c, rel=1e-12)
    # at 90 degrees and U ~ F^3: max of a|sin|^3 + b|cos|^3 is max(a, b)
    peak = planar_damping(TIP, CENTRE, at, ac, phase_deg=90.0, work_energy="peak", **kw)
    assert peak.work_strain_energy == pytest.approx(max(u_t, u_c), rel=1e-9)
    assert peak.work_loss_factor > summed.work_loss_factor


def test_component_energy_between_tabulated_amplitudes():
    bb = first_loading("tip", TIP, 8000.0, 1000, READ)
    for kind in ("branch", "secant", "backbone", "stored"):
        u = ComponentEnergy(bb, kind, copies=2)
        assert float(u(16000.0)) == pytest.approx(
            2 * damping("tip", TIP, 8000.0, 1000, READ, kind).strain_energy, rel=1e-12)
        # 5123 N is between table points; the direct model run to it has its own increments
        direct = damping("tip", TIP, 5123.0, 640, READ, kind).strain_energy
        assert float(u(2 * 5123.0)) == pytest.approx(2 * direct, rel=1e-5)
    with pytest.raises(ParameterError, match="beyond the component's backbone"):
        ComponentEnergy(bb, "secant", copies=2)(17000.0)


def test_load_path_validation():
    th = np.linspace(0.0, 2 * np.pi, 9)
    with pytest.raises(ParameterError, match="does not close"):
        LoadPath(th, np.linspace(0.0, 1.0, 9), np.zeros(9))
    with pytest.raises(ParameterError, match="equal length"):
        LoadPath(th, np.zeros(8), np.zeros(9))
    with pytest.raises(ParameterError, match="non-decreasing"):
        LoadPath(th[::-1], np.zeros(9), np.zeros(9))
    with pytest.raises(ParameterError, match="samples_per_cycle"):
        LoadPath.harmonic(1.0, 1.0, samples_per_cycle=4)
    p = LoadPath.harmonic(100.0, 50.0, 30.0, samples_per_cycle=64)
    assert p.tip_force.flags.writeable is False


def test_an_arbitrary_sampled_path_is_accepted():
    """Two harmonics and a triangle wave: any closed sampled history works."""
    theta = np.linspace(0.0, 4 * np.pi, 4001)
    ft = 3000.0 * np.sin(theta) + 1000.0 * np.sin(3 * theta)
    fc = 8000.0 * (2 / np.pi) * np.arcsin(np.sin(theta + 100 * (theta[1] - theta[0])))
    ft[-1], fc[-1] = ft[2000], fc[2000]
    path = LoadPath(theta, ft, fc, cycle_start=2000)
    t = first_loading("tip", TIP, 4000.0 / 2, 500, READ)
    c = first_loading("centre", CENTRE, 8000.0, 500, READ)
    resp = analytical_response(path, t, c, tip_symmetry=2)
    w = planar.work_damping(resp, ComponentEnergy(t, "secant", 2), ComponentEnergy(c, "secant"))
    assert w.dissipated_energy > 0.0 and w.closure_error < 1e-9
    # the triangle wave has the centre loop's full amplitude: same work as its Masing loop
    wc = damping("centre", CENTRE, 8000.0, 500, READ).dissipated_energy
    assert w.centre_dissipated_energy == pytest.approx(wc, rel=1e-5)


# -- sweep and contract -----------------------------------------------------------------------
def test_sweep_records_cases_the_reading_cannot_compute():
    s = planar.loss_factor_vs_ratio((1.0, 0.25), increments=100, options=ModelOptions(),
                                    samples_per_cycle=128)
    assert s.cases[0].result is not None and s.cases[1].result is None
    assert "macroslip limit of the centre model (16000 N" in s.cases[1].error
    assert math.isnan(s.loss_factor()[1]) and s.normalised_loss_factor()[0] == 1.0
    with pytest.raises(MacroslipError):
        planar.loss_factor_vs_ratio((0.25,), increments=100, options=ModelOptions(),
                                    skip_errors=False)


def test_contract_of_planar_damping():
    r = planar_damping(TIP, CENTRE, 4000.0, 4000.0, increments=200, options=READ,
                       samples_per_cycle=256)
    assert (r.ratio, round(r.eccentricity, 6)) == (2.0, round(math.sqrt(3) / 2, 6))
    for name in ("tip", "centre", "paper"):
        assert getattr(r, name).loss_factor > 0
    assert r.phase_deg == 0.0 and r.strain_energy_kind == "secant"
    # the work of the load on decoupled bars: tip_symmetry tip loops plus one centre loop.
    # U adds exactly; W is the loop work of 256 samples of the cycle against the Masing loop
    # of the 200-increment backbones (they differ by 7.5e-5)
    k = r.tip_symmetry
    w = k * r.tip.dissipated_energy + r.centre.dissipated_energy
    u = k * r.tip.strain_energy + r.centre.strain_energy
    assert r.work_strain_energy == pytest.approx(u, rel=1e-14)
    assert r.work_dissipated_energy == pytest.approx(w, rel=2e-4)
    assert r.work_loss_factor == pytest.approx(w / (2 * math.pi * u), rel=2e-4)
    # centre_options defaults to options: the physical reading cannot reach 16000 N
    with pytest.raises(MacroslipError):
        planar_damping(TIP, CENTRE, 2000.0, 16000.0, increments=50, options=ModelOptions())
    ok = planar_damping(TIP, CENTRE, 2000.0, 16000.0, increments=50, options=ModelOptions(),
                        centre_options=READ, samples_per_cycle=64)
    assert ok.centre.backbone.options.centre == "paper"
    s = r.summary()
    for key in ("dissipated_energy_Nmm", "paper_loss_factor", "work_loss_factor", "ratio",
                "eccentricity", "tip_share_of_dissipation", "centre_share_of_dissipation"):
        assert math.isfinite(s[key])
    assert s["tip_share_of_dissipation"] + s["centre_share_of_dissipation"] == pytest.approx(1)


# -- invariants --------------------------------------------------------------------------------
@settings(max_examples=25, deadline=None)
@given(st.floats(0.02, 0.9), st.floats(0.02, 0.9), st.floats(-180.0, 180.0),
       st.booleans(), st.sampled_from(["branch", "secant", "backbone", "stored"]))
def test_invariants(ft, fc, phase, corrections, kind):
    opt = READ if corrections else UNCORRECTED
    at, ac = ft * TIP.macroslip_force, fc * 2 * CENTRE.macroslip_force
    r = planar_damping(TIP, CENTRE, at, ac, increments=60, options=opt, strain_energy=kind,
                       phase_deg=phase, samples_per_cycle=256)
    loop = r.paper.loop
    assert loop.force[0] == loop.force[-1] and loop.displacement[0] == loop.displacement[-1]
    m = (loop.force.size - 1) // 2  # point symmetry: descending half = -(ascending half)
    np.testing.assert_allclose(loop.force[: m + 1], -loop.force[m:],
                               atol=1e-9 * r.paper.amplitude)
    np.testing.assert_allclose(loop.displacement[: m + 1], -loop.displacement[m:],
                               atol=1e-9 * r.paper.peak_displacement)
    assert r.paper.dissipated_energy > 0.0 and r.work_dissipated_energy > 0.0
    assert 0.0 < r.paper_loss_factors["secant"] <= 4.0 / math.pi
    assert 0.0 < r.work_loss_factors["secant"] <= 4.0 / math.pi
    w_sum = 2 * r.tip.dissipated_energy + r.centre.dissipated_energy
    assert r.work_dissipated_energy == pytest.approx(w_sum, rel=1e-3)
