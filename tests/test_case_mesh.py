"""A case file describes a mesh of the user's own: [mesh] file and sets, [[load]] tables; fe
reads them as its --mesh, --contact-set, --clamp-set and --load, other commands note them."""

from __future__ import annotations

import json
import shutil
from pathlib import Path

import pytest

from microslip.cli.main import main

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"
CASE = """name = "cantilever"
[material]
modulus = 70000
poisson_ratio = 0.33
[contact]
friction = 0.5
stick_slope = 1e4
[clamping]
normal_force = 2000
[mesh]
file = "cantilever.inp"
contact_set = "contact"
clamp_set = "clamp"

[[load]]
set = "tip"
direction = [1, 0, 0]
amplitude = 300

[[load]]
set = "tip"
direction = [0, 1, 0]
amplitude = 40
phase_deg = 90
"""
FLAGS = ["--mesh", "cantilever.inp", "--contact-set", "contact", "--clamp-set", "clamp",
         "--modulus", "70000", "--poisson-ratio", "0.33", "--friction", "0.5",
         "--stick-slope", "1e4", "--normal-force", "2000", "--load", "tip:1,0,0:300",
         "--load", "tip:0,1,0:40:90"]


@pytest.fixture
def case_dir(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    shutil.copy(EXAMPLES / "cantilever.inp", tmp_path / "cantilever.inp")
    (tmp_path / "case.toml").write_text(CASE)
    monkeypatch.chdir(tmp_path)
    return tmp_path


def _json(capsys: pytest.CaptureFixture[str], *argv: str) -> dict:
    assert main(list(argv)) == 0
    out, _ = capsys.readouterr()
    return json.loads(out)


def test_case_file_equals_the_command_line(capsys: pytest.CaptureFixture[str],
                                           case_dir: Path) -> None:
    from_case = _json(capsys, "fe", "--case", "case.toml", "--json")
    from_flags = _json(capsys, "fe", *FLAGS, "--json")
    assert len(from_case["loads"]) == 2
    for key in ("dissipated_energy_Nmm", "peak_displacement_mm"):
        assert from_case[key] == from_flags[key]
    assert from_case["mesh"].endswith("cantilever.inp")


def test_other_commands_note_the_mesh_and_loads(capsys: pytest.CaptureFixture[str],
                                                case_dir: Path) -> None:
    assert main(["modal", "--case", "case.toml", "--frequency", "100", "--modal-mass", "1",
                 "--joint", "jenkins", "--joint-stiffness", "100", "--slip-force", "5",
                 "--amplitude-range", "0.01", "1", "--amplitudes", "3", "--json"]) == 0
    _, err = capsys.readouterr()
    assert "[mesh]" in err and "[[load]]" in err and "not read by modal" in err


@pytest.mark.parametrize(("table", "message"), [
    ('set = "tip"\ndirection = [1, 0, 0]\namplitud = 3', "unknown key amplitud; did you mean "
     "amplitude?"),
    ('set = "tip"\ndirection = [1, 0]\namplitude = 3', "direction must be [DX, DY, DZ]"),
    ('set = "tip"\namplitude = 3', "give direction"),
    ('set = "tip"\ndirection = [0, 0, 0]\namplitude = 3', "zero length"),
])
def test_bad_load_tables(capsys: pytest.CaptureFixture[str], case_dir: Path, table: str,
                         message: str) -> None:
    text = CASE.split("[[load]]")[0] + "[[load]]\n" + table + "\n"
    (case_dir / "bad.toml").write_text(text)
    assert main(["fe", "--case", "bad.toml", "--json"]) == 1
    _, err = capsys.readouterr()
    assert message in err and len(err.strip().splitlines()) == 1
