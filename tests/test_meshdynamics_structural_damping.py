"""``modal --mesh --damping-ratio ZETA`` (issue 34 item 9): a stated structural (modal)
damping ratio on every model, said in the JSON. The EPMC models get C = M Phi diag(2 zeta
omega) Phi^T M on their stuck modes; the full FE's QSMA adds zeta to its friction's ratio
(energy for energy). In the stuck limit every model's ratio is its own plus zeta."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest
from scipy.linalg import eigh

from microslip.cli.main import main
from microslip.dynamics.structure import Structure
from microslip.errors import ParameterError
from microslip.meshdynamics.case import modal_damping
from microslip.meshdynamics.frfstudy import FrfSettings
from microslip.meshdynamics.modalstudy import ModalSettings

PLATE = Path(__file__).resolve().parent / "data" / "meshes" / "plate.msh"
PLATE_CLI = ["--mesh", str(PLATE), "--contact-set", "contact", "--clamp-set", "washer",
             "--normal-force", "8000", "--modulus", "210000", "--poisson-ratio", "0.3",
             "--friction", "0.5", "--density", "7850", "--response-set", "response"]


def test_modal_damping_gives_every_stuck_mode_the_ratio() -> None:
    k = 1e6 * np.array([[2.0, -1.0, 0.0], [-1.0, 2.0, -1.0], [0.0, -1.0, 1.0]])
    m = np.diag([1.0, 2.0, 0.5])
    c0 = 1e-3 * k
    s = Structure(mass=m, damping=c0, stiffness=k, joints=(), output=np.eye(3)[0])
    d = modal_damping(s, 0.02)
    lam, phi = eigh(k, m)
    omega = np.sqrt(lam)
    np.testing.assert_allclose(phi.T @ (d.damping - c0) @ phi, np.diag(2 * 0.02 * omega),
                               atol=1e-9 * omega.max())
    assert modal_damping(s, 0.0) is s
    with pytest.raises(ParameterError, match=r"damping ratio must be in \[0, 1\)"):
        modal_damping(s, 1.0)
    with pytest.raises(ParameterError, match=r"damping ratio must be in \[0, 1\)"):
        ModalSettings(damping_ratio=-0.1)
    with pytest.raises(ParameterError, match=r"damping ratio must be in \[0, 1\)"):
        FrfSettings(damping_ratio=float("nan"))


def _all(capsys: pytest.CaptureFixture[str], *extra: str) -> dict:
    assert main(["modal", *PLATE_CLI, "--mode", "2", "--amplitudes", "2", "--solver", "all",
                 "--rom-modes", "20", "--json", *extra]) == 0
    return json.loads(capsys.readouterr().out)


@pytest.mark.slow
def test_every_model_of_modal_mesh_takes_the_structural_damping(
        capsys: pytest.CaptureFixture[str]) -> None:
    """The plate's in-plane mode: at the first amplitude (near stuck) every model's damping
    ratio rises by the 1 % given (the full FE's exactly, the EPMC models' to their mode's
    share), its frequency stays; the JSON says so."""
    bare, damped = _all(capsys), _all(capsys, "--damping-ratio", "0.01")
    assert bare["structural_damping_ratio"] == 0.0 and damped["structural_damping_ratio"] == 0.01
    assert set(damped["solvers"]) == {"fe", "rom", "interface", "joint"}
    for name, s in damped["solvers"].items():
        z0, z1 = bare["solvers"][name]["damping_ratio"][0], s["damping_ratio"][0]
        assert z1 - z0 == pytest.approx(0.01, rel=0.05 if name != "fe" else 1e-12), name
        f0, f1 = bare["solvers"][name]["frequency_Hz"][0], s["frequency_Hz"][0]
        assert f1 == pytest.approx(f0, rel=1e-4), name


@pytest.mark.slow
def test_damping_ratio_is_taken_by_frf_mesh_and_refused_out_of_range(
        capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["modal", *PLATE_CLI, "--damping-ratio", "1.5"]) == 1
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "damping ratio must be in [0, 1)" in err[0]
    assert main(["frf", *PLATE_CLI, "--mode", "2", "--force", "1", "--rom-modes", "10",
                 "--damping-ratio", "0.01", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["structural_damping_ratio"] == 0.01
    assert out["model"]["sets"]["washer"]["role"] == "preload"
