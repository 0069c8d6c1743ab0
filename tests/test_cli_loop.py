"""``microslip loop`` through main([...]): output, units, errors, and fuzzed argument lists."""

from __future__ import annotations

import json
import math

import pytest
from conftest import run
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from microslip import closedform as cf
from microslip import preset
from microslip.cli.main import main


def test_json_has_the_documented_keys(capsys):
    code, out, err = run(capsys, "loop", "--model", "tip", "--json", "--increments", "200")
    assert code == 0 and err == ""
    data = json.loads(out)
    for key in ("peak_displacement_mm", "dissipated_energy_Nmm", "strain_energy_Nmm",
                "loss_factor", "slip_length_mm"):
        assert isinstance(data[key], float) and data[key] > 0
    assert len(data["loop"]["force_N"]) == len(data["loop"]["displacement_mm"]) == 401
    assert data["amplitude_N"] == 267.0


def test_no_corrections_secant_gives_4_over_3pi(capsys):
    code, out, _ = run(capsys, "loop", "--model", "centre", "--no-corrections", "--json",
                       "--strain-energy", "secant", "--increments", "2000")
    data = json.loads(out)
    assert code == 0
    # trapezoidal loop of the parabola: eta = 4/(3 pi) (1 - 1/n^2) to rounding
    assert data["loss_factor"] == pytest.approx(4 / (3 * math.pi) * (1 - 1 / 2000**2),
                                                rel=2e-14)
    p = preset("table1")
    assert data["peak_displacement_mm"] == pytest.approx(
        cf.centre_displacement(267.0, p.axial_stiffness, p.friction_per_length), rel=1e-12)


def test_explicit_parameters_without_preset(capsys):
    args = ["loop", "--model", "tip", "--preset", "table1", "--length", "254", "--width", "25.4",
            "--thickness", "3.18", "--modulus", "68947", "--poisson-ratio", "0.3",
            "--friction", "0.8", "--normal-force", "445", "--amplitude", "267", "--json"]
    code, out, _ = run(capsys, *args)
    code2, out2, _ = run(capsys, "loop", "--model", "tip", "--json")
    assert code == code2 == 0
    assert json.loads(out)["dissipated_energy_Nmm"] == json.loads(out2)["dissipated_energy_Nmm"]


def test_summary_states_units(capsys):
    code, out, _ = run(capsys, "loop", "--model", "centre")
    assert code == 0
    for unit_line in ("N  (macroslip", "mm", "N·mm", "(dimensionless)"):
        assert unit_line in out
    assert "tension" in out and "compression" in out


def test_plot_is_written(capsys, tmp_path):
    path = tmp_path / "loop.png"
    code, _, _ = run(capsys, "loop", "--model", "tip", "--plot", str(path))
    assert code == 0
    assert path.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


@pytest.mark.parametrize(
    ("argv", "needle"),
    [
        (["--friction", "-0.2"], "friction must be > 0"),
        (["--modulus", "nan"], "modulus must be finite"),
        (["--increments", "0"], "increments must be a whole number"),
        (["--preset", "table9"], "invalid choice: 'table9'"),
        (["--amplitude", "356"], "macroslip"),
        (["--amplitude", "1e9"], "macroslip"),
        (["--poisson-ratio", "0.5"], "poisson_ratio must be in [0, 0.5)"),
    ],
)
def test_bad_input_gives_one_line_and_nonzero_exit(capsys, argv, needle):
    code, out, err = run(capsys, "loop", "--model", "tip", *argv)
    assert code != 0 and out == ""
    assert err.count("\n") == 1 and needle in err


def test_unknown_model(capsys):
    code, _, err = run(capsys, "loop", "--model", "edge")
    assert code == 2 and err.count("\n") == 1 and "tip" in err and "centre" in err


def test_plot_not_half_written_on_error(capsys, tmp_path):
    path = tmp_path / "loop.png"
    code, _, _ = run(capsys, "loop", "--model", "tip", "--amplitude", "400", "--plot", str(path))
    assert code == 1 and not path.exists() and list(tmp_path.iterdir()) == []


FLAGS = ["--model", "--preset", "--amplitude", "--increments", "--length", "--width",
         "--thickness", "--modulus", "--poisson-ratio", "--friction", "--normal-force",
         "--stick-slope", "--pressure-law", "--no-shear-lag",
         "--no-corrections", "--strain-energy", "--json", "--poisson", "--centre-reading",
         "--paper-literal", "--no-length-update", "--bogus"]
VALUES = ["tip", "centre", "table1", "table2-tip", "table2-centre", "0", "-1", "1e400", "nan",
          "inf", "-inf", "3", "0.3", "267", "abc", "", "secant", "stored", "branch", "paper",
          "paper-literal", "1e-300", "17.5", "99999999", "1e4", "parabolic", "power:2:3",
          "table:missing.csv"]


@pytest.mark.slow
@settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.too_slow,
                                                                  HealthCheck.function_scoped_fixture])
@given(st.lists(st.sampled_from(FLAGS) | st.sampled_from(VALUES), max_size=8))
def test_random_arguments_never_raise(capsys, tail):
    argv = ["loop", *tail]
    if "--increments" not in tail:
        argv += ["--increments", "20"]
    code = main(argv)
    out, err = capsys.readouterr()
    assert isinstance(code, int)
    if code != 0:  # one error line, after any warnings about the inputs (e.g. their units)
        lines = err.splitlines()
        assert out == "" and lines and lines[-1].startswith("error: ")
        assert all(line.startswith("warning: ") for line in lines[:-1])
