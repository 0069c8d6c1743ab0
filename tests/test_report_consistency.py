"""``microslip report`` computes what ``loop``, ``fe`` and ``planar`` compute on the same case.

The report's numbers at the case amplitude (``report --json``: ``one_d``, ``fe``, ``planar``)
are those of the three commands run with ``--case`` on the same file, to the last bit: they
run one code path (:mod:`microslip.case.run`).
"""

from __future__ import annotations

import contextlib
import io
import json
from pathlib import Path

import pytest
from conftest import STEEL

from microslip.case.run import COMMAND_DEFAULTS
from microslip.cli.main import build_parser, main

FE = ["--mesh", "tiny", "--substeps", "20"]

#: Keys the command line adds around the computed object (the case file, unit warnings),
#: and the solver's wall time.
ANNOTATIONS = {"case_file", "amplitude_rule", "warnings", "wall_s", "files"}


def _json(capsys, *argv: str) -> tuple[int, dict]:
    code = main(list(argv))
    out = capsys.readouterr().out
    return code, (json.loads(out) if out.strip() else {})


def _same(command: dict, report: dict) -> None:
    """Every key of the report's object equals the command's (annotations aside)."""
    keys = set(report) - ANNOTATIONS
    assert keys and keys <= set(command)
    for key in sorted(keys):
        assert command[key] == report[key], key


@pytest.fixture(scope="module", params=["steel", "template"])
def case(request, tmp_path_factory) -> tuple[str, list[str]]:
    """(case file, the --model the commands need)."""
    d = tmp_path_factory.mktemp(request.param)
    path = d / "case.toml"
    if request.param == "steel":
        path.write_text(STEEL)
        model: list[str] = []
    else:
        assert main(["case", "new", str(path)]) == 0
        model = ["--model", "tip"]  # the template leaves load.model to its default, tip
    return str(path), model


@pytest.fixture(scope="module")
def report(case) -> dict:
    path, _ = case
    buf = io.StringIO()
    with contextlib.redirect_stdout(buf):
        assert main(["report", "--case", path, "--json", "--no-progress", *FE]) == 0
    return json.loads(buf.getvalue())


def test_one_d_is_loop_case(case, report, capsys):
    path, model = case
    code, loop = _json(capsys, "loop", "--case", path, *model, "--json")
    assert code == 0
    _same(loop, report["one_d"])
    assert report["one_d"]["dissipated_energy_Nmm"] == loop["dissipated_energy_Nmm"]
    assert report["one_d"]["loss_factor"] == loop["loss_factor"]


def test_fe_is_fe_case_on_the_same_mesh(case, report, capsys):
    path, model = case
    code, fe = _json(capsys, "fe", "--case", path, *model, *FE, "--json")
    assert code == 0
    _same(fe, report["fe"])
    assert report["fe"]["dissipated_energy_Nmm"] == fe["dissipated_energy_Nmm"]
    assert report["fe"]["loss_factor"] == fe["loss_factor"]


def test_planar_is_planar_case(case, report, capsys):
    path, _ = case
    code, planar = _json(capsys, "planar", "--case", path, "--json")
    err = capsys.readouterr().err
    if report["planar"] is None:  # the case gives no planar load, or one that cannot run
        assert code != 0 or not planar
        if report["planar_error"] is not None:
            assert report["planar_error"] in " ".join(err.split())
        return
    assert code == 0
    _same(planar, report["planar"])
    assert report["planar"]["dissipated_energy_Nmm"] == planar["dissipated_energy_Nmm"]


def test_the_steel_report_uses_the_case_s_contact_and_clamp(tmp_path, capsys):
    path = tmp_path / "steel.toml"
    path.write_text(STEEL)
    code, rep = _json(capsys, "report", "--case", str(path), "--json", "--no-progress",
                      "--no-fe")
    assert code == 0
    one = rep["one_d"]
    assert one["contact"]["stick_slope_N_per_mm3"] == 1e4
    # the shear layer's W_d (issue 21: 0.139 N·mm), not the rigid foundation's 0.429
    assert one["dissipated_energy_Nmm"] == pytest.approx(0.138772, rel=1e-5)
    assert rep["fe"] is None and rep["fe_curve"] == []
    # the planar section is the case's own clamp (tip zone w / 2), not Table 2's
    assert rep["planar"]["tip_params"]["width"] == 10.0
    assert rep["planar"]["centre_params"]["length"] == 40.0


@pytest.mark.parametrize("argv", [["loop", "--model", "tip"], ["planar", "--ratio", "1"],
                                  ["fe", "--model", "tip"]])
def test_the_report_s_defaults_are_the_commands(argv):
    """The options the report does not set are those the commands default to."""
    args = vars(build_parser().parse_args(argv))
    defaults = {k: v for k, v in COMMAND_DEFAULTS[argv[0]].items() if k != "ratio"}
    assert set(defaults) <= set(args)
    assert {k: args[k] for k in defaults} == defaults


def test_report_needs_out_or_json(tmp_path, capsys):
    path = tmp_path / "c.toml"
    path.write_text(STEEL)
    assert main(["report", "--case", str(path)]) == 2
    assert "give --out FILE.html, --json or both" in capsys.readouterr().err


@pytest.mark.slow
def test_report_json_and_page_together(tmp_path, capsys):
    path = tmp_path / "c.toml"
    path.write_text(STEEL)
    page = tmp_path / "r.html"
    code, rep = _json(capsys, "report", "--case", str(path), "--out", str(page), "--json",
                      "--no-progress", "--no-fe")
    assert code == 0 and Path(rep["page"]) == page
    text = page.read_text(encoding="utf-8")
    assert f'<td class="num">{rep["one_d"]["dissipated_energy_Nmm"]:.6g}</td>' in text
    assert f'<td class="num">{rep["planar"]["dissipated_energy_Nmm"]:.6g}</td>' in text

