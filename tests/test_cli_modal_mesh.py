"""``microslip modal --mesh FILE``: stuck and free modes of the user's mesh, full-FE QSMA
(--solver fe) and EPMC on the contact-node ROM (--solver rom) on the same amplitudes, and the
bad inputs of issue 23 refused in one line."""

from __future__ import annotations

import json
import math

import pytest

from microslip.cli.main import main
from microslip.fe.examples import cantilever_mesh
from microslip.fe.meshfile import write_inp

BASE = ["--contact-set", "contact", "--clamp-set", "clamp", "--normal-force", "2000",
        "--friction", "0.5", "--stick-slope", "1e4", "--modulus", "70000",
        "--poisson-ratio", "0.33", "--response-set", "response"]


@pytest.fixture(scope="module")
def mesh(tmp_path_factory: pytest.TempPathFactory) -> str:
    path = tmp_path_factory.mktemp("modal") / "cantilever_12x3x1.inp"
    return str(write_inp(cantilever_mesh(12, 3, 1), path))


def _json(capsys: pytest.CaptureFixture[str], *argv: str) -> dict:
    assert main(["modal", *argv, "--json"]) == 0
    out, _ = capsys.readouterr()
    return json.loads(out)


def test_fe_and_rom_side_by_side(capsys: pytest.CaptureFixture[str], mesh: str) -> None:
    """In-plane bending of the cantilever: the ROM keeps the full FE's stuck frequencies (to
    1e-6 with 60 fixed-interface modes), both curves start at the stuck frequency and soften
    while the damping ratio rises, and at the first slipping amplitude they agree within a
    few percent (the ROM's EPMC against the full FE's QSMA)."""
    argv = ["--mesh", mesh, *BASE, "--density", "2700", "--mode", "2", "--amplitudes", "3"]
    fe = _json(capsys, *argv, "--solver", "fe")
    rom = _json(capsys, *argv, "--solver", "rom")
    assert len(fe["linear_frequencies_Hz"]) >= 6 and len(fe["free_frequencies_Hz"]) >= 6
    assert fe["label"] == "bending in the contact plane"
    stuck = fe["linear_frequencies_Hz"][1]
    assert rom["rom_frequencies_Hz"][1] == pytest.approx(stuck, rel=1e-6)
    assert all(f <= stuck * (1 + 1e-6) for f in fe["frequency_Hz"] + rom["frequency_Hz"])
    assert fe["damping_ratio"][-1] > fe["damping_ratio"][0] > 0
    assert rom["damping_ratio"][-1] > rom["damping_ratio"][0] > 0
    # the first amplitude: the same force grid, mapped through the stuck mode for the ROM
    assert rom["amplitude_mm"][0] == pytest.approx(fe["amplitude_mm"][0], rel=0.02)
    assert rom["frequency_Hz"][0] == pytest.approx(fe["frequency_Hz"][0], rel=0.005)
    assert rom["damping_ratio"][0] == pytest.approx(fe["damping_ratio"][0], rel=0.1)
    # free contact: the in-plane rigid motions are 0 Hz, every free mode below a stuck one
    assert sum(f < 1.0 for f in fe["free_frequencies_Hz"]) == 3
    assert not any(math.isnan(z) for z in fe["damping_ratio"])


@pytest.mark.parametrize(("extra", "message"), [
    (["--density", "2700", "--mode", "51"], "--mode must be in [1, 50]"),
    (["--density", "2700", "--frequency", "100"], "--frequency not used with --mesh"),
    (["--density", "2700", "--harmonics", "5"],
     "--harmonics applies to --solver rom or interface or joint only"),
    (["--density", "-1"], "--density must be > 0"),
])
def test_bad_input_is_one_line(capsys: pytest.CaptureFixture[str], mesh: str,
                               extra: list[str], message: str) -> None:
    assert main(["modal", "--mesh", mesh, *BASE, *extra]) == 1
    _, err = capsys.readouterr()
    assert message in err and len(err.strip().splitlines()) == 1


def test_a_required_option_left_out_is_a_usage_mistake(capsys: pytest.CaptureFixture[str],
                                                       mesh: str) -> None:
    assert main(["modal", "--mesh", mesh, *BASE]) == 2
    _, err = capsys.readouterr()
    assert "needs --density KG/M3" in err and len(err.strip().splitlines()) == 1


def test_mesh_options_without_a_mesh_are_refused(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["modal", "--frequency", "100", "--modal-mass", "1", "--joint", "jenkins",
                 "--joint-stiffness", "100", "--slip-force", "5", "--amplitude-range", "0.01",
                 "1", "--density", "2700"]) == 1
    _, err = capsys.readouterr()
    assert "--density applies to modal --mesh FILE only" in err


@pytest.mark.slow
def test_whole_joint_solver(capsys: pytest.CaptureFixture[str], mesh: str) -> None:
    """--solver joint: the same JSON keys, its backbone (force_N against displacement_mm,
    starting at the stuck interface stiffness), its stuck frequency 3.6 % above the full
    FE's (the rigid interface stiffens the clamp) and an EPMC that softens from there;
    out-of-plane bending says in a warning that the joint does not see its damping."""
    argv = ["--mesh", mesh, *BASE, "--density", "2700", "--amplitudes", "2",
            "--solver", "joint", "--harmonics", "3"]
    out = _json(capsys, *argv, "--mode", "2")
    for key in ("amplitude_mm", "frequency_Hz", "damping_ratio", "linear_frequencies_Hz",
                "free_frequencies_Hz", "warnings"):
        assert key in out
    joint = out["joint"]
    assert joint["source"] == "mode" and out["warnings"] == []
    assert joint["force_N"][0] == 0 and joint["displacement_mm"][0] == 0
    assert joint["force_N"][1] / joint["displacement_mm"][1] == pytest.approx(
        joint["stuck_stiffness_N_per_mm"], rel=1e-9)
    stuck = out["linear_frequencies_Hz"][1]
    assert joint["stuck_frequency_Hz"] == pytest.approx(stuck * (1 + joint[
        "stuck_frequency_error"]), rel=1e-12)
    assert 0.03 < joint["stuck_frequency_error"] < 0.042
    assert out["frequency_Hz"][1] < out["frequency_Hz"][0] < joint["stuck_frequency_Hz"]
    assert out["damping_ratio"][1] > out["damping_ratio"][0] > 0
    out1 = _json(capsys, *argv, "--mode", "1")
    assert out1["joint"]["source"] == "pull"
    assert any("does not load the interface as a whole" in w for w in out1["warnings"])


def test_backbone_is_the_joint_solver_s_option(capsys: pytest.CaptureFixture[str],
                                               mesh: str) -> None:
    assert main(["modal", "--mesh", mesh, *BASE, "--density", "2700", "--backbone",
                 "tip"]) == 1
    _, err = capsys.readouterr()
    assert "--backbone applies to --solver joint only" in err
    assert len(err.strip().splitlines()) == 1
