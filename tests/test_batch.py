"""Batch engine: exact references, agreement with the single-loop API, backends, validation."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from microslip import (
    ClampParams,
    MacroslipError,
    ModelOptions,
    ParameterError,
    closedform,
    damping,
    damping_from_loop,
    first_loading,
    macroslip_force,
    masing_loop,
    preset,
)
from microslip.batch import batch_damping
from microslip.models import batch_kernels

KINDS = ("secant", "backbone", "branch", "stored")
OPTIONS = (
    ModelOptions(),
    ModelOptions.uncorrected(),
    ModelOptions.paper(),
    ModelOptions(poisson="paper-literal"),
    ModelOptions(centre="paper"),
    ModelOptions(poisson="off", length_update=True),
    ModelOptions(poisson="consistent", length_update=False, centre="paper"),
)


def random_params(rng: np.random.Generator, size: int) -> dict[str, np.ndarray]:
    """Random clamped zones; the section is thick enough for paper-literal at n <= 333."""
    return {
        "length": rng.uniform(10.0, 300.0, size),
        "width": rng.uniform(5.0, 30.0, size),
        "thickness": rng.uniform(5.0, 50.0, size),
        "modulus": rng.uniform(5e3, 2.1e5, size),
        "poisson_ratio": rng.uniform(0.0, 0.49, size),
        "friction": rng.uniform(0.1, 1.2, size),
        "normal_force": rng.uniform(100.0, 3e4, size),
    }


def close(a: float, b: float, scale: float, rtol: float) -> bool:
    return abs(a - b) <= rtol * max(abs(b), scale)


# -- exact references first -----------------------------------------------------------------
@pytest.mark.parametrize("model", ["tip", "centre"])
@pytest.mark.parametrize("n", [1, 2, 9, 200, 1000])
def test_rigid_foundation_exact(model: str, n: int) -> None:
    """Updates off: d0 = F0^2/(2EAq) (tip) or F0^2/(8EAq) (centre), and the trapezoidal loop of
    the parabola gives W = 4 F0 d0 (1 - 1/n^2)/3 exactly, so eta_secant = 4/(3 pi)(1 - 1/n^2),
    eta_stored = 2/pi (1 - 1/n^2) and eta_backbone = 4 (1 - 1/n^2)/(pi (4 - 1/n^2))."""
    p = preset("table2-tip" if model == "tip" else "table2-centre")
    amp = np.linspace(500.0, 15000.0, 7)
    opt = ModelOptions.uncorrected()
    ea, q = p.axial_stiffness, p.friction_per_length
    d_exact = (closedform.tip_displacement(amp, ea, q) if model == "tip"
               else closedform.centre_displacement(amp, ea, q))
    c = 1.0 - 1.0 / n**2
    expected = {
        "secant": 4.0 / (3.0 * math.pi) * c,
        "stored": 2.0 / math.pi * c,
        "backbone": 4.0 * c / (math.pi * (4.0 - 1.0 / n**2)),
    }
    for kind, eta in expected.items():
        r = batch_damping(model, p, amp, n, opt, kind)
        np.testing.assert_allclose(r.peak_displacement, d_exact, rtol=1e-13)
        np.testing.assert_allclose(r.dissipated_energy, 4.0 * amp * d_exact * c / 3.0,
                                   rtol=1e-12, atol=1e-14 * float(np.max(amp * d_exact)))
        if n > 1:
            np.testing.assert_allclose(r.loss_factor, eta, rtol=1e-12)


def test_secant_limit_at_1000_increments_is_4_over_3pi() -> None:
    p = preset("table1")
    r = batch_damping("tip", p, np.linspace(10.0, 350.0, 50), 1000, ModelOptions.uncorrected())
    assert np.max(np.abs(r.loss_factor - 4.0 / (3.0 * math.pi))) < 1e-6


# -- the single-loop API, case by case ------------------------------------------------------
@pytest.mark.parametrize("model", ["tip", "centre"])
@pytest.mark.parametrize("opt", OPTIONS, ids=lambda o: f"{o.poisson}-{o.length_update}-{o.centre}")
def test_matches_single_loop_api(model: str, opt: ModelOptions) -> None:
    """Every output of every case equals microslip.damping's to 1e-12 relative."""
    rng = np.random.default_rng([OPTIONS.index(opt), len(model)])
    size = 3
    worst = 0.0
    for n in (1, 2, 7, 64, 333):
        params = random_params(rng, size)
        factor = 2.0 if (model == "centre" and opt.centre == "paper") else 1.0
        limit = factor * params["friction"] * params["normal_force"]
        # keep paper-literal's shrinkage nu F0 (n + 1) / (2 E A) below 0.3
        ea = params["modulus"] * params["width"] * params["thickness"]
        shrink_ok = 0.6 * ea / (params["poisson_ratio"] * (n + 1))
        amp = np.minimum(limit, shrink_ok) * rng.uniform(0.02, 0.98, size)
        batch = {k: batch_damping(model, params, amp, n, opt, k) for k in KINDS}
        for j in range(size):
            cp = ClampParams(**{k: float(v[j]) for k, v in params.items()})
            bb = first_loading(model, cp, float(amp[j]), n, opt)
            loop = masing_loop(bb)
            scale = bb.amplitude * bb.peak_displacement
            for kind in KINDS:
                ref = damping_from_loop(loop, bb, kind)
                got = batch[kind]
                pairs = [(got.peak_displacement[j], ref.peak_displacement, 0.0),
                         (got.dissipated_energy[j], ref.dissipated_energy, scale),
                         (got.strain_energy[j], ref.strain_energy, 0.0)]
                if n > 1:
                    pairs.append((got.loss_factor[j], ref.loss_factor, 0.0))
                for a, b, s in pairs:
                    assert close(a, b, s, 1e-12), (n, j, kind, a, b)
                    worst = max(worst, abs(a - b) / max(abs(b), s))
    assert worst < 1e-12


def test_branch_energy_for_odd_and_even_increments() -> None:
    """Eq. 22's zero crossing falls on a sample (n even) or between two (n odd)."""
    p = preset("table2-centre")
    for n in (10, 11, 12, 13):
        r = batch_damping("centre", p, 12000.0, n, strain_energy="branch")
        bb = first_loading("centre", p, 12000.0, n)
        ref = damping_from_loop(masing_loop(bb), bb, "branch")
        assert close(float(r.strain_energy), ref.strain_energy, 0.0, 1e-12)


# -- backends and threads -------------------------------------------------------------------
@pytest.mark.slow
def test_backends_and_single_loop_agree_bit_for_bit() -> None:
    """The compiled kernel, its Python source and microslip.damping run one step function
    and one energy function: the same bits."""
    rng = np.random.default_rng(7)
    params = random_params(rng, 300)
    amp = params["friction"] * params["normal_force"] * rng.uniform(0.05, 0.95, 300)
    for model in ("tip", "centre"):
        for opt in (ModelOptions(), ModelOptions.paper()):
            for kind in KINDS:
                a = batch_damping(model, params, amp, 57, opt, kind, backend="numba")
                c = batch_damping(model, {k: v[:2] for k, v in params.items()}, amp[:2], 57,
                                  opt, kind, backend="python")
                for j in range(2):
                    cp = ClampParams(**{k: float(v[j]) for k, v in params.items()})
                    one = damping(model, cp, float(amp[j]), 57, opt, kind)
                    for name in ("peak_displacement", "dissipated_energy", "strain_energy",
                                 "loss_factor"):
                        assert getattr(a, name)[j] == getattr(c, name)[j] == getattr(one, name)


def test_threads_and_chunking_do_not_change_results() -> None:
    p = preset("table2-tip")
    amp = np.linspace(100.0, 15000.0, 3 * batch_kernels.CHUNK + 17)
    one = batch_damping("tip", p, amp, 100, threads=1)
    two = batch_damping("tip", p, amp, 100, threads=2)
    part = batch_damping("tip", p, amp[batch_kernels.CHUNK - 3:], 100, threads=2)
    np.testing.assert_array_equal(one.loss_factor, two.loss_factor)
    np.testing.assert_array_equal(one.loss_factor[batch_kernels.CHUNK - 3:], part.loss_factor)


def test_broadcast_shapes() -> None:
    p = preset("table2-tip").as_dict()
    p["friction"] = np.array([[0.6], [0.7], [0.8]])
    r = batch_damping("tip", p, np.array([1000.0, 2000.0]), 50)
    assert r.shape == (3, 2)
    assert r.amplitude.shape == (3, 2)
    s = batch_damping("tip", preset("table2-tip"), 1000.0, 50)
    assert s.shape == () and s.size == 1
    single = first_loading("tip", preset("table2-tip").replace(friction=0.7), 2000.0, 50)
    assert close(float(r.peak_displacement[1, 1]), single.peak_displacement, 0.0, 1e-13)


# -- validation once at the boundary --------------------------------------------------------
def test_macroslip_is_checked_per_case_with_the_models_rule() -> None:
    p = preset("table2-centre")  # mu F_N = 16000 N
    with pytest.raises(MacroslipError, match=r"amplitude 16000 N .* \(16000 N = mu F_N.*"
                       r"\(case 2 of 3\)"):
        batch_damping("tip", p, [1000.0, 15999.0, 16000.0], 10)
    # the paper's reading of the centre model slips at 2 mu F_N
    paper = ModelOptions(centre="paper")
    assert macroslip_force("centre", p, paper) == 32000.0
    r = batch_damping("centre", p, [20000.0, 31000.0], 10, paper)
    assert np.all(np.isfinite(r.loss_factor))
    with pytest.raises(MacroslipError, match="2 mu F_N"):
        batch_damping("centre", p, [20000.0, 32000.0], 10, paper)
    with pytest.raises(MacroslipError, match=r"amplitude 20000 N .*physical reading"):
        batch_damping("centre", p, [20000.0], 10)


@pytest.mark.parametrize(("change", "message"), [
    ({"friction": [0.8, -0.2]},
     r"friction must be finite and in \(0, inf\), got -0.2 \(case 1 of 2\)"),
    ({"poisson_ratio": 0.5}, r"poisson_ratio must be finite and in \[0, 0.5\), got 0.5"),
    ({"modulus": [np.nan, 1.0]}, r"modulus must be finite .* got nan \(case 0 of 2\)"),
    ({"length": [[1.0, 2.0, 3.0]]}, r"do not broadcast"),
    ({"width": "wide"}, r"width must be numbers"),
])
def test_bad_parameters_name_the_value(change: dict, message: str) -> None:
    p = {**preset("table1").as_dict(), **change}
    with pytest.raises(ParameterError, match=message):
        batch_damping("tip", p, [100.0, 200.0], 10)


def test_bad_arguments() -> None:
    p = preset("table1")
    with pytest.raises(ParameterError, match=r"amplitude must be finite .* got -5.0"):
        batch_damping("tip", p, [-5.0], 10)
    with pytest.raises(ParameterError, match="unknown model 'side'"):
        batch_damping("side", p, 100.0)
    with pytest.raises(ParameterError, match="unknown strain-energy definition 'area'"):
        batch_damping("tip", p, 100.0, strain_energy="area")
    with pytest.raises(ParameterError, match="increments must be a whole number"):
        batch_damping("tip", p, 100.0, increments=0)
    with pytest.raises(ParameterError, match="unknown batch backend 'gpu'"):
        batch_damping("tip", p, 100.0, backend="gpu")
    with pytest.raises(ParameterError, match="params lacks normal_force"):
        batch_damping("tip", {k: v for k, v in p.as_dict().items() if k != "normal_force"}, 1.0)
    with pytest.raises(ParameterError, match="unknown parameter 'colour'"):
        batch_damping("tip", {**p.as_dict(), "colour": 1.0}, 1.0)
    with pytest.raises(ParameterError, match="threads must be a whole number"):
        batch_damping("tip", p, 100.0, threads=0)


def test_breakdown_is_reported_like_the_single_loop_api() -> None:
    """Paper-literal Eqs 6-7 shrink the section by nu F_i/(EA) at every increment."""
    p = preset("table2-tip")
    opt = ModelOptions(poisson="paper-literal")
    with pytest.raises(ParameterError, match="broke down"):
        first_loading("tip", p, 8000.0, 1500, opt)
    with pytest.raises(ParameterError, match=r"broke down at 1500 increments.*\(case 1 of 2\)"):
        batch_damping("tip", p, [1000.0, 8000.0], 1500, opt)


def test_a_strain_beyond_the_small_strain_models_is_refused_in_both_paths() -> None:
    """Hypothesis found this clamp (1 mm^2 section, E = 1000 MPa, 0.9 mu F_N = 20 kN, strain
    20): the centre loop came out inside out (W_d = -3.8e5 N mm). Both paths refuse it in the
    same words, and a load just below the strain limit runs with W_d > 0."""
    p = ClampParams(5.0, 1.0, 1.0, 1000.0, 0.0, 0.5, 45255.0)
    amp = 0.9 * p.macroslip_force
    message = r"F0/\(E w t\) = 20\.4, beyond the small-strain models' 0\.1"
    with pytest.raises(ParameterError, match=message + "; microslip needs amplitude < 100 N"):
        first_loading("centre", p, amp, 2)
    with pytest.raises(ParameterError, match=message + r" \(case 1 of 2\)"):
        batch_damping("centre", p, [50.0, amp], 2)
    r = batch_damping("centre", p, 99.0, 50)
    assert float(r.dissipated_energy) > 0.0


# -- invariants over random cases -----------------------------------------------------------
@settings(max_examples=60, deadline=None)
@given(model=st.sampled_from(["tip", "centre"]), opt=st.sampled_from(OPTIONS),
       kind=st.sampled_from(KINDS), n=st.integers(2, 150),
       length=st.floats(5.0, 500.0), width=st.floats(1.0, 50.0), thickness=st.floats(1.0, 80.0),
       modulus=st.floats(1e3, 3e5), nu=st.floats(0.0, 0.49), mu=st.floats(0.05, 1.5),
       fn=st.floats(10.0, 1e5), level=st.floats(0.01, 0.99))
def test_any_case_matches_the_single_loop_api(model: str, opt: ModelOptions, kind: str, n: int,
                                              length: float, width: float, thickness: float,
                                              modulus: float, nu: float, mu: float, fn: float,
                                              level: float) -> None:
    """W_d > 0, U > 0 and the single-loop numbers to 1e-12 for any valid case."""
    p = ClampParams(length, width, thickness, modulus, nu, mu, fn)
    amp = level * macroslip_force(model, p, opt)
    try:
        bb = first_loading(model, p, amp, n, opt)
    except ParameterError as exc:  # the paper-literal section vanished, or the strain is
        # beyond the small-strain models: the batch must say the same
        reason = "broke down" if "broke down" in str(exc) else "small-strain"
        with pytest.raises(ParameterError, match=reason):
            batch_damping(model, p, amp, n, opt, kind)
        return
    ref = damping_from_loop(masing_loop(bb), bb, kind)
    r = batch_damping(model, p, amp, n, opt, kind)
    assert float(r.dissipated_energy) > 0.0 and float(r.strain_energy) > 0.0
    for a, b in ((r.peak_displacement, ref.peak_displacement),
                 (r.dissipated_energy, ref.dissipated_energy),
                 (r.strain_energy, ref.strain_energy), (r.loss_factor, ref.loss_factor)):
        assert abs(float(a) / b - 1.0) < 1e-12
