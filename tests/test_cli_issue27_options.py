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


@pytest.mark.slow
def test_own_law_structure_runs(capsys, own_law_file):
    code, _, err = run(capsys, "modal", "--structure", own_law_file, *MODAL, "--json")
    assert code == 0, err


def test_own_law_structure_refuses_coupling(capsys, own_law_file):
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
    """The report's structure section builds its case from [mesh] with the case's contact
    law (penalty and its slope when given; the clamp's defaults otherwise)."""
    import shutil
    from pathlib import Path

    import tomllib

    from microslip.case.model import parse_case
    from microslip.fe.constants import DEFAULT_NORMAL_CONTACT, DEFAULT_NORMAL_SLOPE
    from microslip.report.structure import case_structure

    shutil.copy(Path(__file__).resolve().parents[1] / "examples" / "cantilever.inp", tmp_path)
    structure = case_structure(parse_case(tomllib.loads(PART), str(tmp_path / "case.toml")))
    assert structure is not None
    assert structure.clamp.normal_contact == "penalty" and structure.clamp.normal_slope == 1e6
    fixed = PART.replace('normal_contact = "penalty"\nnormal_slope = 1e6\n', "")
    assert fixed != PART
    structure = case_structure(parse_case(tomllib.loads(fixed), str(tmp_path / "case.toml")))
    assert structure is not None
    assert structure.clamp.normal_contact == DEFAULT_NORMAL_CONTACT == "fixed"
    assert structure.clamp.normal_slope == DEFAULT_NORMAL_SLOPE


@pytest.mark.slow
def test_the_report_says_when_the_mesh_has_no_density(capsys, tmp_path, monkeypatch):
    """A mesh case without a density: the report is still about the part (issue 34: no bar
    of the template in its place) and says in one warning that its modes are left out."""
    import shutil

    monkeypatch.chdir(tmp_path)
    shutil.copy(ROOT / "examples" / "cantilever.inp", tmp_path / "cantilever.inp")
    (tmp_path / "case.toml").write_text(PART.replace("density = 2700\n", ""))
    code, out, err = run(capsys, "report", "--case", "case.toml", "--no-fe", "--increments",
                         "100", "--out", "r.html")
    assert code == 0, err
    assert "1 warning" in out
    page = (tmp_path / "r.html").read_text()
    assert "cantilever.inp" in page and "its modes and their damping are not reported" in page
    assert "the modes of the part and their damping are left out" in page


# -- the case file describes the part -------------------------------------------------------

ROOT = __import__("pathlib").Path(__file__).resolve().parents[1]
LOAD = '\n[[mesh.load]]\nset = "tip"\ndirection = [1.0, 0.0, 0.0]\namplitude = 100.0\n'


def test_docs_list_every_mesh_key():
    from microslip.case.schema import KEYS, MESH_LOAD_KEYS

    text = (ROOT / "docs" / "casefile.md").read_text()
    for key in KEYS:
        if key.section == "mesh":
            assert f"| `{key.name}` |" in text, key.name
    for name in MESH_LOAD_KEYS:
        assert f"`{name}`" in text


def test_mesh_loads_beside_the_templates_load_section(capsys, tmp_path):
    """The template's [load] table and the mesh's loads in one file (issue 27: "Cannot
    overwrite a value" with [[load]])."""
    from microslip.case.model import load_case

    case = tmp_path / "c.toml"
    assert run(capsys, "case", "new", case)[0] == 0
    case.write_text(case.read_text() + LOAD)
    loaded = load_case(case)
    assert [(ld.set, ld.amplitude) for ld in loaded.mesh_loads] == [("tip", 100.0)]
    both = (LOAD.replace("mesh.load", "load")
            + LOAD.replace("[[mesh.load]]", "[mesh]\n[[mesh.load]]"))
    (tmp_path / "both.toml").write_text(both)
    one_line_error(run(capsys, "case", "check", tmp_path / "both.toml"), "not both")


@pytest.fixture
def part(capsys, tmp_path, monkeypatch):
    """``case new --mesh`` on the cantilever of examples/, with a load and a density."""
    import shutil

    monkeypatch.chdir(tmp_path)
    shutil.copy(ROOT / "examples" / "cantilever.inp", tmp_path / "cantilever.inp")
    code, out, err = run(capsys, "case", "new", "--mesh", "cantilever.inp", "part.toml")
    assert code == 0 and err == "" and "part.toml" in out
    return tmp_path / "part.toml"


def test_case_new_mesh_lists_the_sets_and_check_shows_the_part(capsys, part):
    text = part.read_text()
    assert "node sets: clamp, contact, response, tip" in text
    assert 'file = "cantilever.inp"' in text and 'contact_set = "contact"' in text
    assert 'clamp_set = "clamp"' in text and 'response_set = "response"' in text
    assert "\npreset =" not in text and "\n[geometry]" not in text
    assert "# [[mesh.load]]" in text and "[load]" not in text
    code, out, _ = run(capsys, "case", "check", part)
    assert code == 0
    assert "the part is the mesh " in out and "cantilever.inp (its geometry" in out
    assert "no preset bar" in out
    assert "mesh.contact_set" in out and "no [[mesh.load]] tables" in out
    assert "no density" in out
    assert "750" not in out and "amplitude" not in out.replace("load", "")  # no bar, no F0
    part.write_text(text.replace("# density =", "density = 2700.0") + LOAD)
    code, out, _ = run(capsys, "case", "check", part)
    assert "load 1: 100 N on set tip along (1, 0, 0)" in out and "no density" not in out


def test_fe_runs_on_the_written_case_as_on_its_options(capsys, part):
    import json

    part.write_text(part.read_text() + LOAD)
    code, out, err = run(capsys, "fe", "--case", part, "--json")
    assert code == 0, err
    by_case = json.loads(out)
    code, out, err = run(capsys, "fe", "--mesh", "cantilever.inp", "--contact-set", "contact",
                         "--clamp-set", "clamp", "--modulus", "68947", "--poisson-ratio",
                         "0.3", "--friction", "0.8", "--normal-force", "445", "--stick-slope",
                         "1e4", "--load", "tip:1,0,0:100", "--json")
    assert code == 0, err
    assert by_case["dissipated_energy_Nmm"] == json.loads(out)["dissipated_energy_Nmm"]


@pytest.mark.parametrize("command", ["modal", "frf", "reduce", "validate", "fe"])
def test_every_mesh_command_reads_the_mesh_section(capsys, part, command):
    from microslip.case.options import parse_args
    from microslip.cli.main import build_parser

    part.write_text(part.read_text().replace("# density =", "density = 2700.0")
                    .replace("# normal_contact = \"fixed\"", "normal_contact = \"penalty\"")
                    + LOAD)
    extra = {"frf": ["--force", "1"], "validate": ["--out", "v"], "reduce": [],
             "modal": [], "fe": []}[command]
    argv = [command, "--case", str(part), *extra]
    args = parse_args(build_parser(argv), argv)
    mesh = args.mesh[0] if command == "validate" else args.mesh
    assert mesh.endswith("cantilever.inp") and args.contact_set == "contact"
    assert args.clamp_set == "clamp" and args.normal_contact == "penalty"
    if command in ("modal", "frf", "reduce"):
        assert args.density == 2700.0 and args.response_set == "response"
    if command in ("fe", "validate"):
        from microslip.fe.meshload import MeshLoad

        assert [MeshLoad.parse(x) for x in args.load] == [MeshLoad("tip", (1, 0, 0), 100)]
    capsys.readouterr()


def test_another_structure_leaves_the_mesh_section_unread(capsys, part, own_law_file):
    from microslip.case.options import parse_args
    from microslip.cli.main import build_parser

    argv = ["modal", "--case", str(part), "--structure", own_law_file, "--amplitude-range",
            "1e-3", "1e-2"]
    args = parse_args(build_parser(argv), argv)
    assert args.mesh is None and args.contact_set is None
    assert "[mesh] not read by modal" in capsys.readouterr().err


def test_mode_has_one_range_on_both_structures(capsys, own_law_file):
    one_line_error(run(capsys, "modal", "--structure", own_law_file, "--mode", "0", *MODAL),
                   "--mode must be in [1, 50], got 0")


@pytest.mark.parametrize("flag", [["--normal-contact", "penalty"], ["--normal-slope", "1e6"],
                                  ["--substeps", "20"], ["--load", "tip:1,0,0:1"]])
def test_validate_refuses_the_mesh_options_on_the_box(capsys, tmp_path, flag):
    """The options of a mesh file did nothing on validate's box: refused in one line (they
    are recorded as the mesh's by add_option(mode=...), no hand list)."""
    one_line_error(run(capsys, "validate", "--out", tmp_path / "v", *flag),
                   flag[0], "--mesh FILE only")
    assert not (tmp_path / "v").exists()


def test_mode_records_come_from_add_option():
    from microslip.case.table import MODE_BOX, MODE_MESH, MODE_STRUCTURE, mode_options
    from microslip.cli.main import build_parser

    def modes(argv: list[str], mode: str) -> set[str]:
        return set(mode_options(build_parser(argv).parse_args(argv), mode))

    assert {"density", "response_set", "rom_modes", "solver", "workers"} <= modes(
        ["modal", "--amplitude-range", "1", "2"], MODE_MESH)
    assert {"frequency", "structure", "coupling", "joint", "length", "method"} <= modes(
        ["modal", "--amplitude-range", "1", "2"], MODE_STRUCTURE)
    assert {"model", "preset", "length", "pressure_law", "strain_energy"} <= modes(
        ["fe"], MODE_BOX)
    assert "modulus" not in modes(["fe"], MODE_BOX) | modes(["modal"], MODE_STRUCTURE)


def test_every_option_of_every_command_is_in_the_table():
    """Each flag of each command is an option of the table (its own spelling, or a command's
    other spelling of one: ``--mesh`` for the mesh file); its destination is the option's
    name but where the command's subject keeps its own (report --case)."""
    import argparse

    from microslip.case.table import OPTIONS
    from microslip.cli.main import build_parser

    by_flag = {o.flag: o for o in OPTIONS.values()}
    parser = build_parser()
    (sub,) = [a for a in parser._actions if isinstance(a, argparse._SubParsersAction)]
    parsers = dict(sub.choices)
    for action in parsers["case"]._actions:
        if isinstance(action, argparse._SubParsersAction):
            parsers.update({f"case {k}": v for k, v in action.choices.items()})
    seen = 0
    for command, p in parsers.items():
        for a in p._actions:
            flags = [f for f in a.option_strings if f.startswith("--")]
            if not flags or flags[0] in ("--help", "--solver"):
                continue
            seen += 1
            opt = OPTIONS.get(a.dest) or by_flag.get(flags[0])
            assert opt is not None, (command, flags[0])
            assert a.dest == opt.name or (command, a.dest) == ("report", "report_case"), (
                command, flags[0])
    assert seen > 300
