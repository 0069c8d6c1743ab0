"""``microslip fe --mesh FILE``: the box as a mesh file equals the built-in box, planar loads
on the cantilever, outputs, and every bad input refused in one line with nothing written."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from microslip.cli.main import main

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"
BOX = str(EXAMPLES / "box_table1_24x4x1.inp")
CANTILEVER = str(EXAMPLES / "cantilever.inp")
#: The Table 1 clamp, as the box takes it from its preset.
TABLE1 = ["--normal-force", "445", "--friction", "0.8", "--modulus", "68947",
          "--poisson-ratio", "0.3"]
CANT = ["--mesh", CANTILEVER, "--contact-set", "contact", "--clamp-set", "clamp",
        "--normal-force", "2000", "--friction", "0.5", "--stick-slope", "1e4",
        "--normal-contact", "penalty", "--normal-slope", "1e6", "--modulus", "70000",
        "--poisson-ratio", "0.33"]


def _json(capsys: pytest.CaptureFixture[str], *argv: str) -> dict:
    assert main(["fe", *argv, "--json"]) == 0
    out, _ = capsys.readouterr()
    return json.loads(out)


def _error(capsys: pytest.CaptureFixture[str], *argv: str) -> tuple[int, str]:
    code = main(["fe", *argv])
    _, err = capsys.readouterr()
    lines = [ln for ln in err.splitlines() if ln.strip()]
    assert len(lines) == 1, err
    return code, lines[0]


@pytest.mark.parametrize("model", ["tip", "centre"])
def test_box_as_mesh_file_equals_builtin_box(capsys: pytest.CaptureFixture[str],
                                             model: str) -> None:
    """The issue's contract: the box written as a mesh file, at equal increments (the
    paper's load step, 50 substeps), gives the built-in box's W and d0 to 1e-9."""
    box = _json(capsys, "--model", model, "--mesh", "24x4x1")
    own = _json(capsys, "--mesh", BOX, "--contact-set", "contact", "--clamp-set", "clamp",
                *TABLE1, "--load", f"{model}:1,0,0:267", "--history", "paper")
    assert own["dissipated_energy_Nmm"] == pytest.approx(box["dissipated_energy_Nmm"],
                                                         rel=1e-9)
    assert own["peak_displacement_mm"] == pytest.approx(box["peak_displacement_mm"], rel=1e-9)
    assert own["loads"][0]["work_Nmm"] == own["dissipated_energy_Nmm"]


def test_planar_loads_on_the_cantilever(capsys: pytest.CaptureFixture[str],
                                        tmp_path: Path) -> None:
    """Two loads at 90 degrees: W is the sum of the loads' works over the settled cycle, each
    load has its loop, and result.json, the loop CSVs and the plot are written."""
    out = _json(capsys, *CANT, "--load", "tip:1,0,0:300", "--load", "tip:0,1,0:40:90",
                "--out", str(tmp_path / "run"), "--plot", str(tmp_path / "loops.png"))
    works = [ld["work_Nmm"] for ld in out["loads"]]
    assert len(works) == 2 and out["settled"]
    assert out["dissipated_energy_Nmm"] == pytest.approx(sum(works), rel=1e-12)
    assert out["dissipated_energy_Nmm"] > 0 and out["clamp_portion"] == "whole"
    saved = json.loads((tmp_path / "run" / "result.json").read_text())
    assert saved["dissipated_energy_Nmm"] == out["dissipated_energy_Nmm"]
    assert (tmp_path / "run" / "loop_2_tip.csv").exists()
    assert (tmp_path / "loops.png").stat().st_size > 0


@pytest.mark.parametrize(("argv", "message"), [
    (["--clamp-set", "clmp"], "no set named 'clmp' (the clamp set); did you mean 'clamp'?"),
    (["--contact-set", "response"], "the body is not held after clamping"),
    (["--load", "tip:0,0,0:10"], "zero length"),
    (["--load", "tip:1,0,0:-3"], "amplitude must be > 0 N"),
    (["--load", "nowhere:1,0,0:3"], "no set named 'nowhere'"),
    (["--model", "tip"], "--model applies to the box"),
    (["--pressure-law", "parabolic"], "--pressure-law applies to the box"),
    (["--cycles", "3"], "--cycles applies to --solver calculix"),
])
def test_bad_input_is_one_line(capsys: pytest.CaptureFixture[str], tmp_path: Path,
                               argv: list[str], message: str) -> None:
    base = dict(zip(CANT[::2], CANT[1::2], strict=True))
    given = dict(zip(argv[::2], argv[1::2], strict=True))
    merged = [x for k, v in {**base, **given}.items() if k != "--load" for x in (k, v)]
    load = given.get("--load", "tip:1,0,0:300")
    out = tmp_path / "out"
    code, line = _error(capsys, *merged, "--load", load, "--out", str(out))
    assert code == 1 and message in line
    assert not out.exists() or not any(out.iterdir())


def test_missing_values_are_named(capsys: pytest.CaptureFixture[str]) -> None:
    code, line = _error(capsys, "--mesh", CANTILEVER, "--load", "tip:1,0,0:3")
    assert code == 2  # required options left out: a usage mistake
    for flag in ("--contact-set", "--clamp-set", "--normal-force", "--friction", "--modulus",
                 "--poisson-ratio"):
        assert flag in line


def test_mesh_options_are_refused_on_the_box(capsys: pytest.CaptureFixture[str]) -> None:
    code, line = _error(capsys, "--model", "tip", "--contact-set", "contact")
    assert code == 1 and "--contact-set applies to --mesh FILE only" in line


def test_a_missing_file_is_a_usage_error(capsys: pytest.CaptureFixture[str]) -> None:
    code, line = _error(capsys, "--mesh", "no_such_mesh.inp")
    assert code == 2 and "no_such_mesh.inp" in line


@pytest.mark.ccx
@pytest.mark.slow
def test_validate_a_mesh_against_calculix(capsys: pytest.CaptureFixture[str],
                                          tmp_path: Path) -> None:
    """``validate --mesh FILE``: the built-in solver and CalculiX on the same mesh, loads and
    cycles; W within the 3 % of the issue on a 12x3x1 cantilever under a lateral load, and
    the verdict (exit code, ``passed``) follows the stated tolerances."""
    from microslip.fe.examples import cantilever_mesh
    from microslip.fe.meshfile import write_inp

    mesh = str(write_inp(cantilever_mesh(12, 3, 1), tmp_path / "c.inp"))
    argv = ["validate", "--mesh", mesh, "--contact-set", "contact", "--clamp-set", "clamp",
            "--normal-force", "2000", "--friction", "0.5", "--stick-slope", "1e4",
            "--normal-slope", "1e6", "--modulus", "70000", "--poisson-ratio", "0.33",
            "--load", "tip:0,1,0:50", "--out", str(tmp_path / "v"), "--json"]
    code = main(argv)
    out = json.loads(capsys.readouterr().out)
    b, c = out["builtin"], out["calculix"]
    assert b["cycles"] == c["cycles"] and b["dof"] == c["dof"]
    dw = c["dissipated_energy_Nmm"] / b["dissipated_energy_Nmm"] - 1
    assert out["relative_difference"]["dissipated_energy_Nmm"] == pytest.approx(dw, rel=1e-12)
    assert abs(dw) < 0.03
    assert code == (0 if out["passed"] else 1)
    assert (tmp_path / "v" / "validation_mesh.json").exists()


def test_validate_a_mesh_refuses_the_box_options(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["validate", "--mesh", CANTILEVER, "--model", "tip", "--out", "x"]) == 1
    err = capsys.readouterr().err
    assert "--model applies to the box" in err and len(err.strip().splitlines()) == 1
