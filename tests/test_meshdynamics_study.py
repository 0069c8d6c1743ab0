"""The mesh structure's study in the library (meshdynamics, issue 27): the typed case, the
ROM built once per study, the command line's one builder of the case, and no command line
below cli/."""

from __future__ import annotations

import argparse
import json
import re
from pathlib import Path
from typing import Any

import numpy as np
import pytest

import microslip
from microslip.cli.main import main
from microslip.cli.meshstructure import structure_case
from microslip.errors import ParameterError
from microslip.fe.assembly import rigid_base
from microslip.fe.clamp import NORMAL_CONTACT_NAMES, MeshClamp
from microslip.fe.constants import DEFAULT_NORMAL_CONTACT, DEFAULT_NORMAL_SLOPE
from microslip.fe.examples import cantilever_mesh
from microslip.fe.meshfile import write_inp
from microslip.meshdynamics import reduce
from microslip.meshdynamics.case import StructureCase

CLAMP = {"contact_set": "contact", "clamp_set": "clamp", "normal_force": 2000.0,
         "modulus": 70000.0, "poisson_ratio": 0.33, "friction": 0.5, "stick_slope": 1e4}
FLAGS = ["--contact-set", "contact", "--clamp-set", "clamp", "--normal-force", "2000",
         "--friction", "0.5", "--stick-slope", "1e4", "--modulus", "70000",
         "--poisson-ratio", "0.33", "--density", "2700", "--response-set", "response"]


@pytest.fixture(scope="module")
def mesh(tmp_path_factory: pytest.TempPathFactory) -> str:
    path = tmp_path_factory.mktemp("study") / "cantilever_6x2x1.inp"
    return str(write_inp(cantilever_mesh(6, 2, 1), path))


@pytest.fixture
def builds(monkeypatch: pytest.MonkeyPatch) -> list[tuple[str | None, tuple[str, ...]]]:
    """Every build_rom call of the study: (response set, output sets)."""
    calls: list[tuple[str | None, tuple[str, ...]]] = []
    real = reduce.build_rom

    def counted(*args: Any, **kw: Any) -> Any:
        calls.append((kw.get("response_set"), tuple(kw.get("output_sets", ()))))
        return real(*args, **kw)

    monkeypatch.setattr(reduce, "build_rom", counted)
    return calls


def test_the_clamp_is_validated_once_with_one_line() -> None:
    c = MeshClamp(**CLAMP)  # type: ignore[arg-type]
    assert (c.normal_contact, c.normal_slope) == (DEFAULT_NORMAL_CONTACT, DEFAULT_NORMAL_SLOPE)
    for key, value, message in [("normal_force", -1.0, "normal_force must be > 0 (N), got -1.0"),
                                ("poisson_ratio", 0.5, "poisson_ratio must be in (-1, 0.5)"),
                                ("friction", float("nan"), "friction must be"),
                                ("normal_contact", "glued", "unknown normal contact 'glued'"),
                                ("contact_set", "", "contact_set must name a set")]:
        with pytest.raises(ParameterError, match=re.escape(message)):
            MeshClamp(**{**CLAMP, key: value})  # type: ignore[arg-type]


def test_the_clamps_contacts_are_the_solvers() -> None:
    from microslip.fe.builtin.normal import NORMAL_CONTACTS

    assert tuple(NORMAL_CONTACTS) == NORMAL_CONTACT_NAMES


def test_the_structure_case_is_validated() -> None:
    clamp = MeshClamp(**CLAMP)  # type: ignore[arg-type]
    case = StructureCase("x.inp", clamp, density=2700, mode=2)
    assert case.density == 2700.0 and isinstance(case.density, float)
    for kw, message in [({"density": 0.0}, "density must be > 0 kg/m^3 and finite"),
                        ({"mode": 51}, "mode must be in [1, 50]"),
                        ({"rom_modes": 0}, "rom_modes must be >= 1"),
                        ({"backbone": "glue"}, "unknown backbone 'glue'")]:
        with pytest.raises(ParameterError, match=re.escape(message)):
            StructureCase(**{"mesh": "x.inp", "clamp": clamp, "density": 2700.0, **kw})
    with pytest.raises(ParameterError, match="expected an Assembly or a MeshClamp"):
        StructureCase("x.inp", CLAMP, density=2700.0)  # type: ignore[arg-type]


def test_the_command_line_builds_the_case_once(mesh: str) -> None:
    """structure_case(args): the typed case from the namespace, its messages naming the
    option."""
    from microslip.cli.main import build_parser

    argv = ["modal", "--mesh", mesh, *FLAGS, "--mode", "2", "--rom-modes", "12"]
    case = structure_case(build_parser(argv).parse_args(argv))
    # the command line's --density is the material's (an assembly's bodies carry their own)
    expected = rigid_base(**CLAMP, density=2700.0)  # type: ignore[arg-type]
    assert case == StructureCase(mesh, expected, density=2700.0, mode=2,
                                 response_set="response", rom_modes=12)
    args = argparse.Namespace(**{**vars(build_parser(argv).parse_args(argv)),
                                 "normal_force": -5.0})
    with pytest.raises(ParameterError, match=re.escape("--normal-force must be finite and > 0 N")):
        structure_case(args)


def test_modal_all_builds_the_rom_once(mesh: str, builds: list, capsys: pytest.CaptureFixture[str]
                                       ) -> None:
    assert main(["modal", "--mesh", mesh, *FLAGS, "--mode", "2", "--amplitudes", "1",
                 "--amplitude-range", "1e-4", "1e-4", "--rom-modes", "10", "--harmonics",
                 "1", "--solver", "all", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert list(out["solvers"]) == ["fe", "rom", "interface", "joint"]
    assert out["amplitude_coordinate"] == "response_set"
    assert builds == [("response", ())]
    # each model's error and its cost side by side (issue 28 item 6): wall seconds, the
    # ROM's build counted for each model that runs on it
    for name, v in out["verdicts"].items():
        cost = out["solvers"][name]["cost_s"]
        assert v["cost_s"] == cost and cost > 0.0 and f"cost {cost:.3g} s" in v["verdict"]
    from microslip.meshdynamics.modalstudy import MESH_SOLVERS

    assert "pull-test model" in MESH_SOLVERS["joint"].help


@pytest.mark.slow
def test_frf_all_with_a_load_set_builds_the_rom_once(mesh: str, builds: list,
                                                     capsys: pytest.CaptureFixture[str]) -> None:
    """Both solvers, the response set's and the load set's rows: one build."""
    assert main(["frf", "--mesh", mesh, *FLAGS, "--mode", "2", "--load-set", "tip",
                 "--force", "0.01", "--rom-modes", "10", "--harmonics", "1", "--solver",
                 "all", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert list(out["solvers"]) == ["rom", "joint"] and out["load"]["set"] == "tip"
    assert builds == [("response", ("tip",))]


def test_the_load_sets_rows_equal_a_build_for_that_set(mesh: str) -> None:
    """Rom.outputs: the rows of a second set from the same build equal the rows of a build
    with that set as the response set (the fixed-interface modes' signs: the same solve)."""
    from microslip.meshdynamics.case import clamped

    model = clamped(StructureCase(mesh, MeshClamp(**CLAMP), density=2700.0))  # type: ignore[arg-type]
    one = reduce.build_rom(model, 2700.0, modes=10, response_set="response",
                           output_sets=("clamp", "response"))
    other = reduce.build_rom(model, 2700.0, modes=10, response_set="clamp")
    assert set(one.outputs) == {"clamp"} and other.output is not None
    np.testing.assert_allclose(one.outputs["clamp"], other.output, rtol=0.0,
                               atol=1e-12 * np.abs(other.output).max())
    assert not np.allclose(one.outputs["clamp"], one.output)  # a different set


def test_modal_structure_says_its_coordinate(tmp_path: Path,
                                             capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["modal", "--frequency", "100", "--modal-mass", "0.5", "--joint", "jenkins",
                 "--joint-stiffness", "1000", "--slip-force", "5", "--amplitude-range",
                 "0.001", "1", "--amplitudes", "3", "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["amplitude_coordinate"] == "modal"
    assert main(["modal", "--frequency", "100", "--modal-mass", "0.5", "--joint", "jenkins",
                 "--joint-stiffness", "1000", "--slip-force", "5", "--amplitude-range",
                 "0.001", "1", "--amplitudes", "3"]) == 0
    assert "q (mm)" in capsys.readouterr().out


def test_no_command_line_below_cli() -> None:
    """No argparse and no parse_args in the library layers the study runs in."""
    root = Path(microslip.__file__).parent
    for package in ("meshdynamics", "fe", "dynamics", "report", "reproduce"):
        for path in (root / package).rglob("*.py"):
            text = path.read_text()
            assert "argparse" not in text and "parse_args" not in text, path
