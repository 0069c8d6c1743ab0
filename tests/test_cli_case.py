"""``--case FILE.toml`` on every command and ``microslip case new/check`` through main([...])."""

from __future__ import annotations

import csv
import json

import pytest
from conftest import run

from microslip import preset
from microslip.case import template

TITANIUM_TOML = """\
name = "titanium clamp"
[geometry]
length = 30
width = 12
thickness = 8
[material]
modulus = 114000
poisson_ratio = 0.34
[contact]
friction = 0.5
[clamping]
normal_force = 12000
"""

TITANIUM = {"length": 30.0, "width": 12.0, "thickness": 8.0, "modulus": 114000.0,
            "poisson_ratio": 0.34, "friction": 0.5, "normal_force": 12000.0}


def one_line_error(code: int, out: str, err: str, *words: str) -> None:
    assert code == 1 and out == ""
    assert err.startswith("error: ") and err.count("\n") == 1 and "Traceback" not in err
    for word in words:
        assert word in err


@pytest.fixture
def ti(tmp_path):
    path = tmp_path / "ti.toml"
    path.write_text(TITANIUM_TOML)
    return path


def write(tmp_path, text: str, name: str = "c.toml"):
    path = tmp_path / name
    path.write_text(text)
    return path


def test_case_new_writes_the_template_and_refuses_to_overwrite(capsys, tmp_path):
    path = tmp_path / "new.toml"
    code, out, err = run(capsys, "case", "new", path)
    assert code == 0 and err == "" and str(path) in out
    assert path.read_text() == template()
    path.write_text("# mine\n")
    one_line_error(*run(capsys, "case", "new", path), str(path), "--force")
    assert path.read_text() == "# mine\n"
    assert run(capsys, "case", "new", path, "--force")[0] == 0
    assert path.read_text() == template()


def test_case_new_under_a_file_is_one_line(capsys, tmp_path):
    afile = write(tmp_path, "x", "afile")
    one_line_error(*run(capsys, "case", "new", afile / "c.toml"), "cannot write")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["afile"]


def test_case_check_prints_the_resolved_case_with_units(capsys, ti):
    code, out, err = run(capsys, "case", "check", ti)
    assert code == 0 and err == ""
    assert "geometry.length                30 mm" in out
    assert "material.modulus               114000 MPa" in out
    assert "resolved amplitude F0          3000 N" in out
    data = json.loads(run(capsys, "case", "check", ti, "--json")[1])
    assert data["params"] == TITANIUM and data["amplitude_N"] == 3000.0


def test_titanium_case_drives_loop_fe_and_sweep_with_identical_inputs(capsys, ti, tmp_path):
    code, out, err = run(capsys, "loop", "--case", ti, "--model", "tip", "--json",
                         "--increments", "200")
    loop = json.loads(out)
    # a 30 x 12 x 8 mm block is squat: the 1-D model says it cannot be trusted here
    assert code == 0 and err.splitlines() == [f"warning: {w}" for w in loop["warnings"]]
    assert any("squat" in w for w in loop["warnings"])
    code, out, err = run(capsys, "fe", "--case", ti, "--model", "tip", "--mesh", "tiny",
                         "--substeps", "20", "--json")
    assert code == 0, err
    fe = json.loads(out)
    table = tmp_path / "sweep.csv"
    code, out, err = run(capsys, "sweep", "--case", ti, "--model", "tip", "--out", table,
                         "--increments", "200", "--no-progress", "--seed", "1")
    assert code == 0, err
    (row,) = csv.DictReader(table.open())
    assert loop["params"] == fe["params"] == TITANIUM
    assert loop["amplitude_N"] == fe["amplitude_N"] == float(row["amplitude_N"]) == 3000.0
    assert {k: float(row[c]) for k, c in (("length", "length_mm"), ("modulus", "modulus_MPa"),
                                          ("friction", "friction"),
                                          ("normal_force", "normal_force_N"))} == {
        k: TITANIUM[k] for k in ("length", "modulus", "friction", "normal_force")}
    assert loop["case_file"] == fe["case_file"] == str(ti)
    assert out.startswith(f"case file {ti} (titanium clamp)\n")


def test_case_equals_the_same_options(capsys, ti):
    flags = [x for k, v in TITANIUM.items() for x in (f"--{k.replace('_', '-')}", str(v))]
    by_case = json.loads(run(capsys, "loop", "--case", ti, "--model", "centre", "--json",
                             "--increments", "100")[1])
    by_flags = json.loads(run(capsys, "loop", *flags, "--amplitude", "3000", "--model",
                              "centre", "--json", "--increments", "100")[1])
    assert by_case.pop("case_file") == str(ti) and "case_file" not in by_flags
    assert by_case.pop("amplitude_rule") == ("F0 = 0.5 x the slip limit mu F_N = 0.5 x 0.5 x "
                                             "12000 N = 3000 N (load.amplitude_fraction)")
    assert by_case == by_flags


def test_command_line_options_win_over_the_case(capsys, tmp_path):
    path = write(tmp_path, TITANIUM_TOML + '[load]\nmodel = "centre"\n')
    data = json.loads(run(capsys, "loop", "--case", path, "--friction", "0.4", "--json",
                          "--increments", "100")[1])
    assert data["model"] == "centre"
    assert data["params"] == TITANIUM | {"friction": 0.4}
    assert data["amplitude_N"] == 0.5 * 0.4 * 12000.0  # the default follows the override
    data = json.loads(run(capsys, "loop", "--case", path, "--model", "tip", "--amplitude",
                          "1000", "--json", "--increments", "100")[1])
    assert data["model"] == "tip" and data["amplitude_N"] == 1000.0


def test_case_amplitude_and_fraction(capsys, tmp_path):
    path = write(tmp_path, TITANIUM_TOML + "[load]\namplitude_fraction = 0.25\n")
    data = json.loads(run(capsys, "loop", "--case", path, "--model", "tip", "--json",
                          "--increments", "100")[1])
    assert data["amplitude_N"] == 1500.0
    path = write(tmp_path, '[load]\nmodel = "tip"\n', "load_only.toml")
    data = json.loads(run(capsys, "loop", "--case", path, "--json", "--increments", "100")[1])
    assert data["params"] == preset("table1").as_dict()
    assert data["amplitude_N"] == 0.5 * 0.8 * 445.0  # not the preset's 267 N


def test_sweep_amplitude_range_overrides_the_case_amplitude(capsys, ti, tmp_path):
    table = tmp_path / "s.csv"
    code, _, err = run(capsys, "sweep", "--case", ti, "--model", "tip", "--amplitude-range",
                         "1000", "2000", "--cases", "2", "--out", table, "--increments", "100",
                         "--no-progress")
    assert code == 0, err
    assert [float(r["amplitude_N"]) for r in csv.DictReader(table.open())] == [1000.0, 2000.0]


def test_planar_case_equals_the_same_options(capsys, tmp_path):
    path = write(tmp_path, "[load.planar]\ntip_amplitude = 4000\ncentre_amplitude = 6000\n"
                 "phase_deg = 90\n")
    by_case = json.loads(run(capsys, "planar", "--case", path, "--json",
                             "--increments", "200")[1])
    by_flags = json.loads(run(capsys, "planar", "--tip-amplitude", "4000",
                              "--centre-amplitude", "6000", "--phase", "90", "--json",
                              "--increments", "200")[1])
    assert by_case.pop("case_file") == str(path)
    assert by_case == by_flags


def test_planar_takes_the_clamp_of_the_case(capsys, ti):
    data = json.loads(run(capsys, "planar", "--case", ti, "--tip-amplitude", "1000",
                          "--centre-amplitude", "2000", "--json", "--increments", "100")[1])
    assert data["centre_params"] == TITANIUM
    assert data["tip_params"] == TITANIUM | {"width": 6.0}  # one symmetric half of the width
    by_flags = json.loads(run(capsys, "planar", *(x for k, v in TITANIUM.items() for x in (
        f"--{k.replace('_', '-')}", str(v))), "--tip-amplitude", "1000", "--centre-amplitude",
        "2000", "--json", "--increments", "100")[1])
    assert data.pop("case_file") == str(ti) and data == by_flags


def test_validate_takes_the_clamp_and_amplitude_of_the_case(capsys, ti, tmp_path, monkeypatch):
    import microslip.validate as validate

    seen = {}

    def fake(out, meshes, models, **kwargs):
        seen.update(kwargs)
        raise validate.ParameterError("stop here")

    monkeypatch.setattr(validate, "run_validation", fake)
    code, _, err = run(capsys, "validate", "--case", ti, "--out", tmp_path / "v")
    assert code == 1 and err == "error: stop here\n"
    assert seen["params"].as_dict() == TITANIUM and seen["amplitude"] == 3000.0


def test_stick_slope_goes_to_loop_and_fe_alike(capsys, tmp_path):
    path = write(tmp_path, TITANIUM_TOML + "stick_slope = 2e5\n")  # lands in [clamping]
    one_line_error(*run(capsys, "loop", "--case", path, "--model", "tip"),
                   "clamping.stick_slope", "contact.stick_slope")
    path = write(tmp_path, TITANIUM_TOML.replace("[contact]\n", "[contact]\nstick_slope = 2e5\n"))
    code, out, err = run(capsys, "loop", "--case", path, "--model", "tip", "--json",
                         "--increments", "200")
    assert code == 0, err
    assert json.loads(out)["contact"]["stick_slope_N_per_mm3"] == 2e5
    by_flag = json.loads(run(capsys, "loop", "--case", ti_path(tmp_path), "--model", "tip",
                             "--json", "--increments", "200", "--stick-slope", "2e5")[1])
    assert by_flag["dissipated_energy_Nmm"] == json.loads(out)["dissipated_energy_Nmm"]
    code, out, err = run(capsys, "fe", "--case", path, "--model", "tip", "--mesh", "tiny",
                         "--substeps", "20", "--json")
    assert code == 0, err
    assert json.loads(out)["options"]["stick_slope"] == 2e5


def ti_path(tmp_path):
    return write(tmp_path, TITANIUM_TOML, "ti2.toml")


def test_preset_on_the_command_line_conflicts_with_the_case_clamp(capsys, ti):
    one_line_error(*run(capsys, "loop", "--case", ti, "--model", "tip", "--preset", "table1"),
                   "--preset", "conflicts", str(ti))


@pytest.mark.parametrize("text, words", [
    ("[geometry]\nlenght = 30\n", ["geometry.lenght", "did you mean geometry.length"]),
    ("[geometry\nlength = 30\n", ["not valid TOML"]),
    ("[load]\nmodel = 'planar'\n", ["load.model", "tip, centre"]),
    ("[clamping]\npressure = 'wavy'\n", ["clamping.pressure", "parabolic"]),
])
def test_bad_case_files_are_one_line_exit_1(capsys, tmp_path, text, words):
    path = write(tmp_path, text)
    one_line_error(*run(capsys, "loop", "--case", path, "--model", "tip"), str(path), *words)


def test_missing_case_file_is_one_line(capsys, tmp_path):
    one_line_error(*run(capsys, "fe", "--case", tmp_path / "none.toml", "--model", "tip"),
                   "cannot read case file")


def test_impossible_units_are_one_line_errors_from_case_and_options(capsys, tmp_path):
    """A modulus in pascals cannot be meant (above any solid's): an error naming the key or
    the flag and the likely unit, never a result (issue 34, item 1)."""
    path = write(tmp_path, TITANIUM_TOML.replace("modulus = 114000", "modulus = 114e9"))
    one_line_error(*run(capsys, "loop", "--case", path, "--model", "tip", "--json",
                        "--increments", "100"),
                   "material.modulus 1.14e+11 MPa is above 1e+09 MPa", "pascals given as MPa?")
    one_line_error(*run(capsys, "loop", "--model", "tip", "--modulus", "6.9e10",
                        "--increments", "100"), "--modulus 6.9e+10 MPa", "pascals")
    code, _, err = run(capsys, "loop", "--model", "tip", "--modulus", "1e8", "--increments",
                       "100")
    assert code == 0 and "pascals given as MPa?" in err  # a rigid part may be meant: warns


def test_implausible_units_warn_and_still_run(capsys, tmp_path):
    """A borderline value (a length in metres of a bar that could be that small) warns, on
    one line, and the command runs."""
    code, out, err = run(capsys, "loop", "--model", "tip", "--length", "0.254",
                         "--increments", "100")
    assert code == 0 and "given as" not in err
    code, out, err = run(capsys, "loop", "--model", "tip", "--length", "0.0254",
                         "--increments", "100")
    assert code == 0 and ("warning: length 0.0254 mm is below 0.05 mm: metres given as mm?"
                          in err.splitlines())
    code, out, err = run(capsys, "loop", "--model", "tip", "--length", "0.0254",
                         "--increments", "100", "--json")
    assert code == 0 and sorted(err.splitlines()) == sorted(f"warning: {w}" for w
                                                           in json.loads(out)["warnings"])


def test_no_case_no_extra_keys(capsys):
    data = json.loads(run(capsys, "loop", "--model", "tip", "--json", "--increments", "100")[1])
    assert "case_file" not in data and data["warnings"] == []  # Table 1: within range


def test_case_pressure_law_equals_the_option(capsys, tmp_path):
    path = write(tmp_path, TITANIUM_TOML.replace("[contact]\n", "[contact]\nstick_slope = 1e5\n")
                 .replace("[clamping]\n", "[clamping]\npressure = 'parabolic'\n"))
    by_case = json.loads(run(capsys, "loop", "--case", path, "--model", "tip", "--json",
                             "--increments", "200")[1])
    plain = write(tmp_path, TITANIUM_TOML, "plain.toml")
    by_flags = json.loads(run(capsys, "loop", "--case", plain, "--model", "tip", "--json",
                              "--increments", "200", "--stick-slope", "1e5",
                              "--pressure-law", "parabolic")[1])
    assert by_case["contact"]["pressure_law"].startswith("power(n=2")
    assert by_case["dissipated_energy_Nmm"] == by_flags["dissipated_energy_Nmm"]


def test_the_case_default_amplitude_is_stated_as_a_fraction_of_the_slip_limit(capsys,
                                                                              tmp_path):
    path = tmp_path / "c.toml"
    path.write_text('preset = "table1"\n[contact]\nfriction = 0.5\n[clamping]\n'
                    "normal_force = 12000\n[load]\namplitude_fraction = 0.25\n")
    code, out, err = run(capsys, "loop", "--case", path, "--model", "tip", "--increments",
                         "20")
    assert code == 0, err
    lines = out.splitlines()
    assert lines[0] == f"case file {path}"
    assert lines[1] == ("  amplitude F0 = 0.25 x the slip limit mu F_N = 0.25 x 0.5 x 12000 N "
                        "= 1500 N (load.amplitude_fraction)")
    assert "amplitude F0                   1500 N" in out
