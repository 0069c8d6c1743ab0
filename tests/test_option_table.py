"""The one option table (microslip.case.table): the command line and the case schema are
built from it, so a flag and its case key share type, unit, range, check and meaning."""

from __future__ import annotations

import argparse

import pytest

from microslip.case.options import CASE_OPTIONS
from microslip.case.schema import JOINT_KEYS, KEYS
from microslip.case.table import OPTIONS, SOLVERS, mesh_file, mesh_level, mesh_or_file, number
from microslip.cli.main import build_parser, main


def subparsers() -> dict[str, argparse.ArgumentParser]:
    parser = build_parser()
    (sub,) = [a for a in parser._actions if isinstance(a, argparse._SubParsersAction)]
    return dict(sub.choices)


def actions(flag: str) -> dict[str, argparse.Action]:
    """Command -> its action of ``flag``, for every command that takes it."""
    out = {}
    for name, p in subparsers().items():
        for a in p._actions:
            if flag in a.option_strings:
                out[name] = a
    return out


def test_every_case_key_of_an_option_is_built_from_it():
    by_dotted = {k.dotted: k for k in KEYS}
    for opt in OPTIONS.values():
        if opt.key is not None:
            key = by_dotted[opt.key]
            assert key.check is opt.check and key.unit == opt.unit and key.range == opt.range
            # the mesh file of a case is fe's --mesh FILE (--mesh also takes a box level)
            flag, dest = (("fe --mesh FILE", "mesh") if opt.key == "mesh.file"
                          else (opt.flag, opt.name))
            assert key.meaning.startswith(opt.help) and f"(as {flag})" in key.meaning
            assert CASE_OPTIONS[opt.key] == (dest, opt.scope)
        if opt.joint_key is not None:
            (key,) = [k for k in JOINT_KEYS if k.name == opt.joint_key]
            assert key.check is opt.check and key.range == opt.range


def test_every_case_key_maps_onto_an_option_a_command_takes():
    dests = {a.dest for p in subparsers().values() for a in p._actions}
    for key, (dest, _) in CASE_OPTIONS.items():
        assert dest in OPTIONS and dest in dests, key


@pytest.mark.parametrize("name", ["stick_slope", "length", "normal_force", "elements",
                                  "joint_stiffness", "phase", "structure", "fe_mesh"])
def test_an_option_is_the_same_on_every_command(name):
    opt = OPTIONS[name]
    found = actions(opt.flag)
    if name == "fe_mesh":
        found.pop("reproduce")  # reproduce --fe-mesh is its own: the validation's meshes
    assert found, name
    for command, a in found.items():
        assert a.dest == opt.name, command
        assert a.type is opt.type and a.metavar == opt.metavar, command
        assert a.help.startswith(opt.help), command


def test_stick_slope_is_one_option_on_five_commands():
    found = actions("--stick-slope")
    assert {"loop", "planar", "fe", "fit", "validate", "joint", "modal", "frf"} <= set(found)
    assert {a.type for a in found.values()} == {number}


def test_mesh_is_checked_the_same_on_every_command_that_takes_it():
    found = actions("--mesh")
    assert {"fe", "planar", "sweep", "report", "validate"} <= set(found)
    # fe's --mesh takes a mesh file of the user's own too; every other command a level
    assert found.pop("fe").type is mesh_or_file
    assert found.pop("modal").type is mesh_file  # the structure's own mesh
    assert found.pop("frf").type is mesh_file  # the structure's own mesh (frf --mesh)
    assert found.pop("reduce").type is mesh_file  # the structure's own mesh (reduce)
    assert found.pop("validate").type is mesh_or_file  # its own mesh against CalculiX
    assert {a.type for a in found.values()} == {mesh_level}
    assert actions("--fe-mesh")["modal"].type is mesh_level


@pytest.mark.parametrize("argv", [
    ["fe", "--model", "tip", "--mesh", "corse"],
    ["planar", "--solver", "fe", "--mesh", "corse", "--tip-amplitude", "1",
     "--centre-amplitude", "1"],
    ["sweep", "--solver", "fe", "--mesh", "corse", "--model", "tip"],
    ["validate", "--out", "x", "--mesh", "corse"],
    ["report", "--case", "c.toml", "--out", "r.html", "--mesh", "corse"],
])
def test_a_bad_mesh_is_one_usage_line_naming_the_allowed_ones(capsys, argv):
    assert main(argv) == 2
    out, err = capsys.readouterr()
    assert out == "" and err.count("\n") == 1
    assert "unknown mesh 'corse'" in err and "coarse" in err and "NXxNYxNZ" in err


def test_solver_says_what_it_means_on_each_command():
    found = actions("--solver")
    assert set(SOLVERS) <= set(found)
    for command, meaning in SOLVERS.items():
        a = found[command]
        assert list(a.choices) == list(meaning)
        for name, text in meaning.items():
            assert f"{name}: {text}" in a.help


def test_the_command_line_is_parsed_once_and_explicit_options_win(tmp_path, monkeypatch):
    from microslip.case.options import parse_args

    case = tmp_path / "c.toml"
    case.write_text('preset = "table1"\n[contact]\nfriction = 0.5\n[load]\nmodel = "centre"\n')
    parser = build_parser()
    calls = []
    real = type(parser).parse_args

    def counted(self, *a, **k):
        calls.append(a)
        return real(self, *a, **k)

    monkeypatch.setattr(type(parser), "parse_args", counted)
    args = parse_args(parser, ["loop", "--case", str(case), "--friction", "0.7"])
    assert len(calls) == 1
    assert args.friction == 0.7 and args.model == "centre"  # --model came from the case
    assert args.given_options == frozenset({"case", "friction"})
    assert args.normal_force == 445.0 and args.increments == 1000  # case, then default


def test_a_required_option_neither_given_nor_in_the_case_is_a_usage_error(capsys, tmp_path):
    case = tmp_path / "c.toml"
    case.write_text('preset = "table1"\n')
    assert main(["frf", "--case", str(case)]) == 2
    assert capsys.readouterr().err == ("error: microslip frf: the following arguments are "
                                       "required: --force\n")


def test_a_required_option_takes_the_default_the_case_file_documents(tmp_path):
    """load.model is documented as "default: tip": --case gives it to loop and sweep, which
    require --model (issue 27: sweep --case on the template failed)."""
    from microslip.case.options import parse_args

    case = tmp_path / "c.toml"
    case.write_text('preset = "table1"\n')
    for command in ("loop", "sweep"):
        args = parse_args(build_parser([command]), [command, "--case", str(case)])
        assert args.model == "tip" and "model" not in args.given_options
    args = parse_args(build_parser(["loop"]), ["loop", "--case", str(case), "--model",
                                               "centre"])
    assert args.model == "centre"
