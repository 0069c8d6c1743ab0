"""Mesh convergence as a result (fe.convergence, fe --mesh --refine/--convergence, modal --mesh
--convergence): Richardson's estimate exact on sequences with a known limit and order, the
levels equal to the plain runs of the refined meshes, and the options' one-line refusals."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest

from microslip.cli.main import main
from microslip.errors import ParameterError
from microslip.fe.convergence import (
    THEORETICAL_ORDER,
    converge_frequencies,
    richardson,
)
from microslip.fe.examples import cantilever_mesh
from microslip.fe.meshfile import write_inp

CLAMP = ["--contact-set", "contact", "--clamp-set", "clamp", "--normal-force", "2000",
         "--friction", "0.5", "--stick-slope", "1e4", "--modulus", "70000",
         "--poisson-ratio", "0.33"]


@pytest.mark.parametrize("order", [1.0, 1.5, 2.0, 3.0])
def test_three_levels_give_the_limit_and_the_order_exactly(order: float) -> None:
    h = np.array([1.0, 0.5, 0.25])
    est = richardson(list(3.0 + 0.7 * h ** order), assumed_order=2.0)
    assert est.order_source == "observed" and est.note == ""
    assert est.order == pytest.approx(order, rel=1e-12)
    assert est.value == pytest.approx(3.0, rel=1e-14)
    assert est.relative_error == pytest.approx(0.7 / 3.0, rel=1e-12)


def test_two_levels_assume_the_order_and_say_so() -> None:
    est = richardson([3.0 + 0.7, 3.0 + 0.7 / 4], assumed_order=2.0)  # exact at order 2
    assert est.order_source == "assumed" and "theoretical order" in est.note
    assert est.value == pytest.approx(3.0, rel=1e-15)
    # the grid convergence index with Roache's safety factor 3 for an assumed order
    assert est.uncertainty == pytest.approx(3 * 0.7 / 4 / 3.0, rel=1e-12)


@pytest.mark.parametrize("values, note", [
    ([1.0, 0.9, 0.95], "oscillate"),
    ([1.0, 0.98, 0.9], "do not shrink"),
    ([1.0, 1.0, 1.0], "same value"),
])
def test_three_levels_out_of_the_asymptotic_range_fall_back(values: list[float],
                                                           note: str) -> None:
    est = richardson(values, assumed_order=2.0)
    assert est.order_source == "none" and note in est.note and est.order == 2.0
    assert est.value == values[2]  # no extrapolation outside the asymptotic range
    big = max(abs(values[1] - values[0]), abs(values[2] - values[1]))
    assert est.uncertainty == pytest.approx(3 * big / abs(est.value), rel=1e-12)


@pytest.mark.parametrize("bad", [[1.0], [1.0, 2.0, 3.0, 4.0], [1.0, math.nan]])
def test_bad_values_are_refused(bad: list[float]) -> None:
    with pytest.raises(ParameterError, match="2 or 3 finite values"):
        richardson(bad, 2.0)


def test_frequency_levels_are_the_refined_meshes() -> None:
    """A stand-in eigen-solve f = 100 (1 + h^2) on the given mesh and its refinements."""
    mesh = cantilever_mesh(3, 1, 1)
    n0 = len(mesh.elements)

    def freqs(m):
        h = (n0 / len(m.elements)) ** (1 / 3)
        return 3 * len(m.nodes), [100 * (1 + h ** 2), 250 * (1 + 2 * h ** 2)]

    found = converge_frequencies(mesh, freqs, levels=3)
    assert found.refine == (1, 2, 4)
    assert found.dof == tuple(3 * (3 * r + 1) * (r + 1) ** 2 for r in (1, 2, 4))
    assert [e.value for e in found.estimates] == pytest.approx([100.0, 250.0], rel=1e-13)
    assert [e.order for e in found.estimates] == pytest.approx([2.0, 2.0], rel=1e-12)
    summary = found.summary()
    assert summary["converged_linear_frequencies_Hz"] == pytest.approx([100.0, 250.0])
    assert found.warnings() and "modes 1, 2" in found.warnings()[0]


@pytest.fixture(scope="module")
def small(tmp_path_factory: pytest.TempPathFactory) -> str:
    path = tmp_path_factory.mktemp("mesh") / "cant6.inp"
    write_inp(cantilever_mesh(6, 2, 1), path)
    return str(path)


def _fe(capsys: pytest.CaptureFixture[str], *argv: str) -> dict:
    assert main(["fe", *argv, "--json"]) == 0
    return json.loads(capsys.readouterr().out)


def test_fe_convergence_json_levels_are_the_refined_runs(capsys, small: str) -> None:
    load = ["--load", "tip:1,0,0:300"]
    out = _fe(capsys, "--mesh", small, *CLAMP, *load, "--convergence")
    plain = _fe(capsys, "--mesh", small, *CLAMP, *load)
    fine = _fe(capsys, "--mesh", small, *CLAMP, *load, "--refine", "2")
    conv = out["converged"]
    levels = conv["levels"]
    assert [lv["refine"] for lv in levels] == [1, 2]
    # the given mesh's own keys are the plain run's, the levels the refined runs
    assert out["dissipated_energy_Nmm"] == plain["dissipated_energy_Nmm"]
    assert levels[0]["dissipated_energy_Nmm"] == plain["dissipated_energy_Nmm"]
    assert levels[1]["dissipated_energy_Nmm"] == fine["dissipated_energy_Nmm"]
    assert levels[1]["dof"] == fine["dof"] and fine["refine"] == 2
    assert fine["elements"] == 8 * plain["elements"]
    w = [lv["dissipated_energy_Nmm"] for lv in levels]
    est = richardson(w, THEORETICAL_ORDER["dissipated_energy"])
    assert conv["dissipated_energy_Nmm"] == est.value and conv["order"] == est.order
    assert out["discretisation_error_estimate"] == pytest.approx(
        w[0] / est.value - 1, rel=1e-14)
    assert conv["peak_displacement_mm"] > 0 and out["solver_converged"] is True
    if abs(out["discretisation_error_estimate"]) > 0.05:
        assert any("from the converged estimate" in x for x in out["warnings"])


def _error(capsys, *argv: str) -> tuple[int, str]:
    code = main(list(argv))
    lines = [ln for ln in capsys.readouterr().err.splitlines() if ln.strip()]
    assert len(lines) == 1, lines
    return code, lines[0]


@pytest.mark.parametrize("extra, code, message", [
    (["--levels", "3"], 1, "--levels applies with --convergence only"),
    (["--convergence", "--out", "OUT"], 1, "--out not used with --convergence"),
    (["--refine", "0"], 1, r"--refine must be a whole number in \[1, 8\], got 0"),
    (["--refine", "4", "--convergence", "--levels", "3"], 1, "would subdivide 16 times"),
    (["--convergence", "--levels", "4"], 2, "invalid choice"),
])
def test_fe_options_refused_in_one_line(capsys, small: str, tmp_path: Path, extra: list[str],
                                        code: int, message: str) -> None:
    extra = [str(tmp_path / "out") if x == "OUT" else x for x in extra]
    argv = ["fe", "--mesh", small, *CLAMP, "--load", "tip:1,0,0:300", *extra]
    got, line = _error(capsys, *argv)
    assert got == code and line.startswith("error:"), line
    assert __import__("re").search(message, line), line
    assert not (tmp_path / "out").exists()


def test_the_box_refuses_the_mesh_options(capsys) -> None:
    code, line = _error(capsys, "fe", "--model", "tip", "--refine", "2")
    assert code == 1 and "--refine applies to --mesh FILE only" in line


def test_modal_convergence_adds_the_converged_frequencies(capsys, small: str) -> None:
    argv = ["modal", "--mesh", small, *CLAMP, "--density", "2700", "--amplitudes", "1",
            "--convergence", "--json"]
    assert main(argv) == 0
    out = json.loads(capsys.readouterr().out)
    conv = out["frequency_convergence"]
    assert len(out["converged_linear_frequencies_Hz"]) == len(out["linear_frequencies_Hz"])
    assert conv["levels"][0]["linear_frequencies_Hz"] == out["linear_frequencies_Hz"]
    f = np.array([lv["linear_frequencies_Hz"] for lv in conv["levels"]])
    assert np.allclose(out["converged_linear_frequencies_Hz"], f[1] + (f[1] - f[0]) / 3,
                       rtol=1e-14)
    assert conv["error_estimate"][0] == pytest.approx(
        f[0, 0] / out["converged_linear_frequencies_Hz"][0] - 1, rel=1e-12)
