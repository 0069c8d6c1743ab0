"""Every W_d says which part of the clamp it belongs to, the same way in every command.

``clamp_portion`` in the JSON (and the words on the text W_d line): the paper's tip model is
one symmetric half of the clamp (``loop``/``fe --model tip``), the centre model, the work of a
planar load and the coupled FE study are the whole clamp (docs/interpretation.md §8).
"""

from __future__ import annotations

import json
import re

import pytest
from conftest import STEEL

from microslip.cli.main import main

FE = ["--mesh", "tiny", "--substeps", "20"]


def _json(capsys, *argv: str) -> dict:
    assert main(list(argv)) == 0
    return json.loads(capsys.readouterr().out)


def test_every_output_says_which_part_of_the_clamp(tmp_path, capsys):
    path = tmp_path / "steel.toml"
    path.write_text(STEEL)
    loop = _json(capsys, "loop", "--case", str(path), "--json")
    centre = _json(capsys, "loop", "--case", str(path), "--model", "centre", "--json")
    planar = _json(capsys, "planar", "--case", str(path), "--json")
    fe = _json(capsys, "fe", "--case", str(path), *FE, "--json")
    assert loop["clamp_portion"] == fe["clamp_portion"] == "half"
    assert centre["clamp_portion"] == "whole"
    assert planar["clamp_portion"] == "whole" and planar["tip"]["clamp_portion"] == "half"
    assert planar["centre"]["clamp_portion"] == "whole"
    assert planar["paper_clamp_portion"] == "mixed"
    for argv, words in ((["loop"], "one symmetric half of the clamp"),
                        (["loop", "--model", "centre"], "the whole clamp"),
                        (["fe", *FE], "one symmetric half of the clamp")):
        assert main([*argv, "--case", str(path)]) == 0
        line = next(x for x in capsys.readouterr().out.splitlines() if "W_d" in x)
        assert line.endswith(f"N·mm  ({words})"), line
    assert main(["planar", "--case", str(path)]) == 0
    text = capsys.readouterr().out
    assert re.search(r"tip model .* one symmetric half of the clamp", text)
    assert re.search(r"work of the load .* the whole clamp", text)


def test_the_coupled_fe_planar_study_is_the_whole_clamp(capsys):
    argv = ["planar", "--solver", "fe", "--tip-amplitude", "100", "--centre-amplitude", "100",
            "--mesh", "tiny", "--cycles", "2", "--increments-per-cycle", "32"]
    out = _json(capsys, *argv, "--json")
    assert out["clamp_portion"] == "whole"
    main(argv)
    line = next(x for x in capsys.readouterr().out.splitlines() if "coupled  " in x)
    assert line.endswith("N·mm  (the whole clamp)"), line


def test_the_numbers_do_not_change_with_the_label(tmp_path, capsys):
    """planar's tip half at 900 N on the steel clamp is twice loop's tip at 900 N (its zone is
    half as wide), and its work is the whole clamp: the label adds no factor."""
    path = tmp_path / "steel.toml"
    path.write_text(STEEL)
    loop = _json(capsys, "loop", "--case", str(path), "--json")
    planar = _json(capsys, "planar", "--case", str(path), "--json")
    assert loop["dissipated_energy_Nmm"] == pytest.approx(0.138772, rel=1e-5)
    assert planar["tip"]["dissipated_energy_Nmm"] == pytest.approx(0.27759, rel=1e-5)
    assert planar["dissipated_energy_Nmm"] == pytest.approx(0.555181, rel=1e-5)
