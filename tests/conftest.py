"""Shared test set-up.

- Tests marked ``ccx`` are skipped, with a reason, when ccx is absent.
- The one command-line runner of the tests: ``run(capsys, *argv)`` calls ``main`` in-process
  and returns ``(exit code, stdout, stderr)``; ``run_json`` adds ``--json``, insists on exit 0
  and returns the parsed JSON; ``one_line_error`` checks the "one ``error:`` line, exit 1"
  contract of a user mistake; ``listing`` is the files under a directory (to check that a
  refused command left nothing behind). Test modules import them with
  ``from conftest import run`` (pytest puts ``tests/`` on the path), never from one another.
"""

from __future__ import annotations

import json
import shutil
from pathlib import Path
from typing import Any

import pytest

from microslip.cli.main import main

#: Not test modules: tests/data holds the committed meshes' generator scripts, which need gmsh
#: (a tool to make the files, not a dependency: the tests read the committed files).
collect_ignore_glob = ["data/*"]


def pytest_collection_modifyitems(config: pytest.Config, items: list[pytest.Item]) -> None:
    if shutil.which("ccx") is not None:
        return
    skip = pytest.mark.skip(reason="CalculiX (ccx) is not on PATH; run `bash scripts/setup.sh`")
    for item in items:
        if "ccx" in item.keywords:
            item.add_marker(skip)


def run(capsys: pytest.CaptureFixture[str], *argv: object) -> tuple[int, str, str]:
    """``microslip ARGV...`` in-process (each argument through ``str``): code, stdout, stderr."""
    code = main([str(a) for a in argv])
    out, err = capsys.readouterr()
    return code, out, err


def run_json(capsys: pytest.CaptureFixture[str], *argv: object) -> Any:
    """``microslip ARGV... --json``, which must exit 0 (else stderr is shown): the JSON."""
    code, out, err = run(capsys, *argv, "--json")
    assert code == 0, err
    return json.loads(out)


def one_line_error(result: tuple[int, str, str], *words: str) -> None:
    """A user mistake: exit 1 and one ``error:`` line on stderr holding every one of ``words``."""
    code, _, err = result
    assert code == 1, err
    assert err.startswith("error: ") and err.count("\n") == 1 and "Traceback" not in err
    for word in words:
        assert word in err


def listing(path: Path) -> list[str]:
    """Every file and directory under ``path``, relative and sorted."""
    return sorted(str(p.relative_to(path)) for p in path.rglob("*"))


#: A steel clamp with a shear layer in its contact and a planar load (issue 21): the report
#: used to show the rigid-foundation model here (W_d 0.429 N·mm) against `loop`'s 0.139.
STEEL = """\
name = "steel clamp"
[geometry]
length = 40.0
width = 20.0
thickness = 6.0
[material]
modulus = 210000.0
poisson_ratio = 0.3
[contact]
friction = 0.6
stick_slope = 1e4
[clamping]
normal_force = 3000.0
[load]
model = "tip"
amplitude = 900.0
[load.planar]
tip_amplitude = 900.0
centre_amplitude = 900.0
"""
