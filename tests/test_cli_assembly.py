"""The assembly on the command line and in the case file (issue 32, item 5; item 7's one-line
errors of the input): ``--contact``, ``--preload``, ``--fixed``, ``--material`` and their
``[[mesh.*]]`` tables become one :class:`~microslip.fe.assembly.Assembly`, the clamp's
options its shorthand; every set, material and body is checked against the mesh before
anything is built."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import pytest
from assemblymesh import bar_on_base, write_bar_on_base
from conftest import one_line_error, run, run_json

from microslip.case.assembly import MissingInput, build_assembly
from microslip.case.meshroles import check_on_mesh, interface_pairs, offer
from microslip.case.options import parse_args
from microslip.cli.main import build_parser
from microslip.cli.ownmesh import mesh_clamp
from microslip.errors import ParameterError
from microslip.fe.assembly import Assembly, Contact, Material, Preload, Support, rigid_base

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"
CANTILEVER = str(EXAMPLES / "cantilever.inp")
LAW = ["--friction", "0.5"]
#: The issue's check on the bar standing on a base block 1000 x stiffer, fixed at its bottom.
PARTS = ["--contact", "bar_int:base_int", "--preload", "clamp:2000", "--fixed", "base_fix",
         "--material", "BAR:70000:0.33", "--material", "BASE:7e7:0.33", *LAW]


@pytest.fixture
def two(tmp_path: Path) -> str:
    return write_bar_on_base(tmp_path / "bar_on_base.inp")


def _args(*argv: str, command: str = "fe") -> argparse.Namespace:
    full = [command, *argv]
    return parse_args(build_parser(full), full)


def _flag(dest: str) -> str:
    return "--" + dest.replace("_", "-")


# -- the options -------------------------------------------------------------------------------

@pytest.mark.parametrize(("argv", "words"), [
    (["--contact", "a:b:c"], ["argument --contact", "'a:b:c'", "SET[:COUNTER_SET]"]),
    (["--contact", "a:a"], ["argument --contact", "its own counter face"]),
    (["--preload", "clamp"], ["argument --preload", "'clamp'", "SET:FORCE (FORCE in N"]),
    (["--preload", "clamp:x"], ["argument --preload", "the force must be a number (N)"]),
    (["--preload", "clamp:-2"], ["argument --preload", "> 0 (N), got -2.0", "SET:FORCE"]),
    (["--fixed", "fix:xq"], ["argument --fixed", "letters of xyz", "SET[:DIRECTIONS]"]),
    (["--fixed", ":z"], ["argument --fixed", "':z'", "SET[:DIRECTIONS]"]),
    (["--material", "BAR:7e4"], ["argument --material", "ELSET:MODULUS:POISSON[:DENSITY]"]),
    (["--material", "BAR:7e4:0.6"], ["argument --material", "poisson_ratio of BAR must be"]),
    (["--material", "BAR:7e4:0.3:7.85e-9"], ["argument --material", "t/mm^3"]),
    (["--bolt", "head:nut"], ["argument --bolt", "HEAD:NUT:FORCE[:DIAMETER]"]),
    (["--bolt", "head:head:10"], ["argument --bolt", "the head and the nut are one face"]),
    (["--bolt", "head:nut:10:-1"], ["argument --bolt", "diameter must be > 0 (mm)"]),
])
def test_a_malformed_value_is_one_usage_line(capsys: pytest.CaptureFixture[str], two: str,
                                              argv: list[str], words: list[str]) -> None:
    """Exit 2 and one line naming the option, the value and the form expected."""
    code, out, err = run(capsys, "fe", "--mesh", two, *argv, "--load", "tip:1,0,0:1")
    assert code == 2 and out == "" and err.count("\n") == 1 and err.startswith("error: ")
    for word in words:
        assert word in err


def test_the_shorthand_is_the_rigid_base_clamp() -> None:
    a = mesh_clamp(_args("--mesh", CANTILEVER, "--contact-set", "contact", "--clamp-set",
                         "clamp", "--normal-force", "2000", "--modulus", "70000",
                         "--poisson-ratio", "0.33", *LAW))
    assert a == rigid_base(contact_set="contact", clamp_set="clamp", normal_force=2000.0,
                           modulus=70000.0, poisson_ratio=0.33, friction=0.5)
    assert a.is_shorthand


def test_the_options_build_the_assembly(two: str) -> None:
    a = mesh_clamp(_args("--mesh", two, *PARTS, "--stick-slope", "3e4"))
    assert a.contacts == (Contact("bar_int", "base_int"),)
    assert a.preloads == (Preload("clamp", 2000.0),)
    assert a.supports == (Support("base_fix", "xyz"),)
    assert a.materials == (Material(70000.0, 0.33, None, "BAR"), Material(7e7, 0.33, None,
                                                                          "BASE"))
    assert (a.friction, a.stick_slope, a.normal_contact) == (0.5, 3e4, "fixed")
    assert not a.is_shorthand


def test_the_shorthand_mixes_with_the_assembly_options(two: str) -> None:
    """--contact-set X is --contact X, --clamp-set Y --normal-force F is --preload Y:F,
    --modulus/--poisson-ratio the material of every element no --material names, --density
    the density of every material that gives none."""
    a = mesh_clamp(_args("--mesh", two, "--contact-set", "bar_int", "--contact",
                         "base_fix", "--clamp-set", "clamp", "--normal-force", "100",
                         "--preload", "tip:50", "--modulus", "7e7", "--poisson-ratio", "0.3",
                         "--material", "BAR:70000:0.33", "--material", "BASE:2e5:0.3:7800",
                         "--density", "2700", "--fixed", "base_fix:z", *LAW, command="modal"))
    assert [c.label for c in a.contacts] == ["bar_int", "base_fix"]
    assert [(p.face, p.force) for p in a.preloads] == [("clamp", 100.0), ("tip", 50.0)]
    assert [(m.elset, m.modulus, m.density) for m in a.materials] == [
        (None, 7e7, 2700.0), ("BAR", 70000.0, 2700.0), ("BASE", 2e5, 7800.0)]
    assert a.supports == (Support("base_fix", "z"),)


@pytest.mark.parametrize(("argv", "words"), [
    ([], ["--contact-set NAME (or --contact SET[:COUNTER_SET])", "--clamp-set NAME with "
          "--normal-force N (or --preload SET:FORCE, or --bolt HEAD:NUT:FORCE)",
          "--modulus MPA and --poisson-ratio X",
          "--friction X", "--load"]),
    (["--contact", "bar_int:base_int", "--preload", "clamp:9", "--material", "BAR:1e5:0.3",
      "--friction", "0.4", "--modulus", "1e5"], ["needs --poisson-ratio X,", "--load"]),
    (["--contact", "bar_int", "--clamp-set", "clamp", "--material", "BAR:1e5:0.3",
      "--friction", "0.4"], ["needs --normal-force N (the force on --clamp-set clamp)"]),
])
def test_what_is_left_out_is_one_usage_line(capsys: pytest.CaptureFixture[str], two: str,
                                            argv: list[str], words: list[str]) -> None:
    code, _, err = run(capsys, "fe", "--mesh", two, *argv)
    assert code == 2 and err.count("\n") == 1
    for word in words:
        assert word in err


def test_a_normal_force_without_its_clamp_set_is_refused(capsys: pytest.CaptureFixture[str],
                                                         two: str) -> None:
    one_line_error(run(capsys, "fe", "--mesh", two, *PARTS, "--normal-force", "300", "--load",
                       "tip:1,0,0:10"), "--normal-force 300 presses no face",
                   "with --preload or --bolt give each its own force")


def test_a_bolt_is_its_two_preloads_and_its_shank(tmp_path: Path) -> None:
    from microslip.fe.assembly import Shank

    a = mesh_clamp(_args("--mesh", CANTILEVER, "--contact", "contact", "--bolt",
                         "clamp:tip:500:8", "--bolt", "tip:response:300", "--modulus", "7e4",
                         "--poisson-ratio", "0.3", *LAW))
    assert a.preloads == (Preload("clamp", 500.0), Preload("tip", 500.0),
                          Preload("tip", 300.0), Preload("response", 300.0))
    assert a.shanks == (Shank("clamp", "tip", 8.0),)
    (tmp_path / "b.toml").write_text(
        '[contact]\nfriction = 0.5\n[material]\nmodulus = 7e4\npoisson_ratio = 0.3\n'
        f'[mesh]\nfile = "{CANTILEVER}"\ncontact_set = "contact"\n[[mesh.bolt]]\n'
        'head = "clamp"\nnut = "tip"\nforce = 500\ndiameter = 8\n[[mesh.bolt]]\n'
        'head = "tip"\nnut = "response"\nforce = 300\n')
    assert mesh_clamp(_args("--case", str(tmp_path / "b.toml"))) == a


def test_build_assembly_names_every_missing_value_in_the_callers_spelling() -> None:
    with pytest.raises(MissingInput) as err:
        build_assembly({"clamp_set": "clamp"}, lambda d: f"<{d}>")
    assert err.value.missing == ("<contact_set> NAME (or <contact> SET[:COUNTER_SET])",
                                 "<normal_force> N (the force on <clamp_set> clamp)",
                                 "<modulus> MPA and <poisson_ratio> X (or <material> per "
                                 "element set)", "<friction> X")


def test_assembly_options_belong_to_mesh_files(capsys: pytest.CaptureFixture[str]) -> None:
    """The box (fe --mesh LEVEL) and modal without --mesh refuse them, naming them."""
    one_line_error(run(capsys, "fe", "--model", "tip", "--mesh", "tiny", "--fixed", "a"),
                   "--fixed applies to --mesh FILE only")
    one_line_error(run(capsys, "modal", "--frequency", "100", "--modal-mass", "1", "--joint",
                       "jenkins", "--joint-stiffness", "100", "--slip-force", "5",
                       "--amplitude-range", "0.01", "1", "--preload", "a:1"),
                   "--preload applies to modal --mesh FILE only")


@pytest.mark.parametrize("command", ["fe", "validate", "modal", "frf", "reduce"])
def test_every_mesh_command_takes_the_assembly_options(command: str) -> None:
    parser = build_parser([command])
    sub = next(a for a in parser._actions if isinstance(a, argparse._SubParsersAction))
    flags = {s for a in sub.choices[command]._actions for s in a.option_strings}
    assert {"--contact", "--preload", "--fixed", "--material", "--contact-set"} <= flags


# -- the mesh checks ---------------------------------------------------------------------------

def test_the_interface_of_two_bodies_is_found() -> None:
    """The sets of two bodies whose nodes coincide one to one; the counter on the body with
    fewer elements (the base); one body (the interface glued) has none."""
    assert interface_pairs(bar_on_base()) == (("bar_int", "base_int"),)
    assert interface_pairs(bar_on_base(share_nodes=True)) == ()


def _assembly(**kw: object) -> Assembly:
    base = {"contacts": (Contact("bar_int", "base_int"),),
            "preloads": (Preload("clamp", 2000.0),), "supports": (Support("base_fix"),),
            "materials": (Material(7e4, 0.33, None, "BAR"), Material(7e7, 0.33, None, "BASE")),
            "friction": 0.5}
    return Assembly(**{**base, **kw})  # type: ignore[arg-type]


def test_a_right_assembly_has_no_finding() -> None:
    found = check_on_mesh(bar_on_base(), _assembly(), ["tip"], [("tip", "response set")])
    assert found.errors == () and found.warnings == ()


@pytest.mark.parametrize(("change", "words"), [
    ({"supports": (Support("base_fx"),)},
     ["no set named 'base_fx' (the support set); did you mean 'base_fix'?"]),
    ({"contacts": (Contact("bar_int", "bas_int"),)},
     ["no set named 'bas_int' (the counter set of contact bar_int:bas_int); did you mean "
      "'base_int'?"]),
    ({"materials": (Material(7e4, 0.33, None, "BAR"), Material(7e7, 0.33, None, "BASS"))},
     ["no element set named 'BASS'", "did you mean 'BASE'?"]),
    ({"materials": (Material(7e4, 0.33, None, "BAR"),)},
     ["4 of 16 elements (e.g. element 13) have no material"]),
    ({"contacts": (Contact("bar_int", "clamp"),)},
     ["the counter set 'clamp' lies on the same body as 'bar_int' (body 1 (BAR))"]),
    ({"contacts": (Contact("bar_int"),)},
     ["body 1 (BAR) and body 2 (BASE) touch at 9 coincident nodes with no contact named",
      "--contact bar_int:base_int"]),
    ({"supports": ()}, ["the preloads push the free-free assembly (net force 2000 N)",
                        "hold it (--fixed)"]),
    ({"preloads": (Preload("clamp", 5e9),)},
     ["the clamping pressure F/A on 'clamp' = 5e+09 N / 1290 mm^2", "times the modulus "
      "(70000 MPa)", "a mesh in metres"]),
])
def test_each_mistake_is_one_line_naming_it(change: dict[str, object],
                                            words: list[str]) -> None:
    found = check_on_mesh(bar_on_base(), _assembly(**change))
    assert len(found.errors) == 1, found.errors
    assert all(w in found.errors[0] for w in words), found.errors[0]
    with pytest.raises(ParameterError, match="bar_on_base: "):
        found.raise_first()


def test_a_mesh_in_metres_is_an_error_and_a_light_clamp_a_warning() -> None:
    (err,) = check_on_mesh(bar_on_base(scale=1e-3), _assembly()).errors
    assert "the part is 0.152 mm across" in err and "a mesh in metres" in err
    found = check_on_mesh(bar_on_base(), _assembly(preloads=(Preload("clamp", 1e-5),)))
    assert found.errors == ()
    (warning,) = found.warnings
    assert "outside [1e-08, 0.01]" in warning and "a modulus in Pa" in warning


def test_the_fe_checks_the_mesh_before_it_builds_anything(capsys: pytest.CaptureFixture[str],
                                                          two: str, tmp_path: Path) -> None:
    one_line_error(run(capsys, "fe", "--mesh", two, *PARTS[:4], "--fixed", "base_fx",
                       *PARTS[6:], "--load", "tip:1,0,0:10", "--out", tmp_path / "run"),
                   "did you mean 'base_fix'?")
    assert not (tmp_path / "run").exists()
    metres = write_bar_on_base(tmp_path / "m.inp", scale=1e-3)
    one_line_error(run(capsys, "fe", "--mesh", metres, *PARTS, "--load", "tip:1,0,0:10"),
                   "mm across", "a mesh in metres")


BLOCK = str(Path(__file__).resolve().parent / "data" / "meshes" / "cantilever_on_block.inp")
RIGID = ["--mesh", CANTILEVER, "--contact-set", "contact", "--clamp-set", "clamp",
         "--normal-force", "2000", "--modulus", "70000", "--poisson-ratio", "0.33", *LAW]


@pytest.mark.parametrize("load", ["tip:1,0,0:300", "tip:0,1,0:60"])
def test_the_bar_on_a_stiff_block_is_the_rigid_base(capsys: pytest.CaptureFixture[str],
                                                    load: str) -> None:
    """Issue 32's check through the command line: the cantilever on a block 1000 x stiffer,
    held at its bottom, gives the rigid base's W within 0.5 % and d within 0.2 %."""
    block = run_json(capsys, "fe", "--mesh", BLOCK, *PARTS, "--load", load)
    rigid = run_json(capsys, "fe", *RIGID, "--load", load)
    assert block["dissipated_energy_Nmm"] > 0 and block["settled"]
    assert block["dissipated_energy_Nmm"] == pytest.approx(rigid["dissipated_energy_Nmm"],
                                                           rel=5e-3)
    assert block["peak_displacement_mm"] == pytest.approx(rigid["peak_displacement_mm"],
                                                           rel=2e-3)
    assert block["assembly"]["contacts"] == [{"face": "bar_int", "counter": "base_int"}]
    assert block["assembly"]["supports"] == [{"set": "base_fix", "directions": "xyz"}]


LAP = str(Path(__file__).resolve().parent / "data" / "meshes" / "bolted_lap_small.msh")


def test_the_bolted_lap_runs_from_the_command_line(capsys: pytest.CaptureFixture[str]) -> None:
    """Two steel plates, one bolt with a shank, the far end held: the lateral load that the
    lap alone cannot carry past its friction limit runs with the shank (issue 32)."""
    out = run_json(capsys, "fe", "--mesh", LAP, "--contact", "a_int:b_int", "--bolt",
                   "head:nut:8000:10", "--fixed", "fix", "--material", "PLATE_A:210000:0.3",
                   "--material", "PLATE_B:210000:0.3", "--friction", "0.3",
                   "--load", "tip:0,1,0:150")
    assert out["settled"] and out["dissipated_energy_Nmm"] > 0
    assert out["assembly"]["shanks"][0]["head"] == "head"
    assert out["assembly"]["shanks"][0]["diameter_mm"] == 10.0
    assert [p["face"] for p in out["assembly"]["preloads"]] == ["head", "nut"]


def test_the_assembly_case_file_runs_as_its_options(capsys: pytest.CaptureFixture[str],
                                                    tmp_path: Path) -> None:
    import shutil

    shutil.copy(BLOCK, tmp_path / "bar_on_base.inp")
    (tmp_path / "c.toml").write_text(CASE)
    by_case = run_json(capsys, "fe", "--case", tmp_path / "c.toml")
    by_flags = run_json(capsys, "fe", "--mesh", BLOCK, *PARTS, "--load", "tip:1,0,0:100")
    assert by_case["dissipated_energy_Nmm"] == by_flags["dissipated_energy_Nmm"]
    assert by_case["assembly"] == by_flags["assembly"]


@pytest.mark.slow
@pytest.mark.ccx
def test_validate_runs_the_assembly_with_its_default_fixed_contact(
        capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    """validate --mesh on the bar on its block (about 30 s): the default fixed contact
    compared as a hard contact and said so, both sides settled and within the tolerances,
    the case's fixed W beside; CalculiX's progress on stderr although it is not a
    terminal."""
    code, out, err = run(capsys, "validate", "--mesh", BLOCK, *PARTS, "--stick-slope", "1e4",
                         "--load", "tip:1,0,0:300", "--out", tmp_path / "v")
    assert code == 0, err
    assert "normal contact: the case's fixed; CalculiX has no fixed normal contact" in out
    assert "the case's fixed contact, built-in: W " in out and "passed; wrote" in out
    assert "CalculiX (node-to-surface): " in err and "increments (100 %)" in err


def test_a_structure_takes_each_materials_density(capsys: pytest.CaptureFixture[str],
                                                   tmp_path: Path) -> None:
    """reduce (as modal and frf --mesh) on two bodies: each material's own density (the
    block's is the structure's mass, so a heavier block lowers the frequencies), --density
    for those that give none; no density at all is a usage line."""
    import json

    argv = ["reduce", "--mesh", BLOCK, *PARTS[:6], "--friction", "0.5", "--rom-modes", "5",
            "--out", tmp_path / "r.npz", "--json"]
    freq = {}
    for rho in ("2700", "7800"):
        code, out, err = run(capsys, *argv, "--material", "BAR:70000:0.33:2700", "--material",
                             f"BASE:7e7:0.33:{rho}")
        assert code == 0, err
        freq[rho] = json.loads(out)["full_frequencies_Hz"]
    assert all(h < light for h, light in zip(freq["7800"], freq["2700"], strict=True))
    code, out, err = run(capsys, *argv, "--material", "BAR:70000:0.33", "--material",
                         "BASE:7e7:0.33:2700", "--density", "2700")
    assert code == 0 and json.loads(out)["full_frequencies_Hz"] == freq["2700"], err
    code, _, err = run(capsys, *argv, "--material", "BAR:70000:0.33", "--material",
                       "BASE:7e7:0.33")
    assert code == 2 and "--density KG/M3" in err


# -- units -------------------------------------------------------------------------------------

CANT = ["--mesh", CANTILEVER, "--contact-set", "contact", "--clamp-set", "clamp",
        "--normal-force", "2000", "--friction", "0.5", "--poisson-ratio", "0.33"]


@pytest.mark.parametrize(("argv", "words"), [
    (["fe", *CANT, "--modulus", "7e10", "--load", "tip:1,0,0:100"],
     ["--modulus 7e+10 MPa", "pascals given as MPa?"]),
    (["modal", *CANT, "--modulus", "70000", "--density", "7.85e-9"],
     ["--density 7.85e-09 kg/m^3 is below 100 kg/m^3", "t/mm^3"]),
    (["reduce", *CANT, "--modulus", "70000", "--density", "7.85", "--out", "r.npz"],
     ["--density 7.85 kg/m^3", "g/cm^3"]),
    (["fe", *CANT, "--modulus", "70000", "--normal-force", "2e9", "--load", "tip:1,0,0:100"],
     ["the clamping pressure F/A on 'clamp'", "times the modulus"]),
])
def test_a_value_that_cannot_be_meant_is_an_error(capsys: pytest.CaptureFixture[str],
                                                  argv: list[str], words: list[str]) -> None:
    """Issue 34, item 1: a unit mistake exits 1 with one line naming it, no result."""
    code, out, err = run(capsys, *argv)
    assert code == 1 and out == "" and err.count("\n") == 1
    assert all(w in err for w in words), err


# -- the case file -----------------------------------------------------------------------------

CASE = """name = "bar on its base"
[contact]
friction = 0.5
[mesh]
file = "bar_on_base.inp"
[[mesh.contact]]
face = "bar_int"
counter = "base_int"
[[mesh.preload]]
face = "clamp"
force = 2000.0
[[mesh.support]]
set = "base_fix"
[[mesh.material]]
elset = "BAR"
modulus = 70000
poisson_ratio = 0.33
[[mesh.material]]
elset = "BASE"
modulus = 7e7
poisson_ratio = 0.33
[[mesh.load]]
set = "tip"
direction = [1, 0, 0]
amplitude = 100
"""


def test_the_case_tables_are_the_options(two: str, tmp_path: Path) -> None:
    (tmp_path / "c.toml").write_text(CASE)
    by_case = mesh_clamp(_args("--case", str(tmp_path / "c.toml")))
    assert by_case == mesh_clamp(_args("--mesh", two, *PARTS))
    # an option given on the command line wins over its tables
    assert mesh_clamp(_args("--case", str(tmp_path / "c.toml"), "--fixed", "tip:z")
                      ).supports == (Support("tip", "z"),)


@pytest.mark.parametrize(("old", "new", "words"), [
    ('counter = "base_int"', 'countr = "base_int"',
     ["[[mesh.contact]] 1: unknown key countr; did you mean counter?"]),
    ("[[mesh.support]]", "[[mesh.suport]]", ["unknown case key mesh.suport; did you mean "
                                             "mesh.support?"]),
    ("force = 2000.0", "force = -1.0", ["[[mesh.preload]] 1: preload clamp's force must be > 0"]),
    ("force = 2000.0", 'force = "2000"', ["[[mesh.preload]] 1: force must be a number (N)"]),
    ('elset = "BAR"\n', "", ["[[mesh.material]] 1: give elset"]),
    ("modulus = 7e7\n", "modulus = 7e7\ndensity = 7.85e-9\n",
     ["[[mesh.material]] 2: density of BASE = 7.85e-09 kg/m^3 is outside"]),
    ('[mesh]\nfile = "bar_on_base.inp"', '[mesh]\nfile = "bar_on_base.inp"\ndensity = 7.85e-9',
     ["case key mesh.density = 7.85e-09 kg/m^3 is below 100 kg/m^3", "t/mm^3"]),
])
def test_bad_tables_are_one_line(capsys: pytest.CaptureFixture[str], two: str, tmp_path: Path,
                                 old: str, new: str, words: list[str]) -> None:
    assert old in CASE
    (tmp_path / "c.toml").write_text(CASE.replace(old, new, 1))
    one_line_error(run(capsys, "case", "check", tmp_path / "c.toml"), *words)


def test_case_check_opens_the_mesh(capsys: pytest.CaptureFixture[str], two: str,
                                   tmp_path: Path) -> None:
    """Every error of the case against its mesh, one line each, exit 1; a right case exits 0
    and lists its tables."""
    path = tmp_path / "c.toml"
    path.write_text(CASE)
    code, out, err = run(capsys, "case", "check", path)
    assert code == 0 and err == "", err
    assert "[[mesh.contact]] 1: bar_int on base_int" in out
    assert "[[mesh.material]] 2: BASE: modulus 7e+07 MPa" in out
    path.write_text(CASE.replace('set = "base_fix"', 'set = "base_fx"')
                    .replace('set = "tip"', 'set = "tipp"'))
    code, out, err = run(capsys, "case", "check", path)
    lines = err.splitlines()
    assert code == 1 and len(lines) == 2 and all(ln.startswith("error: ") for ln in lines)
    assert "did you mean 'base_fix'?" in lines[0] and "did you mean 'tip'?" in lines[1]


def test_case_check_names_the_missing_keys(capsys: pytest.CaptureFixture[str],
                                           tmp_path: Path) -> None:
    """Issue 34: a case without its clamp set exits non-zero naming the key."""
    import shutil

    shutil.copy(CANTILEVER, tmp_path / "cantilever.inp")
    path = tmp_path / "c.toml"
    path.write_text('[material]\nmodulus = 70000\npoisson_ratio = 0.33\n[contact]\n'
                    'friction = 0.5\n[clamping]\nnormal_force = 2000\n[mesh]\n'
                    'file = "cantilever.inp"\ncontact_set = "contact"\n')
    one_line_error(run(capsys, "case", "check", path), "the part needs mesh.clamp_set NAME "
                   "with clamping.normal_force N (or [[mesh.preload]] SET:FORCE, or "
                   "[[mesh.bolt]] HEAD:NUT:FORCE)")
    path.write_text(path.read_text() + 'clamp_set = "clmp"\n')
    one_line_error(run(capsys, "case", "check", path),
                   "no set named 'clmp' (the clamp set); did you mean 'clamp'?")


def test_case_new_writes_the_bodies_and_their_interface(capsys: pytest.CaptureFixture[str],
                                                        two: str, tmp_path: Path) -> None:
    """A mesh of two bodies: a [[mesh.material]] table per body's element set, the
    interface found as [[mesh.contact]], the support found by name as [[mesh.support]]; the
    file passes case check, and without its support case check names the body nothing
    holds."""
    path = tmp_path / "two.toml"
    code, out, err = run(capsys, "case", "new", "--mesh", two, path)
    assert code == 0 and err == "" and "to fill" not in out
    text = path.read_text()
    assert '[[mesh.contact]]\nface = "bar_int"\ncounter = "base_int"' in text
    assert 'elset = "BAR"  # body 1' in text and 'elset = "BASE"  # body 2' in text
    assert '[[mesh.support]]\nset = "base_fix"\ndirections = "xyz"' in text
    assert "# 2 bodies: body 1 (BAR); body 2 (BASE)" in text
    code, _, err = run(capsys, "case", "check", path)
    assert code == 0, err
    path.write_text(text.replace('[[mesh.support]]\nset = "base_fix"\ndirections = "xyz"', ""))
    one_line_error(run(capsys, "case", "check", path), "the preloads push the free-free "
                   "assembly", "[[mesh.support]]")


def test_case_new_finds_a_bolts_faces_and_names_what_is_left(
        capsys: pytest.CaptureFixture[str], tmp_path: Path) -> None:
    """Two bodies with a bolt's head and nut faces and no support: a [[mesh.bolt]] (the
    [clamping] force then commented out: it has no face), the support named as a role to
    fill."""

    from microslip.fe.hexmesh import HexMesh
    from microslip.fe.meshfile import write_inp

    m = bar_on_base()
    sets = {("head" if k == "clamp" else "nut" if k == "base_fix" else k): v
            for k, v in m.node_sets.items()}
    faces = {("head" if k == "clamp" else "nut" if k == "base_fix" else k): v
             for k, v in m.surfaces.items()}
    write_inp(HexMesh(m.nodes, m.elements, sets, faces, source="bolted",
                      element_sets=dict(m.element_sets)), tmp_path / "b.inp")
    code, out, _ = run(capsys, "case", "new", "--mesh", tmp_path / "b.inp", tmp_path / "b.toml")
    text = (tmp_path / "b.toml").read_text()
    assert code == 0 and "to fill: [[mesh.support]]" in out and "clamp_set" not in out
    assert ('[[mesh.bolt]]\nhead = "head"\nnut = "nut"\nforce = 445.0\n# diameter = 10.0'
            in text) and "[[mesh.preload]]\n" not in text
    assert "\n# normal_force = 445.0" in text
    assert offer(bar_on_base()).pairs == (("bar_int", "base_int"),)
    # the bolt's head and nut press alike: a free-free assembly, which holds together
    code, _, err = run(capsys, "case", "check", tmp_path / "b.toml")
    assert code == 0, err


def test_case_new_never_proposes_a_volume_group(capsys: pytest.CaptureFixture[str],
                                                tmp_path: Path) -> None:
    """A mesh whose only sets besides the clamp's roles are its volume: the load example is a
    placeholder, the load named as a role to fill, the volume group listed as such."""
    import numpy as np

    from microslip.fe.examples import cantilever_mesh
    from microslip.fe.hexmesh import HexMesh
    from microslip.fe.meshfile import write_inp

    m = cantilever_mesh(12, 3, 1)
    body = np.arange(len(m.nodes))
    sets = {"contact": m.node_sets["contact"], "clamp": m.node_sets["clamp"], "body": body}
    write_inp(HexMesh(m.nodes, m.elements, sets, source="plate",
                      element_sets={"body": np.arange(len(m.elements))}), tmp_path / "p.inp")
    assert offer(HexMesh(m.nodes, m.elements, sets, element_sets={
        "body": np.arange(len(m.elements))})).volumes == ("body",)
    code, out, _ = run(capsys, "case", "new", "--mesh", tmp_path / "p.inp", tmp_path / "p.toml")
    text = (tmp_path / "p.toml").read_text()
    assert code == 0 and '# set = "SET"' in text and 'set = "body"' not in text
    assert "# volume groups (never a face or a load): body" in text
    assert "to fill: [[mesh.load]]" in out and "to fill: mesh.response_set" in out


# -- exits, W and help -------------------------------------------------------------------------

RUN = [*CANT, "--modulus", "70000", "--load", "tip:1,0,0:300"]


def test_a_result_that_did_not_settle_exits_3(capsys: pytest.CaptureFixture[str]) -> None:
    """Issue 34, item 8: the figures printed, exit 3; --accept-unsettled takes them."""
    code, out, err = run(capsys, "fe", *RUN, "--max-cycles", "2", "--settle-tol", "1e-12")
    assert code == 3 and "did not settle" in out and "exit status 3" in out
    assert "over the last cycle" in out and "warning: W per cycle did not settle" in err
    assert run(capsys, "fe", *RUN, "--max-cycles", "2", "--settle-tol", "1e-12",
               "--accept-unsettled")[0] == 0
    assert run(capsys, "fe", *RUN)[0] == 0  # settled


def test_a_w_below_the_tolerance_prints_as_zero(capsys: pytest.CaptureFixture[str]) -> None:
    """Issue 34, item 9: a stuck W is 0 with the solver's tolerance, not 1.9e-11."""
    import json

    code, out, _ = run(capsys, "fe", *CANT, "--modulus", "70000", "--load", "tip:1,0,0:20",
                       "--normal-force", "20000")
    assert code == 0
    line = next(ln for ln in out.splitlines() if "dissipated energy W" in ln)
    assert " 0 N·mm  (below the solver's tolerance of " in line and "e-1" in line
    code, out, _ = run(capsys, "fe", *CANT, "--modulus", "70000", "--load", "tip:1,0,0:20",
                       "--normal-force", "20000", "--json")
    data = json.loads(out)
    assert abs(data["dissipated_energy_Nmm"]) < data["work_tolerance_Nmm"] < 1e-6
    assert data["assembly"]["preloads"] == [{"face": "clamp", "force_N": 20000.0}]


def test_validate_mesh_status() -> None:
    from microslip.cli.validate import mesh_status

    ok = {"passed": True, "settled": {"builtin": True, "calculix": True},
          "relative_difference": {"w": 0.0}, "tolerance": {"w": 0.01}}
    loose = {**ok, "passed": False, "settled": {"builtin": True, "calculix": False}}
    far = {**ok, "passed": False, "relative_difference": {"w": 0.5}}
    plain, accept = argparse.Namespace(), argparse.Namespace(accept_unsettled=True)
    assert mesh_status(plain, ok) == 0
    assert mesh_status(plain, loose) == 3 and mesh_status(accept, loose) == 0
    assert mesh_status(plain, far) == 1 and mesh_status(accept, far) == 1


@pytest.mark.parametrize("command", ["fe", "validate", "modal", "frf", "reduce"])
def test_help_says_which_mode_an_option_belongs_to(command: str) -> None:
    """Issue 34, item 9: every option of one mode says so in its help."""
    from microslip.case.table import MODE_NOTES, MODES_KEY

    parser = build_parser([command])
    sub = next(a for a in parser._actions if isinstance(a, argparse._SubParsersAction))
    p = sub.choices[command]
    modes = p.get_default(MODES_KEY) or {}
    assert modes
    for a in p._actions:
        if a.dest in modes and a.help != argparse.SUPPRESS:
            assert a.help.endswith(MODE_NOTES[modes[a.dest]]), (a.dest, a.help)


def test_modal_help_does_not_offer_csv_with_a_mesh(capsys: pytest.CaptureFixture[str]) -> None:
    code, out, _ = run(capsys, "modal", "--help")
    assert code == 0
    assert ("--csv FILE.csv write the table as CSV [1-D structure (--structure FILE or one "
            "mode) only: not with --mesh]") in " ".join(out.split())


def test_help_states_the_exit_statuses(capsys: pytest.CaptureFixture[str]) -> None:
    for argv in (["--help"], ["fe", "--help"], ["validate", "--help"]):
        text = " ".join(run(capsys, *argv)[1].split())
        assert "3 a result that did not settle" in text and "--accept-unsettled" in text


def test_progress_shows_as_lines_when_stderr_is_a_file(capsys: pytest.CaptureFixture[str],
                                                       monkeypatch: pytest.MonkeyPatch
                                                       ) -> None:
    """Issue 34, item 8: a run whose stderr goes to a file still says it moves: a line
    every LINE_SECONDS at most, and the last; a run shorter than that says nothing."""
    from microslip import progress

    clock = iter([0.0, 1.0, 2.0, 20.0, 21.0, 22.0, 0.0, 1.0, 2.0])
    monkeypatch.setattr(progress.time, "monotonic", lambda: next(clock))
    assert not sys.stderr.isatty()
    with progress.progress_bar(5, "CalculiX runs", unit="run") as bar:
        for _ in range(5):
            bar.update()
    lines = capsys.readouterr().err.splitlines()
    assert lines == ["CalculiX runs: 3/5 runs (60 %), 20 s, about 13 s left",
                     "CalculiX runs: 5/5 runs (100 %), 22 s"]
    with progress.progress_bar(2, "quick") as bar:
        bar.update()
        bar.update()
    assert capsys.readouterr().err == ""
    with progress.progress_bar(5, "quiet", enabled=False) as bar:
        bar.update()
    assert capsys.readouterr().err == ""
