"""The command line imports only the module of the command that runs: ``microslip --help``
lists every command from :data:`microslip.cli.main.COMMANDS` without importing them."""

from __future__ import annotations

import argparse
import importlib
import json
import subprocess
import sys

import pytest

from microslip.cli.main import COMMANDS, build_parser, main

#: Modules the start-up of ``--help`` must not import (prefixes).
HEAVY = ("matplotlib", "scipy.sparse", "numba", "xarray", "dask", "microslip.models",
         "microslip.dynamics", "microslip.fe.builtin", "microslip.fe.run")


def _modules_after(argv: list[str]) -> list[str]:
    code = ("import sys, json, io, contextlib\n"
            "from microslip.cli.main import main\n"
            "with contextlib.redirect_stdout(io.StringIO()):\n"
            f"    main({argv!r})\n"
            "print(json.dumps(sorted(sys.modules)))")
    out = subprocess.run([sys.executable, "-c", code], check=True, capture_output=True,
                         text=True).stdout
    return json.loads(out)


#: Modules a single loop must not import (prefixes): numba and the compiled kernels (the
#: models run as plain Python, :func:`microslip.models.kernel`), and scipy.
COMPILED = ("numba", "scipy", "microslip.models.compiled", "microslip.models.batch_kernels",
            "microslip.dynamics", "microslip.batch")


@pytest.mark.parametrize("model", ["tip", "centre"])
def test_a_single_loop_loads_no_compiled_kernel(model):
    """``microslip loop`` within 3x of importing numpy and scipy.sparse (issue 27): it
    imports neither numba nor scipy (benchmarks/bench_startup.py times it)."""
    loaded = _modules_after(["loop", "--model", model, "--preset", "table1", "--json"])
    assert "microslip.models" in loaded
    assert [m for m in loaded if m.startswith(COMPILED)] == []


def test_help_imports_no_command():
    loaded = _modules_after(["--help"])
    commands = [m for m in loaded if m.rsplit(".", 1)[-1] in COMMANDS
                and m.startswith("microslip.cli.")]
    assert commands == []
    assert [m for m in loaded if m.startswith(HEAVY)] == []


def test_a_command_imports_its_own_module_only():
    loaded = _modules_after(["case", "--help"])
    commands = {m.rsplit(".", 1)[-1] for m in loaded if m.startswith("microslip.cli.")}
    assert "case" in commands and not commands & (set(COMMANDS) - {"case"})


def test_help_lists_every_command(capsys):
    assert main(["--help"]) == 0
    out = capsys.readouterr().out
    for name in COMMANDS:
        assert f"    {name}" in out


@pytest.mark.parametrize("name", list(COMMANDS))
def test_summary_is_the_commands_own(name):
    """The summary of --help is the one each command's add_parser gives."""
    sub = argparse.ArgumentParser().add_subparsers()
    importlib.import_module(f"microslip.cli.{name}").add_parser(sub)
    helps = {a.dest: a.help for a in sub._choices_actions}
    assert helps[name] == COMMANDS[name]


def test_the_named_command_gets_its_full_parser():
    parser = build_parser(["loop", "--model", "tip"])
    args = parser.parse_args(["loop", "--model", "tip", "--preset", "table1"])
    assert args.model == "tip" and callable(args.func)


def test_an_unknown_command_lists_the_commands(capsys):
    assert main(["lop"]) == 2
    err = capsys.readouterr().err
    assert "invalid choice: 'lop'" in err and "'report'" in err
