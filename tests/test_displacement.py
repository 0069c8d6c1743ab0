"""Displacement-controlled amplitudes: the inversion of the backbone and --displacement-amplitude
on loop, fe, planar and sweep."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from conftest import run
from hypothesis import given, settings
from hypothesis import strategies as st

from microslip import ModelOptions, first_loading, preset
from microslip.displacement import (
    displacement_range,
    force_for_displacement,
    force_for_fe_displacement,
)
from microslip.errors import MacroslipError
from microslip.models import macroslip_force

OPTIONS = (ModelOptions(), ModelOptions.uncorrected(), ModelOptions.paper())


def test_rigid_limit_inverts_the_closed_form():
    # tip model, both updates off: d = F^2 / (2 EA q) exactly (Eq. 4 on a rigid foundation)
    p = preset("table1")
    d0 = 0.004
    f = force_for_displacement("tip", p, d0, 500, ModelOptions.uncorrected())
    assert f == pytest.approx(math.sqrt(2 * p.axial_stiffness * p.friction_per_length * d0),
                              rel=1e-12)


def test_range_is_the_displacement_just_below_macroslip():
    p = preset("table1")
    opt = ModelOptions()
    limit = displacement_range("tip", p, 1000, opt)
    below = first_loading("tip", p, 0.999 * macroslip_force("tip", p, opt), 1000, opt)
    assert below.peak_displacement < limit < 1.01 * below.peak_displacement
    with pytest.raises(MacroslipError, match=r"0 < displacement < 0\.0081"):
        force_for_displacement("tip", p, limit, 1000, opt)
    for bad in (0.0, -1e-3, math.nan, math.inf):
        with pytest.raises(MacroslipError):
            force_for_displacement("tip", p, bad, 1000, opt)


@settings(max_examples=30, deadline=None)
@given(model=st.sampled_from(["tip", "centre"]), which=st.integers(0, 2),
       share=st.floats(1e-4, 0.9999))
def test_the_force_found_reaches_the_displacement(model, which, share):
    p = preset("table1")
    opt = OPTIONS[which]
    n = 200
    d0 = share * displacement_range(model, p, n, opt)
    f = force_for_displacement(model, p, d0, n, opt)
    assert 0 < f < macroslip_force(model, p, opt)
    assert first_loading(model, p, f, n, opt).peak_displacement == pytest.approx(d0, rel=1e-12)


def test_a_larger_displacement_needs_a_larger_force():
    p = preset("table2-tip")
    d = np.linspace(0.1, 0.9, 9) * displacement_range("tip", p)
    f = [force_for_displacement("tip", p, x) for x in d]
    assert np.all(np.diff(f) > 0)


def test_loop_displacement_amplitude_gives_the_loop_of_its_force(capsys):
    code, out, err = run(capsys, "loop", "--model", "centre", "--displacement-amplitude",
                         "0.0015", "--json", "--increments", "300")
    assert code == 0 and err == ""
    by_d = json.loads(out)
    assert by_d["displacement_amplitude_mm"] == 0.0015
    assert by_d["peak_displacement_mm"] == pytest.approx(0.0015, rel=1e-12)
    code, out, _ = run(capsys, "loop", "--model", "centre", "--amplitude",
                       repr(by_d["amplitude_N"]), "--json", "--increments", "300")
    by_f = json.loads(out)
    assert code == 0
    assert by_f["loop"] == by_d["loop"]
    assert by_f["loss_factor"] == by_d["loss_factor"]


def test_loop_text_names_the_force_found(capsys):
    code, out, _ = run(capsys, "loop", "--model", "tip", "--displacement-amplitude", "0.005")
    assert code == 0
    assert "from --displacement-amplitude 0.005 mm" in out and "279.37" in out


@pytest.mark.parametrize("argv, code, text", [
    (["loop", "--model", "tip", "--displacement-amplitude", "0.05"], 1,
     "0 < displacement < 0.00811"),
    (["loop", "--model", "tip", "--displacement-amplitude", "0.001", "--amplitude", "100"], 2,
     "not allowed with argument --amplitude"),
    (["planar", "--displacement-amplitude", "0.01", "0.001", "--ratio", "1"], 2,
     "not allowed with argument --ratio"),
    (["planar", "--displacement-amplitude", "0.01", "0.001", "--solver", "fe"], 1,
     "applies to --solver analytical"),
    (["sweep", "--model", "tip", "--displacement-amplitude", "0.005", "--grid", "mu=0.4,0.8"],
     1, "cannot be combined with sweeping or sampling friction"),
    (["sweep", "--model", "tip", "--displacement-amplitude", "0.005", "--amplitude-range",
      "1", "2"], 2, "not allowed with argument --amplitude-range"),
])
def test_user_errors_are_one_line(capsys, argv, code, text):
    got, out, err = run(capsys, *argv)
    assert got == code and out == ""
    assert text in err and err.count("\n") == 1 and "Traceback" not in err


def test_planar_displacement_amplitudes(capsys):
    code, out, _ = run(capsys, "planar", "--displacement-amplitude", "0.01", "0.001", "--json",
                       "--increments", "300")
    assert code == 0
    data = json.loads(out)
    tip = force_for_displacement("tip", preset("table2-tip"), 0.01, 300)
    centre = force_for_displacement("centre", preset("table2-centre"), 0.001, 300)
    code, out, _ = run(capsys, "planar", "--tip-amplitude", repr(tip), "--centre-amplitude",
                       repr(centre), "--json", "--increments", "300")
    assert code == 0 and json.loads(out) == data


def test_sweep_displacement_amplitude_runs_the_force_found(capsys):
    code, out, _ = run(capsys, "sweep", "--model", "tip", "--displacement-amplitude", "0.005",
                       "--no-progress")
    f = force_for_displacement("tip", preset("table1"), 0.005)
    code2, out2, _ = run(capsys, "sweep", "--model", "tip", "--amplitude", repr(f),
                         "--no-progress")
    assert code == code2 == 0
    eta = [line for line in out.splitlines() if "loss factor" in line]
    assert eta and eta == [line for line in out2.splitlines() if "loss factor" in line]


def test_fe_root_find_on_a_known_curve():
    # d(F) = F^2 (a parabola): the root is sqrt(d), whatever the guess
    for guess in (0.1, 1.0, 3.0, 10.0):
        assert force_for_fe_displacement(lambda f: f * f, 4.0, guess, 10.0) == pytest.approx(
            2.0, rel=1e-9)
    with pytest.raises(MacroslipError, match="0 < displacement < 100"):
        force_for_fe_displacement(lambda f: f * f, 200.0, 5.0, 10.0)


def test_fe_displacement_amplitude_gives_the_loop_of_its_force(capsys):
    argv = ["fe", "--model", "tip", "--mesh", "tiny", "--substeps", "20", "--json"]
    code, out, _ = run(capsys, *argv, "--displacement-amplitude", "0.004")
    assert code == 0
    by_d = json.loads(out)
    assert by_d["peak_displacement_mm"] == pytest.approx(0.004, rel=1e-8)
    code, out, _ = run(capsys, *argv, "--amplitude", repr(by_d["amplitude_N"]))
    by_f = json.loads(out)
    assert code == 0
    for key in ("peak_displacement_mm", "dissipated_energy_Nmm", "loss_factor"):
        assert by_f[key] == by_d[key]
