"""Every ``microslip`` command shown in README.md and docs/*.md runs and exits 0.

The commands are read from the fenced code blocks (continuation lines joined, comments
dropped) and run in-process in an empty directory (a ``--structure`` file is first written by
the document's own ``python`` blocks; a case file shown in a ``toml`` block whose first line
is ``# file: NAME.toml`` is written first); examples that differ only in their output
paths or ``--json`` run once. Full-size runs are shrunk so that the
suite stays fast, by the rules of :data:`SHRINK` (fewer cases and samples, the smallest mesh
of the solver); the options and their combination are those of the documentation, which is
what this test guards: an example that no longer parses, refers to a removed option or fails
on its own inputs fails here. Lines with a literal ``...`` are elisions, not commands.
"""

from __future__ import annotations

import re
import shlex
import shutil
from pathlib import Path

import numpy as np
import pytest

from microslip import ModelOptions, first_loading, masing_loop
from microslip.cli.main import main

ROOT = Path(__file__).resolve().parents[1]
DOCS = [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]

#: option -> function of its value giving the value the test uses (None: keep)
SHRINK = {
    "--cases": lambda v: str(min(int(float(v)), 2000)),
    "--samples": lambda v: str(min(int(float(v)), 50)),
    "--amplitudes": lambda v: str(min(int(v), 12)),
}


def _python_blocks(doc: str) -> list[str]:
    path = next(p for p in DOCS if p.name == doc)
    return re.findall(r"```python\n(.*?)```", path.read_text(encoding="utf-8"), re.S)


def _toml_files(doc: str) -> dict[str, str]:
    """The document's ``toml`` blocks whose first line is ``# file: NAME.toml``."""
    path = next(p for p in DOCS if p.name == doc)
    blocks = re.findall(r"```toml\n# file: (\S+)\n(.*?)```", path.read_text(encoding="utf-8"),
                        re.S)
    return dict(blocks)


def _commands() -> list[tuple[str, str]]:
    found = []
    for path in DOCS:
        for block in re.findall(r"```[a-z]*\n(.*?)```", path.read_text(encoding="utf-8"), re.S):
            for line in block.replace("\\\n", " ").splitlines():
                line = line.strip()
                if line.startswith("microslip ") and "..." not in line:
                    found.append((path.name, line))
    return found


def _shrink(argv: list[str]) -> list[str]:
    out = list(argv)
    for i, arg in enumerate(out[:-1]):
        if arg in SHRINK:
            out[i + 1] = SHRINK[arg](out[i + 1])
    own_mesh = any(a.startswith("examples/") for a in out)  # a mesh file of examples/
    if out[0] in ("fe", "validate", "planar") and "--mesh" in out and not own_mesh:
        calculix = out[0] == "validate" or "calculix" in out
        small = "coarse" if calculix else "tiny"
        meshes = [i for i, a in enumerate(out) if a == "--mesh"]
        for i in reversed(meshes[1:]):
            del out[i:i + 2]
        out[meshes[0] + 1] = small
    if out[0] == "validate" and "--model" not in out:
        out += ["--model", "tip"]
    if out[0] == "reproduce":  # the FE parts have their own tests (test_reproduce*.py)
        out += [a for a in ("--no-fe", "--increments", "100") if a not in out]
    return out


COMMANDS = _commands()


def _key(line: str) -> frozenset[str]:
    """A command as run, output paths and ``--json`` aside: examples that differ only there
    run once."""
    argv = _shrink(shlex.split(line, comments=True)[1:])
    return frozenset("OUT" if prev in ("--out", "--plot") else a
                     for prev, a in zip(["", *argv[:-1]], argv, strict=True) if a != "--json")


RUN = list({_key(line): (doc, line) for doc, line in reversed(COMMANDS)}.values())[::-1]


def _measured_loops(directory: Path, argv: list[str]) -> None:
    """The loop CSVs a ``fit`` example reads (``loop_2kN.csv``: 2 kN; ``loop_3k6N.csv``:
    3.6 kN): model loops of the clamp its options give."""
    from microslip.cli.common import params_from_args
    from microslip.cli.main import build_parser

    args = build_parser().parse_args(argv)
    params, _ = params_from_args(args, fallback_amplitude=1.0)
    for name in (a for a in argv if a.endswith(".csv")):
        kilo, frac = re.fullmatch(r"loop_(\d+)k(\d*)N\.csv", name).groups()
        amplitude = float(f"{kilo}.{frac or 0}") * 1e3
        loop = masing_loop(first_loading(args.model, params, amplitude, 400, ModelOptions()))
        np.savetxt(directory / name, np.column_stack([loop.force, loop.displacement]),
                   delimiter=",", header="force_N,displacement_mm", comments="")


def test_the_documents_show_commands():
    assert len(COMMANDS) >= 15
    names = {line.split()[1] for _, line in COMMANDS}
    assert {"loop", "planar", "fe", "sweep", "fit", "joint"} <= names


def _slow(line: str) -> bool:
    """Examples that run CalculiX, the FE solver in a sweep or on a planar path, a structure
    of its own mesh, or the whole reproduction: seconds to minutes each (``pytest -m "not
    slow"`` leaves them out)."""
    argv = _shrink(shlex.split(line, comments=True)[1:])
    solver = argv[argv.index("--solver") + 1] if "--solver" in argv[:-1] else None
    structure = argv[0] in ("modal", "frf", "reduce") and "--mesh" in argv
    return (argv[0] in ("validate", "reproduce") or "calculix" in argv or solver == "fe"
            or structure)


@pytest.mark.parametrize(("doc", "line"), [
    pytest.param(d, c, marks=pytest.mark.slow if _slow(c) else ()) for d, c in RUN
], ids=[f"{d}:{c[:60]}" for d, c in RUN])
def test_documented_command_runs(doc, line, tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    argv = _shrink(shlex.split(line, comments=True)[1:])
    cases = _toml_files(doc)  # case files the document shows in full
    if any("examples/" in a for a in argv) or any("examples/" in cases.get(a, "")
                                                   for a in argv):
        shutil.copytree(ROOT / "examples", tmp_path / "examples")  # the example meshes
    for name in {a for a in argv if a in cases}:
        (tmp_path / name).write_text(cases[name], encoding="utf-8")
    if "--structure" in argv or any("[structure]" in cases.get(a, "") for a in argv):
        # the document's python blocks write the structure file
        for code in _python_blocks(doc):
            exec(compile(code, f"{doc} python block", "exec"), {})
    if argv[0] == "fit":
        _measured_loops(tmp_path, argv)
    for toml in {a for a in argv if a.endswith(".toml")} - {"new"}:
        if not (argv[:2] == ["case", "new"] or (tmp_path / toml).exists()):
            assert main(["case", "new", toml]) == 0  # the template the docs start from
            capsys.readouterr()
    code = main(argv)
    out, err = capsys.readouterr()
    assert code == 0, f"{doc}: `{line}` exited {code}: {err.strip()[-400:]}"
    assert "Traceback" not in err
    assert out.strip() or any(tmp_path.iterdir()), "the example printed and wrote nothing"


#: The "From Python" example of docs/ownmesh.md at a small size: fewer ROM modes, one
#: amplitude, one force and one harmonic (the options are the document's).
OWNMESH_SHRINK = (("rom_modes=60", "rom_modes=12"), ("amplitudes=5", "amplitudes=1"),
                  ("[1.0, 3.0]", "[1.0]"), ("harmonics=3", "harmonics=1"))


@pytest.mark.slow
def test_ownmesh_python_example_runs(tmp_path, monkeypatch, capsys):
    """docs/ownmesh.md's Python example on examples/cantilever.inp, shrunk: it runs, and the
    mode it prints is the command line's (stuck 1714.79 Hz, in-plane bending)."""
    (code,) = [b for b in _python_blocks("ownmesh.md") if "StructureCase" in b]
    for old, new in OWNMESH_SHRINK:
        assert old in code
        code = code.replace(old, new)
    monkeypatch.chdir(tmp_path)
    shutil.copytree(ROOT / "examples", tmp_path / "examples")
    exec(compile(code, "ownmesh.md python block", "exec"), {})
    out = capsys.readouterr().out
    assert "mode 2: bending in the contact plane, stuck 1714.79 Hz" in out
    assert "(response_set)" in out and "F 1 N: peak" in out


#: The part of the "From Python" example: its first statements up to the structure's
#: preparation; the rest is the same for any part.
OWNMESH_PART = re.compile(r"^mesh = ms\.read_mesh.*?(?=^s = ms\.prepare_structure)", re.M | re.S)
#: A new user's part in its place (issue 34 item 7): the steel plate on a washer of
#: tests/data/meshes/plate.msh, its in-plane mode, a force (20 N) whose peak the friction
#: softens below the default range (its damping ratio None: the example crashed with a
#: TypeError on it).
PLATE_PART = """mesh = ms.read_mesh("tests/data/meshes/plate.msh")
clamp = ms.MeshClamp("contact", "washer", normal_force=8000.0, modulus=210000.0,
                     poisson_ratio=0.3, friction=0.5, stick_slope=1e4)
case = ms.StructureCase(mesh, clamp, density=7850.0, mode=2, response_set="response",
                        rom_modes=20)
forces = [1.0, 20.0]
"""


@pytest.mark.slow
def test_ownmesh_python_example_runs_on_another_part(monkeypatch, capsys):
    """The same example, its part replaced by the plate: every statement after the part runs
    on it as written, the level without a peak is said, not a TypeError."""
    (code,) = [b for b in _python_blocks("ownmesh.md") if "StructureCase" in b]
    assert len(OWNMESH_PART.findall(code)) == 1
    code = OWNMESH_PART.sub(PLATE_PART, code)
    monkeypatch.chdir(ROOT)
    exec(compile(code, "ownmesh.md python block on the plate", "exec"), {})
    out = capsys.readouterr().out
    assert "mode 2: bending in the contact plane" in out
    assert "contact: 63 nodes" in out and "washer 101.8 mm^2" in out
    assert "F 1 N: peak" in out and "zeta" in out
    # the 20 N level softens the plate's mode below or into the range: either way the
    # example says what it found (before: a TypeError on a level with no peak)
    assert "F 20 N: no peak in" in out or "F 20 N: peak" in out


@pytest.mark.slow
def test_ownmesh_assembly_example_runs(tmp_path, monkeypatch, capsys):
    """docs/ownmesh.md's assembly example (the bolted lap with a shank, 150 N lateral: past
    the shank-free lap's friction torque) runs and settles."""
    (code,) = [b for b in _python_blocks("ownmesh.md") if "ms.Assembly" in b]
    monkeypatch.chdir(tmp_path)
    shutil.copytree(ROOT / "examples", tmp_path / "examples")
    exec(compile(code, "ownmesh.md assembly block", "exec"), {})
    out = capsys.readouterr().out
    assert "W = " in out and "settled: True" in out
