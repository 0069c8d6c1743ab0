"""``microslip report --case FILE``: a case with a mesh of the structure ([mesh] file, sets,
density, mode, response_set) gets the section "Damping of the structure's mode": every solver
of ``modal --mesh`` side by side with the verdicts, the same numbers in ``--json``
(issue 23, item 5)."""

from __future__ import annotations

import json
import re
from pathlib import Path

import pytest

from microslip.case.model import parse_case
from microslip.cli.main import main
from microslip.fe.clamp import MeshClamp
from microslip.fe.examples import cantilever_mesh
from microslip.fe.meshfile import write_inp
from microslip.meshdynamics.case import StructureCase
from microslip.report.structure import case_structure

CASE = """name = "cantilever on its clamp"
preset = "table1"
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
density = 2700
mode = 2
response_set = "response"
"""


def test_the_case_gives_the_structure_of_modal_mesh() -> None:
    """The case file's [mesh] as the library's typed case (no command line forged): the
    assembly ``modal --case`` builds, the material carrying [mesh] density as there."""
    from dataclasses import replace

    from microslip.fe.assembly import as_assembly

    case = case_structure(parse_case(_toml(CASE), "dir/case.toml"))
    assert case is not None and case.mesh.endswith("dir/cantilever.inp")
    clamp = as_assembly(MeshClamp("contact", "clamp", normal_force=2000.0, modulus=70000.0,
                                  poisson_ratio=0.33, friction=0.5, stick_slope=1e4))
    clamp = replace(clamp, materials=(replace(clamp.materials[0], density=2700.0),))
    assert case == StructureCase(case.mesh, clamp, density=2700.0, mode=2,
                                 response_set="response")
    # no density: no structure section
    assert case_structure(parse_case(_toml(CASE.replace("density = 2700\n", "")))) is None


def _toml(text: str) -> dict:
    import tomllib

    return tomllib.loads(text)


@pytest.mark.parametrize(("value", "message"), [("mode = 0", "mesh.mode must be a whole "
                                                  "number in [1, 50]"),
                                                 ("density = -2",
                                                  "mesh.density must be a finite number > 0")])
def test_bad_structure_keys_are_refused(value: str, message: str) -> None:
    text = re.sub(r"^" + value.split(" ")[0] + " = .*$", value, CASE, flags=re.M)
    with pytest.raises(Exception, match=re.escape(message)):
        parse_case(_toml(text))


@pytest.mark.slow
def test_report_shows_the_structure_section(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
                                            capsys: pytest.CaptureFixture[str]) -> None:
    monkeypatch.chdir(tmp_path)
    write_inp(cantilever_mesh(12, 3, 1), tmp_path / "cantilever.inp")
    (tmp_path / "case.toml").write_text(CASE)
    assert main(["report", "--case", "case.toml", "--out", "report.html", "--json",
                 "--no-fe", "--no-progress"]) == 0
    out = json.loads(capsys.readouterr().out)
    s = out["structure"]
    assert s["mode"] == 2 and s["label"] == "bending in the contact plane"
    assert set(s["solvers"]) >= {"fe", "rom"} and "rom" in s["verdicts"]
    assert len(s["solvers"]["fe"]["amplitude_mm"]) == 6
    verdict = s["verdicts"]["rom"]["verdict"]
    page = (tmp_path / "report.html").read_text()
    section = page[page.index("<h2>Damping of the structure's mode</h2>"):]
    assert verdict.replace("'", "&#x27;") in section
    assert section.count('<img src="data:image/svg+xml;base64,') == 1


def test_a_case_without_a_structure_says_so(tmp_path: Path,
                                            capsys: pytest.CaptureFixture[str]) -> None:
    case = tmp_path / "case.toml"
    case.write_text('preset = "table1"\n')
    assert main(["report", "--case", str(case), "--out", str(tmp_path / "r.html"), "--json",
                 "--no-fe", "--no-progress"]) == 0
    assert json.loads(capsys.readouterr().out)["structure"] is None
    assert "no structure to report" in (tmp_path / "r.html").read_text()


def test_write_report_from_python_computes_the_structure_section(
        tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """write_report() from Python asks the case itself for its structure section (no
    command-line callback); structure=False leaves it out."""
    from microslip.case.model import load_case
    from microslip.report import ReportSettings, compute, write_report

    seen: list[object] = []

    def section(case: object) -> None:
        seen.append(case)

    monkeypatch.setattr(compute, "structure_section", section)
    (tmp_path / "case.toml").write_text('preset = "table1"\n')
    case = load_case(str(tmp_path / "case.toml"))
    settings = ReportSettings(fe_points=False)
    write_report(case, tmp_path / "r.html", settings, progress=False)
    assert seen == [case]
    write_report(case, tmp_path / "s.html", settings, progress=False, structure=False)
    assert seen == [case]
