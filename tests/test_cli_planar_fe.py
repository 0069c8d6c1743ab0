"""``microslip planar --solver fe``: coupled 2-D friction against its two uni-axial runs."""

from __future__ import annotations

import json

import pytest

from microslip.cli.main import main

ARGS = ["planar", "--solver", "fe", "--tip-amplitude", "150", "--centre-amplitude", "150",
        "--phase", "90", "--mesh", "tiny", "--cycles", "3", "--increments-per-cycle", "32"]


@pytest.fixture(scope="module")
def result() -> dict:
    import contextlib
    import io

    buf = io.StringIO()
    with contextlib.redirect_stdout(buf):
        code = main([*ARGS, "--json"])
    assert code == 0
    return json.loads(buf.getvalue())


def test_json_reports_coupled_decoupled_and_ratio(result):
    w, wd = result["dissipated_energy_Nmm"], result["decoupled_dissipated_energy_Nmm"]
    assert w > 0 and wd > 0
    # the CLI reports the library's coupling ratio (tests/test_fe_builtin_coupling.py: the same
    # case, recorded value; Newton's 1e-9 tolerance makes it reproducible to ~1e-8)
    assert result["coupling_ratio"] == pytest.approx(1.0332162671175356, rel=1e-7)
    assert wd == pytest.approx(result["tip_only_dissipated_energy_Nmm"]
                               + result["centre_only_dissipated_energy_Nmm"], rel=1e-12)
    # the coupled work splits into the work of each component of the load
    assert result["tip_work_Nmm"] + result["centre_work_Nmm"] == pytest.approx(w, rel=1e-9)
    # at 90 degrees each component does positive work over the cycle
    assert 0.0 < result["tip_share"] < 1.0 and 0.0 < result["centre_share"] < 1.0
    assert result["phase_deg"] == 90.0 and result["converged"] is True


def _without_timing(obj):
    if isinstance(obj, dict):
        return {k: _without_timing(v) for k, v in obj.items() if k != "wall_s"}
    return obj


def test_rerun_is_identical(result, capsys):
    assert main([*ARGS, "--json"]) == 0
    again = json.loads(capsys.readouterr().out)
    assert _without_timing(again) == _without_timing(result)
    assert again["dissipated_energy_Nmm"] == result["dissipated_energy_Nmm"]


def test_summary_has_units(capsys):
    assert main(ARGS) == 0
    out = capsys.readouterr().out
    assert "N·mm" in out and "coupling ratio" in out and "DOF" in out


@pytest.mark.parametrize(("extra", "needle"), [
    (["--mesh", "nope"], "unknown mesh"),
    (["--cycles", "0"], "--cycles must be"),
    (["--tip-amplitude", "500"], "macroslip"),
])
def test_bad_input_one_line(capsys, extra, needle):
    args = list(ARGS)
    for i in range(0, len(extra), 2):
        if extra[i] in args:
            args[args.index(extra[i]) + 1] = extra[i + 1]
        else:
            args += extra[i:i + 2]
    assert main(args) != 0
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and needle in err
