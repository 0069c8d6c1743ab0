"""The contact under the 1-D models (models.contact) and its command-line options.

Exact references: the paper's corrected recurrence in the rigid limit (to 1e-9), Menq's
shear-layer bar (REFERENCES.md) with the corrections off; then the FE figures of issue 11
(built-in solver, medium mesh, Table 1 material, 213 N) within 2 %; then the CLI contract:
``--stick-slope`` on loop and planar, ``warnings`` in JSON and on stderr.
"""

from __future__ import annotations

import dataclasses
import json
import math

import numpy as np
import pytest
from conftest import run

from microslip import ModelOptions, damping, preset
from microslip.errors import ParameterError
from microslip.models import Contact, first_loading
from microslip.models.interface import power_law, virgin_curve

P = preset("table1")
EA = P.modulus * P.width * P.thickness
Q = P.friction * P.normal_force / P.length
OPTIONS = [ModelOptions(), ModelOptions.uncorrected(), ModelOptions(poisson="paper-literal"),
           ModelOptions(length_update=False)]


@pytest.mark.parametrize("model", ["tip", "centre"])
@pytest.mark.parametrize("opt", OPTIONS, ids=lambda o: f"{o.poisson}-{o.length_update}")
def test_rigid_limit_is_the_papers_recurrence(model, opt):
    """An infinitely stiff contact without shear lag is the paper's foundation: the corrected
    recurrence is recovered to rounding, whatever the Poisson and length readings."""
    paper = first_loading(model, P, 267.0, 500, opt)
    stiff = first_loading(model, P, 267.0, 500, opt, Contact(1e300, shear_lag=False))
    np.testing.assert_allclose(stiff.displacement, paper.displacement, rtol=1e-9, atol=0)
    np.testing.assert_allclose(stiff.slip_length, paper.slip_length, rtol=1e-9, atol=1e-12)


def test_menq_closed_form_with_the_corrections_off():
    """Menq's bar, parametric in the slip length a: F = q a + (q/lambda) tanh(lambda (L - a)),
    d = q/k + (F a - q a^2/2)/(E A), k = stick slope x width."""
    slope = 2e3
    k = slope * P.width
    lam = math.sqrt(k / EA)
    a = np.array([0.1, 0.4, 0.8]) * P.length
    f = Q * a + Q / lam * np.tanh(lam * (P.length - a))
    d = Q / k + (f * a - Q * a * a / 2) / EA
    for fi, di in zip(f, d, strict=True):
        bb = first_loading("tip", P, float(fi), 4, ModelOptions.uncorrected(),
                           Contact(slope, shear_lag=False))
        assert bb.displacement[-1] == pytest.approx(di, rel=1e-11)


def test_a_finite_layer_is_softer_and_dissipates_less_than_the_rigid_bar():
    rigid = damping("tip", P, 213.0, 1000)
    for slope in (1e3, 1e4, 1e5):
        layered = damping("tip", P, 213.0, 1000, contact=Contact.layer(slope))
        assert layered.peak_displacement > rigid.peak_displacement
        assert layered.dissipated_energy < rigid.dissipated_energy


# issue 11: built-in FE, medium mesh, 213 N, W_d (N mm) at stick slope 1e4 / 1e5 / 1e6 N/mm^3
FE = {3.18: (0.820, 0.822, 0.822), 12.7: (0.201, 0.203, 0.204), 25.4: (0.095, 0.097, 0.097)}


@pytest.mark.parametrize("thickness", list(FE))
def test_layer_model_against_the_fe_of_issue_11(thickness):
    """Within 2 % of the FE (the medium mesh is itself 1-3 % high through the thickness)."""
    p = dataclasses.replace(P, thickness=thickness)
    for slope, fe in zip((1e4, 1e5, 1e6), FE[thickness], strict=True):
        w = damping("tip", p, 213.0, 2000, contact=Contact.layer(slope)).dissipated_energy
        assert w == pytest.approx(fe, rel=0.02), (thickness, slope)


def test_pressure_law_reaches_the_backbone():
    law = power_law(2.0, 3.0)
    bb = first_loading("tip", P, 200.0, 50, ModelOptions.uncorrected(),
                       Contact(math.inf, shear_lag=False, law=law))
    _, d = virgin_curve("tip", P, bb.force, law=law, shear_lag=False)
    np.testing.assert_allclose(bb.displacement, d, rtol=1e-14, atol=0)
    uniform = first_loading("tip", P, 200.0, 50, ModelOptions.uncorrected())
    assert bb.displacement[-1] != pytest.approx(uniform.displacement[-1], rel=1e-3)


def test_refusals():
    with pytest.raises(ParameterError, match="stick slope must be > 0"):
        Contact(-1.0)
    with pytest.raises(ParameterError, match="'stored'"):
        damping("tip", P, 200.0, 100, strain_energy="stored", contact=Contact.layer(1e4))
    with pytest.raises(ParameterError, match="physical centre reading"):
        first_loading("centre", P, 200.0, 100, ModelOptions(centre="paper"), Contact.layer(1e4))


# -- command line ---------------------------------------------------------------------------
def test_loop_stick_slope_json_and_text(capsys):
    code, out, err = run(capsys, "loop", "--model", "tip", "--amplitude", "213", "--json",
                         "--stick-slope", "1e5", "--increments", "2000")
    assert code == 0 and err == ""
    d = json.loads(out)
    assert d["contact"] == {"stick_slope_N_per_mm3": 1e5, "shear_lag": True,
                            "pressure_law": "uniform"}
    assert d["warnings"] == []
    expected = damping("tip", P, 213.0, 2000, contact=Contact.layer(1e5)).dissipated_energy
    assert d["dissipated_energy_Nmm"] == expected
    code, out, _ = run(capsys, "loop", "--model", "tip", "--stick-slope", "1e5")
    assert code == 0 and "stick slope 100000 N/mm^3 + the body's shear lag" in out


def test_thick_block_warns_on_stderr_and_in_json(capsys):
    code, out, err = run(capsys, "loop", "--model", "tip", "--amplitude", "213", "--json",
                         "--thickness", "50.8")
    d = json.loads(out)
    assert code == 0 and d["warnings"]
    assert err.splitlines() == [f"warning: {w}" for w in d["warnings"]]
    assert any("shear lag" in w for w in d["warnings"])
    assert any("microslip fe --model tip" in w for w in d["warnings"])


def test_planar_gross_sliding_is_said(capsys):
    code, out, _ = run(capsys, "planar", "--ratio", "0.25", "--centre-reading", "paper",
                       "--json", "--increments", "100", "--samples-per-cycle", "128")
    assert code == 0
    assert any("gross sliding" in w for w in json.loads(out)["warnings"])


@pytest.mark.parametrize(("argv", "message"), [
    (["loop", "--model", "tip", "--no-shear-lag"], "--no-shear-lag needs --stick-slope"),
    (["loop", "--model", "tip", "--pressure-law", "wavy"], "--pressure-law 'wavy'"),
    (["loop", "--model", "tip", "--stick-slope", "0"], "stick slope must be > 0"),
    (["loop", "--model", "tip", "--stick-slope", "1e4", "--strain-energy", "stored"],
     "'stored'"),
    (["planar", "--solver", "fe", "--tip-amplitude", "100", "--centre-amplitude", "100",
      "--pressure-law", "parabolic"], "apply to the analytical models"),
])
def test_bad_contact_options_are_one_line(capsys, argv, message):
    code, out, err = run(capsys, *argv)
    assert code == 1 and out == "" and message in err and len(err.strip().splitlines()) == 1


def test_sweep_on_a_contact_is_the_loop_of_each_case(capsys, tmp_path):
    """The batch engine's layer kernel gives each case's single loop bit for bit."""
    table = tmp_path / "s.csv"
    code, out, err = run(capsys, "sweep", "--model", "tip", "--amplitude-range", "100", "300",
                         "--cases", "3", "--increments", "200", "--stick-slope", "1e4",
                         "--no-progress", "--out", table)
    assert code == 0, err
    assert "contact: stick slope 10000 N/mm^3 + shear lag, uniform pressure" in out
    rows = np.genfromtxt(table, delimiter=",", names=True)
    for row in rows:
        r = damping("tip", P, float(row["amplitude_N"]), 200, contact=Contact.layer(1e4))
        assert row["dissipated_energy_Nmm"] == r.dissipated_energy
        assert row["loss_factor"] == r.loss_factor
