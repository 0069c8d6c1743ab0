"""The comparison code of ``microslip validate`` on synthetic FE results built from the exact
closed forms (no CalculiX needed): rows, errors, verdicts, figures, contract, CLI errors."""

from __future__ import annotations

import inspect
import math
from pathlib import Path

import numpy as np
import pytest

from microslip import closedform as cf
from microslip import preset
from microslip.cli.main import main
from microslip.energy import damping_from_loop, loop_work
from microslip.errors import ParameterError
from microslip.fe import FECase, SolverNotFoundError
from microslip.fe.calculix.boxrun import box20_mesh
from microslip.fe.calculix.collect import CalculixDetails
from microslip.fe.result import ContactHistory, FELoopResult, column_lengths
from microslip.results import HysteresisLoop
from microslip.validate import (
    TOLERANCES,
    ValidationReport,
    _slipping_force,
    closed_form,
    plot_contact_status,
    plot_fe_vs_model,
    run_validation,
    shear_layer_reference,
    validation_row,
)

P = preset("table1")
EA, Q, F0 = P.axial_stiffness, P.friction_per_length, 267.0


def exact_result(model: str, scale: float = 1.0) -> FELoopResult:
    """An FELoopResult whose loop is the exact Masing loop (times ``scale``) at the 50 substeps
    and whose contact status is the closed-form slip zone."""
    case = FECase(model)
    c = 2 * EA * Q if model == "tip" else 8 * EA * Q
    t = case.times
    f = case.force(t)
    g = lambda x: x * x / c  # noqa: E731
    d0 = g(F0)
    d = np.where(t <= 0.25 + 1e-12, g(f),
                 np.where(t <= 0.75 + 1e-12, d0 - 2 * g((F0 - f) / 2), -d0 + 2 * g((F0 + f) / 2)))
    d = scale * d
    mesh = box20_mesh(P, case.spec)
    ids = np.sort(mesh.node_sets["contact"])
    xyz = mesh.nodes[ids]
    status = np.ones((t.size, ids.size), dtype=np.int8)
    for k, tk in enumerate(t):
        span = _slipping_force(tk, f[k], F0)
        if model == "tip":
            slipping = xyz[:, 0] > P.length - span / Q + 1e-9
        else:
            slipping = np.abs(xyz[:, 0] - P.length / 2) < span / (2 * Q) - 1e-9
        status[k, slipping] = 2
    contact = ContactHistory(ids, xyz, t, status, column_lengths(xyz[:, 0]),
                             np.zeros((*status.shape, 2)))
    loop = HysteresisLoop(f[10:], d[10:], "calculix", {"time_s": t[10:]})
    details = CalculixDetails(case, 0.0, np.full(status.shape, 0.07),
                              np.zeros((*status.shape, 2)))
    return FELoopResult("calculix", model, P, F0, t, f, d, loop, damping_from_loop(loop), contact,
                        case.spec.dof, np.full(50, 4), 1.0, True, "converged", details)


@pytest.mark.parametrize("model", ["tip", "centre"])
def test_exact_loop_gives_zero_peak_error_and_the_sampling_bias(model):
    row = validation_row(exact_result(model), "coarse")
    assert row["err_peak_fe_closed"] == pytest.approx(0.0, abs=1e-12)
    # 40 trapezoids per cycle underestimate the area of the quadratic loop by 0.41 %
    assert row["wd_fe_Nmm"] == pytest.approx(row["wd_closed_sampled_Nmm"], rel=1e-12)
    assert row["err_wd_fe_closed"] == pytest.approx(-0.0041, abs=2e-4)
    assert row["eta_closed"] == pytest.approx(4 / (3 * math.pi))
    assert row["peak_uncorrected_mm"] == pytest.approx(row["peak_closed_mm"], rel=1e-9)
    assert row["verdict"] == "pass" and row["loop_closure"] == 0.0
    assert row["peak_shear_layer_mm"] > row["peak_closed_mm"]
    assert row["wd_shear_layer_Nmm"] < row["wd_closed_Nmm"]
    exact_slip = F0 / Q if model == "tip" else F0 / (2 * Q)
    assert row["slip_length_closed_mm"] == pytest.approx(exact_slip)
    assert row["slip_length_fe_mm"] == pytest.approx(exact_slip, abs=12.7)


@pytest.mark.parametrize("model", ["tip", "centre"])
def test_verdict_fails_just_outside_the_tolerance(model):
    tol = TOLERANCES[model]["peak"]
    assert validation_row(exact_result(model, 1 + 0.9 * tol), "coarse")["verdict"] == "pass"
    assert validation_row(exact_result(model, 1 + 1.1 * tol), "coarse")["verdict"] == "FAIL"


def test_closed_form_matches_the_references():
    tip, centre = closed_form("tip", P, F0), closed_form("centre", P, F0)
    assert tip["peak_mm"] == pytest.approx(F0**2 / (2 * EA * Q), rel=1e-14)
    assert tip["wd_Nmm"] == cf.tip_dissipated_energy(F0, EA, Q)
    assert centre["peak_mm"] == pytest.approx(F0**2 / (8 * EA * Q), rel=1e-14)
    assert centre["wd_Nmm"] == cf.centre_dissipated_energy(F0, EA, Q)
    with pytest.raises(ParameterError):
        closed_form("side", P, F0)


@pytest.mark.parametrize("model", ["tip", "centre"])
def test_shear_layer_reference_tends_to_the_closed_form(model):
    exact = closed_form(model, P, F0)
    errors = []
    for lam in (1e3, 1e4, 1e5, 1e6):
        r = shear_layer_reference(model, P, F0, lam)
        errors.append((r["peak_mm"] / exact["peak_mm"] - 1, r["wd_Nmm"] / exact["wd_Nmm"] - 1))
    e = np.array(errors)
    assert np.all(e[:, 0] > 0) and np.all(e[:, 1] < 0)  # softer and less dissipative
    # the stick-slope error falls as 1/lambda (the shear-lag length is 1/sqrt(lambda w/EA),
    # the extra displacement ~ q/(lambda w) relative to d0)
    np.testing.assert_allclose(e[1:, 0] / e[:-1, 0], 0.1, rtol=0.06)
    # pinned values quoted in docs/validation.md, Section 4
    r4 = shear_layer_reference(model, P, F0, 1e4)
    expected = {"tip": (0.060, -0.178), "centre": (0.242, -0.701)}[model]
    assert 100 * (r4["peak_mm"] / exact["peak_mm"] - 1) == pytest.approx(expected[0], abs=5e-4)
    assert 100 * (r4["wd_Nmm"] / exact["wd_Nmm"] - 1) == pytest.approx(expected[1], abs=5e-4)


def test_shear_layer_reference_below_first_slip_is_linear():
    r = shear_layer_reference("tip", P, 0.5, 1e2)  # far below (q/beta) tanh(beta L)
    assert r["wd_Nmm"] == pytest.approx(0.0, abs=1e-15) and r["peak_mm"] > 0


def test_slipping_force_follows_masing():
    assert _slipping_force(0.25, F0, F0) == F0  # first loading
    assert _slipping_force(0.5, 0.0, F0) == F0 / 2  # back to zero from +F0
    assert _slipping_force(0.75, -F0, F0) == F0  # full reversal
    assert _slipping_force(1.0, 0.0, F0) == F0 / 2  # back to zero from -F0


@pytest.mark.parametrize("model", ["tip", "centre"])
def test_sampled_closed_form_area_is_the_trapezoid_of_the_exact_loop(model):
    """The row's sampled closed form is the exact loop's trapezoid at the FE's 41 samples;
    sampled finely, the same loop's area is the closed form W_d (Eq. 21) to O(1/n^2)."""
    row = validation_row(exact_result(model), "coarse")
    r = exact_result(model)
    assert row["wd_closed_sampled_Nmm"] == pytest.approx(
        loop_work(r.loop.force, r.loop.displacement), rel=1e-12)
    c = 2 * EA * Q if model == "tip" else 8 * EA * Q
    f = F0 * np.cos(np.linspace(0.0, 2 * np.pi, 200_001))
    up = np.arange(f.size) >= f.size // 2
    d0 = F0 * F0 / c
    d = np.where(up, -d0 + 2 * ((F0 + f) / 2) ** 2 / c, d0 - 2 * ((F0 - f) / 2) ** 2 / c)
    closed = cf.tip_dissipated_energy(F0, EA, Q) if model == "tip" else \
        cf.centre_dissipated_energy(F0, EA, Q)
    assert loop_work(f, d) == pytest.approx(closed, rel=1e-9)
    # the 40-interval trapezoid misses 0.41 % of the area (docs/validation.md)
    assert row["wd_closed_sampled_Nmm"] / closed - 1 == pytest.approx(-0.0041, abs=5e-5)


def test_figures_are_written(tmp_path: Path):
    pytest.importorskip("matplotlib")
    results = [exact_result("tip"), exact_result("centre")]
    plot_contact_status(results, tmp_path / "fig08.png")
    plot_fe_vs_model(results, ["coarse", "coarse"], tmp_path / "fig09.png")
    assert (tmp_path / "fig08.png").stat().st_size > 10_000
    assert (tmp_path / "fig09.png").stat().st_size > 10_000
    assert sorted(p.name for p in tmp_path.iterdir()) == ["fig08.png", "fig09.png"]


def test_run_validation_contract():
    sig = inspect.signature(run_validation)
    names = list(sig.parameters)
    assert names[:3] == ["out_dir", "meshes", "models"]
    assert sig.parameters["meshes"].default == ("coarse",)
    assert sig.parameters["models"].default == ("tip", "centre")
    for kw, default in (("progress", True), ("timeout", None), ("scheduler", None)):
        assert sig.parameters[kw].kind is inspect.Parameter.KEYWORD_ONLY
        assert sig.parameters[kw].default == default
    fields = ValidationReport.__dataclass_fields__
    assert {"files", "rows", "summary_markdown"} <= set(fields)
    assert ValidationReport.__dataclass_params__.frozen  # type: ignore[attr-defined]


def test_run_validation_rejects_bad_arguments(tmp_path):
    with pytest.raises(ParameterError):
        run_validation(tmp_path, models=("side",))
    with pytest.raises(ParameterError):
        run_validation(tmp_path, meshes=())
    with pytest.raises(ParameterError):
        run_validation(tmp_path, meshes=("huge",))
    with pytest.raises(ParameterError):
        run_validation(tmp_path, timeout=-1.0)


def test_without_ccx_nothing_is_written(monkeypatch, tmp_path):
    monkeypatch.setenv("PATH", str(tmp_path / "empty"))
    with pytest.raises(SolverNotFoundError, match="apt-get install calculix-ccx"):
        run_validation(tmp_path / "out")
    assert not (tmp_path / "out").exists()


@pytest.mark.parametrize("argv", [
    ["fe", "--model", "tip", "--solver", "calculix"],
    ["fe", "--model", "centre", "--solver", "calculix", "--mesh", "paper", "--out", "DIR",
     "--json"],
    ["validate", "--out", "DIR"],
])
def test_cli_without_ccx_fails_with_one_line(argv, monkeypatch, tmp_path, capsys):
    monkeypatch.setenv("PATH", str(tmp_path / "empty"))
    argv = [str(tmp_path / "o") if a == "DIR" else a for a in argv]
    code = main(argv)
    out, err = capsys.readouterr()
    assert code == 1 and out == ""
    assert err.count("\n") == 1 and err.startswith("error: ")
    assert "bash scripts/setup.sh" in err and "apt-get install calculix-ccx" in err
    assert not (tmp_path / "o").exists()


@pytest.mark.parametrize("argv, code, text", [
    (["fe", "--model", "tip", "--amplitude", "400"], 1, "macroslip"),
    (["fe", "--model", "tip", "--stick-slope", "-5"], 1, "stick_slope"),
    (["fe", "--model", "tip", "--substeps", "52"], 1, "multiple of 5"),
    (["fe", "--model", "tip", "--timeout", "0"], 1, "timeout"),
    (["fe", "--model", "tip", "--mesh", "huge"], 2, "unknown mesh 'huge'"),
    (["fe", "--model", "tip", "--solver", "calculix", "--mesh", "9x2x1"], 1,
     "nx must be an even integer"),
    (["fe", "--model", "tip", "--element", "C3D20R"], 1, "not an element of the builtin"),
    (["fe", "--model", "tip", "--solver", "ansys"], 2, "invalid choice"),
    (["validate"], 2, "--out"),
    (["validate", "--out", "x", "--timeout", "-3"], 1, "timeout"),
])
def test_cli_user_errors_are_one_line(argv, code, text, capsys):
    assert main(argv) == code
    out, err = capsys.readouterr()
    assert out == "" and err.count("\n") == 1 and text in err


def test_the_box_validation_refuses_a_contact_formulation(capsys):
    """--contact-formulation chooses CalculiX's contact on a mesh file; the box's validation
    has its own deck, so the option is refused there (one line, exit 1)."""
    from microslip.cli.main import main

    assert main(["validate", "--out", "x", "--contact-formulation", "face-to-face"]) == 1
    err = capsys.readouterr().err
    assert "--contact-formulation applies to --mesh FILE" in err
    assert len(err.strip().splitlines()) == 1
