"""``microslip fe --solver builtin`` (the default): same JSON as ``loop`` and the CalculiX path."""

from __future__ import annotations

import json

import numpy as np
import pytest
from conftest import run

from microslip import closedform as cf
from microslip import preset
from microslip.cli.main import main

P = preset("table1")
EA, Q = P.axial_stiffness, P.friction_per_length
EXACT = {
    "tip": (cf.tip_displacement(267.0, EA, Q), cf.tip_dissipated_energy(267.0, EA, Q)),
    "centre": (cf.centre_displacement(267.0, EA, Q), cf.centre_dissipated_energy(267.0, EA, Q)),
}


def quiet_json(capsys, *argv: str) -> dict:
    """The shared runner, for a command that must exit 0 and warn of nothing (the caller
    gives ``--json``): its JSON."""
    code, out, err = run(capsys, *argv)
    assert code == 0 and err == ""
    return json.loads(out)


@pytest.mark.parametrize(("model", "tol"), [("tip", 0.01), ("centre", 0.03)])
def test_builtin_default_matches_closed_form(capsys, model, tol):
    data = quiet_json(capsys, "fe", "--model", model, "--preset", "table1", "--json")
    d0, wd = EXACT[model]
    assert data["solver"] == "builtin" and data["converged"] is True
    assert abs(data["peak_displacement_mm"] / d0 - 1) < tol
    assert abs(data["dissipated_energy_Nmm"] / wd - 1) < tol
    # secant U (the default): the closed-form loss factor is 4 / (3 pi) for both load cases
    # (docs/validation.md); the FE loop's eta is off by its W_d and d0 errors
    assert data["strain_energy_definition"] == "secant"
    assert abs(data["loss_factor"] / (4 / (3 * 3.141592653589793)) - 1) < 2 * tol


def test_keys_are_those_of_loop_and_of_calculix(capsys):
    data = quiet_json(capsys, "fe", "--model", "centre", "--mesh", "tiny", "--json")
    loop = quiet_json(capsys, "loop", "--model", "centre", "--json", "--increments", "20")
    # the 1-D model's contact and validity warnings are its own: the FE has its stick slope
    # in "options" and is the reference the warnings point to
    assert set(loop) - {"contact", "warnings"} <= set(data)
    for key in ("dof", "wall_s", "converged", "iterations", "loop_closure"):
        assert key in data
    assert set(data["slip_length_by_domain_mm"]) == {"tension", "compression"}
    # 50 substeps over 1.25 s: the loop t = 0.25..1.25 s has 41 points, as with CalculiX
    assert len(data["loop"]["force_N"]) == 41 and data["increments"] == 50


def test_out_keeps_the_result(capsys, tmp_path):
    data = quiet_json(capsys, "fe", "--model", "tip", "--mesh", "tiny", "--out",
                      str(tmp_path / "job"), "--json")
    saved = json.loads((tmp_path / "job" / "result.json").read_text(encoding="utf-8"))
    assert saved["dissipated_energy_Nmm"] == data["dissipated_energy_Nmm"]


def test_needs_no_calculix(capsys, monkeypatch, tmp_path):
    monkeypatch.setenv("PATH", str(tmp_path / "empty"))
    data = quiet_json(capsys, "fe", "--model", "tip", "--mesh", "tiny", "--json")
    assert data["converged"] is True


def test_out_writes_result_json_and_a_vtu_series_read_back(capsys, tmp_path):
    """--out: result.json and one VTU per increment (+ .pvd); the displacement in the VTU at
    the first peak, averaged over the loaded end face with the consistent-load weights and
    measured from the clamped state, is the loop's first displacement."""
    meshio = pytest.importorskip("meshio")
    from microslip.fe.examples import box_hexmesh
    from microslip.fe.hexmesh import face_load

    out = tmp_path / "run"
    data = quiet_json(capsys, "fe", "--model", "tip", "--mesh", "tiny", "--out", str(out),
                      "--json")
    assert json.loads((out / "result.json").read_text())["dissipated_energy_Nmm"] == \
        data["dissipated_energy_Nmm"]
    vtus = sorted(out.glob("fe_tip_*.vtu"))
    assert len(vtus) == data["increments"] + 1
    pvd = (out / "fe_tip.pvd").read_text()
    assert pvd.count("<DataSet") == len(vtus) and 'timestep="1.25"' in pvd
    mesh = box_hexmesh(P, (8, 2, 1))
    ids, w, _ = face_load(mesh, mesh.faces("tip"))
    clamped, peak = meshio.read(vtus[0]), meshio.read(vtus[10])  # t = 0 and 0.25 s
    d = (peak.point_data["displacement"][ids, 0] - clamped.point_data["displacement"][ids, 0])
    assert d @ w == pytest.approx(data["loop"]["displacement_mm"][0], rel=1e-9)
    bottom = mesh.node_sets["contact"]
    assert set(np.unique(clamped.point_data["contact_status"][bottom])) == {1}
    status = peak.point_data["contact_status"]
    assert set(np.unique(status[bottom])) == {1, 2} and np.all(
        np.delete(status, bottom) == -1)
    slipping = status == 2
    assert np.all(np.linalg.norm(peak.point_data["contact_slip"][slipping], axis=1) > 0)


@pytest.mark.parametrize("extreme", [["--length", "1e-6"], ["--thickness", "1e6"],
                                     ["--thickness", "1e-9"]])
def test_extreme_geometry_is_one_line_not_a_traceback(capsys, extreme):
    code = main(["fe", "--model", "tip", "--mesh", "tiny", *extreme])
    out, err = capsys.readouterr()
    lines = [ln for ln in err.splitlines() if not ln.startswith("warning: ")]
    assert code == 1 and "Traceback" not in err and "dissipated energy" not in out
    assert len(lines) <= 1  # one error line, or the non-convergence said on stdout
    assert lines or "not converged" in out
