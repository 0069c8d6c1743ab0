"""What each mesh command built, printed and in its JSON as ``model`` (issue 34 item 5), on
``modal``, ``frf`` and ``validate`` as on ``fe``; and the Python API's forced response is
the command line's (issue 34 item 7: ``frf_study`` runs the very continuation ``frf --mesh``
runs, so it costs the same; profile in docs/ownmesh.md). Part: the new user's plate."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from microslip.cli.main import main

PLATE = Path(__file__).resolve().parent / "data" / "meshes" / "plate.msh"
CLAMP = ["--contact-set", "contact", "--clamp-set", "washer", "--normal-force", "8000",
         "--modulus", "210000", "--poisson-ratio", "0.3", "--friction", "0.5"]
STRUCTURE = ["--mesh", str(PLATE), *CLAMP, "--density", "7850", "--response-set", "response"]


def _washer(model: dict) -> None:
    s = model["sets"]["washer"]
    assert s["role"] == "preload" and s["faces"] == 4
    assert s["area_mm2"] == pytest.approx(101.823, rel=1e-4)
    assert s["pressure_MPa"] == pytest.approx(8000.0 / s["area_mm2"])
    assert model["open_after_preload"] == 38 and model["closed_after_preload"] == 25


def test_modal_prints_the_model_under_its_first_line(capsys: pytest.CaptureFixture[str]
                                                     ) -> None:
    assert main(["modal", *STRUCTURE, "--mode", "2", "--amplitudes", "1"]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert lines[0].startswith("mesh ") and lines[1].startswith("  model: 1 body, 63 contact")
    assert any(line.split()[:2] == ["preload", "washer"] and "101.823 mm^2" in line
               and "78.57 MPa" in line for line in lines)
    assert any(line.strip().startswith("amplitude limit") and "1 mm" in line
               for line in lines)


@pytest.mark.slow
def test_frf_prints_and_writes_the_model_and_frf_study_is_frf_mesh(
        capsys: pytest.CaptureFixture[str]) -> None:
    argv = ["frf", *STRUCTURE, "--mode", "2", "--force", "1", "--rom-modes", "10"]
    assert main([*argv, "--json"]) == 0
    cli = json.loads(capsys.readouterr().out)
    _washer(cli["model"])
    assert main(argv) == 0
    assert "  model: 1 body, 63 contact nodes" in capsys.readouterr().out
    import microslip as ms

    case = ms.StructureCase(str(PLATE), ms.MeshClamp(
        "contact", "washer", normal_force=8000.0, modulus=210000.0, poisson_ratio=0.3,
        friction=0.5), density=7850.0, mode=2, response_set="response", rom_modes=10)
    api = ms.frf_study(case, [1.0]).to_dict()
    (a,), (c,) = api["curves"], cli["curves"]
    np.testing.assert_array_equal(a["frequency_Hz"], c["frequency_Hz"])
    np.testing.assert_array_equal(a["amplitude_mm"], c["amplitude_mm"])
    assert a["damping_ratio"] == c["damping_ratio"] and a["peak_in_range"]
    # the same model; the command line's material also carries --density
    assert {k: v for k, v in api["model"].items() if k != "assembly"} == {
        k: v for k, v in cli["model"].items() if k != "assembly"}


@pytest.mark.slow
@pytest.mark.ccx
def test_validate_prints_and_writes_the_model_of_the_case_as_given(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    """The model of the case's own fixed contact (not the hard contact CalculiX compares):
    38 nodes open after the preload, as fe --mesh builds it."""
    code = main(["validate", "--mesh", str(PLATE), *CLAMP, "--load", "tip:0,1,0:20",
                 "--out", str(tmp_path / "v"), "--json", "--no-progress"])
    out = json.loads(capsys.readouterr().out)
    assert code in (0, 1)  # passing is CalculiX's business; the model is ours
    assert out["model"]["normal_contact"] == "fixed"
    _washer(out["model"])
