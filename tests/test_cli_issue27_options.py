"""Issue 27, items 6 and 7: the option table's promises on the command line (a default the
help promises holds, an option that changes nothing is refused, a case file's documented
default is used) and the case file that describes the user's own part."""

from __future__ import annotations

import numpy as np
import pytest
from conftest import one_line_error, run


@pytest.fixture
def own_law_file(tmp_path):
    """A two-DOF structure file whose one two-directional joint carries its own law (as
    ``reduce`` writes a contact node's circular Jenkins element)."""
    path = tmp_path / "own.npz"
    np.savez(path, M=np.eye(2), K=np.diag([4e6, 9e6]), joints=np.array([[[0, -1], [1, -1]]]),
             joint_stiffness=np.array([1e3]), joint_slip_force=np.array([1.0]))
    return str(path)


MODAL = ("--amplitude-range", "1e-3", "1e-2", "--amplitudes", "2", "--harmonics", "1")


def test_own_law_structure_runs_and_refuses_coupling(capsys, own_law_file):
    code, out, err = run(capsys, "modal", "--structure", own_law_file, *MODAL, "--json")
    assert code == 0, err
    for coupling in ("decoupled", "circular"):
        one_line_error(run(capsys, "modal", "--structure", own_law_file, "--coupling",
                           coupling, *MODAL), "--coupling", "own law", own_law_file)
    one_line_error(run(capsys, "frf", "--structure", own_law_file, "--coupling", "decoupled",
                       "--force", "1"), "--coupling", "own law")
    one_line_error(run(capsys, "modal", "--structure", own_law_file, "--joint", "jenkins",
                       "--joint-stiffness", "1", "--slip-force", "1", *MODAL),
                   "--joint, --joint-stiffness, --slip-force", "own law")


def test_own_law_structure_refuses_the_case_files_coupling(capsys, own_law_file, tmp_path):
    case = tmp_path / "c.toml"
    case.write_text(f'[structure]\nfile = "{own_law_file}"\ncoupling = "decoupled"\n')
    one_line_error(run(capsys, "modal", "--case", case, *MODAL),
                   "[structure] coupling of case", "own law")


def test_sweep_runs_on_the_template_with_the_cases_model(capsys, tmp_path):
    case = tmp_path / "clamp.toml"
    assert run(capsys, "case", "new", case)[0] == 0
    code, out, err = run(capsys, "sweep", "--case", case)
    assert code == 0, err
    assert "tip model" in out
    # the same numbers as the explicit --model tip
    code, explicit, _ = run(capsys, "sweep", "--case", case, "--model", "tip")
    assert code == 0
    strip = [line for line in out.splitlines() if "computed in" not in line]
    assert strip == [line for line in explicit.splitlines() if "computed in" not in line]


PART = """preset = "table1"
[material]
modulus = 70000
poisson_ratio = 0.33
[contact]
friction = 0.5
[clamping]
normal_force = 2000
[mesh]
file = "cantilever.inp"
contact_set = "contact"
clamp_set = "clamp"
density = 2700
response_set = "response"
normal_contact = "penalty"
normal_slope = 1e6
"""


def test_the_reports_structure_uses_the_cases_contact_law(tmp_path):
    import shutil
    import tomllib
    from pathlib import Path

    from microslip.case.model import parse_case
    from microslip.cli.main import build_parser
    from microslip.cli.modalcompare import case_argv

    shutil.copy(Path(__file__).resolve().parents[1] / "examples" / "cantilever.inp", tmp_path)
    argv = case_argv(parse_case(tomllib.loads(PART), str(tmp_path / "case.toml")), 4)
    assert argv is not None
    flags = dict(zip(argv, argv[1:], strict=False))
    assert flags["--normal-contact"] == "penalty" and flags["--normal-slope"] == "1000000.0"
    # and modal --mesh parses it (the study's own checks take it: no refusal of penalty)
    args = build_parser(argv).parse_args(argv)
    assert args.normal_contact == "penalty" and args.normal_slope == 1e6
    fixed = PART.replace('normal_contact = "penalty"\nnormal_slope = 1e6\n', "")
    argv = case_argv(parse_case(tomllib.loads(fixed), "dir/case.toml"), 4)
    assert argv is not None and "--normal-contact" not in argv and "--normal-slope" not in argv


def test_the_report_says_when_the_mesh_has_no_density(capsys, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "case.toml").write_text(PART.replace("density = 2700\n", ""))
    code, out, err = run(capsys, "report", "--case", "case.toml", "--no-fe", "--increments",
                         "100", "--out", "r.html")
    assert code == 0, err
    assert err.count("\n") == 1 and err.startswith("warning: ")
    assert "no density" in err and "bar of the case's clamp" in err
    page = (tmp_path / "r.html").read_text()
    assert "has no density" in page and "not this mesh" in page
